//! The record of the copies this tool pasted, kept in the scene's string signal
//! [`signals::COPIES`](super::signals::COPIES) so that a later run over the ZeroMQ API (one call per object, no
//! batching) knows a child of the maze dummy for a template's copy without reading its alias.
//!
//! The record maps handles to the alias of the template they copy, written compactly as
//! `Line:12-40,45;Post:41-44` (consecutive handles as ranges: a paste makes consecutive
//! handles). It only ever holds handles this tool pasted or identified as copies, so it can
//! say "ours" but never "the user's": a handle that is no longer in the scene, or an object
//! that is not of the template's type, is simply not taken from it (CoppeliaSim does not
//! reuse handles within a session; signals are not saved with a scene, so after a reload
//! the record is gone and copies are recognised by their aliases again). An alias holding
//! one of the record's separators (`;:,`) is left out of it: such copies are recognised by
//! their aliases. The record is a Rust string, so valid UTF-8 whatever the aliases are (4.10's
//! add-on never answers the read of a string signal that is not,
//! `../shared/spec/real-coppeliasim-4.10.md` "The remote APIs").

use std::collections::BTreeMap;

/// Characters the written record uses to separate aliases, handles and ranges.
const SEPARATORS: [char; 3] = [';', ':', ','];

/// Handles of pasted copies and the alias of the template each copies.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct CopyRecord(BTreeMap<i32, String>);

impl CopyRecord {
    /// Reads a record; anything malformed in it is left out (never an error: the record
    /// only saves reads).
    pub fn parse(text: &str) -> CopyRecord {
        let mut record = BTreeMap::new();
        for section in text.split(';') {
            let Some((alias, ranges)) = section.split_once(':') else {
                continue;
            };
            if alias.is_empty() {
                continue;
            }
            for range in ranges.split(',') {
                let (from, to) = range.split_once('-').unwrap_or((range, range));
                let (Ok(from), Ok(to)) = (from.parse::<i32>(), to.parse::<i32>()) else {
                    continue;
                };
                // a bounded range: a corrupt record cannot make us allocate without end
                if from < 0 || to < from || to - from > 1_000_000 {
                    continue;
                }
                for h in from..=to {
                    record.insert(h, alias.to_string());
                }
            }
        }
        CopyRecord(record)
    }

    /// The record as [`CopyRecord::parse`] reads it.
    pub fn format(&self) -> String {
        let mut by_alias: BTreeMap<&str, Vec<(i32, i32)>> = BTreeMap::new();
        for (&h, alias) in self.0.iter().filter(|(_, a)| !a.contains(SEPARATORS)) {
            let ranges = by_alias.entry(alias).or_default();
            match ranges.last_mut() {
                Some((_, to)) if *to + 1 == h => *to = h,
                _ => ranges.push((h, h)),
            }
        }
        by_alias
            .iter()
            .map(|(alias, ranges)| {
                let ranges: Vec<String> = ranges
                    .iter()
                    .map(|&(from, to)| {
                        if from == to {
                            from.to_string()
                        } else {
                            format!("{from}-{to}")
                        }
                    })
                    .collect();
                format!("{alias}:{}", ranges.join(","))
            })
            .collect::<Vec<_>>()
            .join(";")
    }

    /// The alias of the template `handle` copies, if recorded.
    pub fn get(&self, handle: i32) -> Option<&str> {
        self.0.get(&handle).map(String::as_str)
    }

    /// Records `handle` as a copy of the template with alias `alias`; `true` if that
    /// changed the record.
    pub fn insert(&mut self, handle: i32, alias: &str) -> bool {
        if self.get(handle) == Some(alias) {
            return false;
        }
        self.0.insert(handle, alias.to_string());
        true
    }

    /// Keeps only the handles `keep` accepts; `true` if any was dropped.
    pub fn retain(&mut self, mut keep: impl FnMut(i32) -> bool) -> bool {
        let before = self.0.len();
        self.0.retain(|h, _| keep(*h));
        self.0.len() != before
    }

    /// The record of both `self` and `other` (`self`'s alias where both hold a handle): how
    /// the record under the new name and an older version's are read together. Safe, as
    /// either only says "ours" of copies, and a handle no longer in the scene is never taken
    /// from it; a mixed history (a newer run, a clear, then an older version's run) leaves
    /// a stale record beside a true one.
    pub fn merged(mut self, other: CopyRecord) -> CopyRecord {
        for (h, alias) in other.0 {
            self.0.entry(h).or_insert(alias);
        }
        self
    }

    /// Number of handles recorded.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// `true` if nothing is recorded.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_round_trip_and_malformed_parts_are_left_out() {
        let mut r = CopyRecord::default();
        for h in [12, 13, 14, 20, 16] {
            assert!(r.insert(h, "Line"));
        }
        assert!(!r.insert(13, "Line"));
        r.insert(15, "Post");
        assert_eq!(r.format(), "Line:12-14,16,20;Post:15");
        assert_eq!(CopyRecord::parse(&r.format()), r);
        assert_eq!(r.get(16), Some("Line"));
        assert_eq!(r.get(17), None);
        let odd = CopyRecord::parse("Line:3-1,x,4;:5;Wall:7-9;junk;Post:-2,0-99999999");
        assert_eq!(odd.format(), "Line:4;Wall:7-9");
        assert!(CopyRecord::parse("").is_empty());
        let both = CopyRecord::parse("Line:1-2").merged(CopyRecord::parse("Wall:2-3"));
        assert_eq!(both.format(), "Line:1-2;Wall:3");
        // separators in an alias would change what the record says: such copies are left out
        let mut odd = r.clone();
        odd.insert(30, "a;b:c");
        odd.insert(31, "Lîne é");
        assert_eq!(odd.format(), "Line:12-14,16,20;Lîne é:31;Post:15");
        assert!(r.retain(|h| h != 20));
        assert!(!r.retain(|_| true));
        assert_eq!(r.len(), 5);
    }
}
