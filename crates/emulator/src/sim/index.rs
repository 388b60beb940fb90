//! The scene's lookup indexes, so that no scene operation scans every object: names to
//! handles, aliases to handles, parents to children, and, per base name, the numbers used by
//! copy names (`Line7` in plain naming, `Line#7` in hash naming) as runs, so that "the lowest
//! free `Line<N>` from N" is one ordered-map lookup. They are derived from the objects alone:
//! never serialized, rebuilt when a scene is read.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use vrep_maze_core::coppelia::names::{split_hash, split_plain};

use super::object::Object;

/// Used numbers as disjoint, non-adjacent inclusive runs `start -> end`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(super) struct Runs(BTreeMap<u64, u64>);

impl Runs {
    /// The run holding `n`, as (start, end).
    fn holding(&self, n: u64) -> Option<(u64, u64)> {
        self.0
            .range(..=n)
            .next_back()
            .filter(|(_, e)| **e >= n)
            .map(|(s, e)| (*s, *e))
    }

    /// Marks `n` used (merging with the runs either side).
    pub(super) fn insert(&mut self, n: u64) {
        if self.holding(n).is_some() {
            return;
        }
        let mut start = n;
        let mut end = n;
        if let Some(b) = n.checked_sub(1)
            && let Some((s, _)) = self.holding(b)
        {
            start = s;
        }
        if let Some(a) = n.checked_add(1)
            && let Some(e) = self.0.remove(&a)
        {
            end = e;
        }
        self.0.insert(start, end);
    }

    /// Marks `n` free (splitting its run).
    pub(super) fn remove(&mut self, n: u64) {
        let Some((s, e)) = self.holding(n) else {
            return;
        };
        self.0.remove(&s);
        if s < n {
            self.0.insert(s, n - 1);
        }
        if n < e {
            self.0.insert(n + 1, e);
        }
    }

    /// The lowest number at or above `from` that is not used.
    pub(super) fn first_free(&self, from: u64) -> u64 {
        match self.holding(from) {
            Some((_, e)) => e.saturating_add(1),
            None => from,
        }
    }

    fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// Lookups over a scene's objects (object names are unique in a scene).
#[derive(Debug, Clone, Default)]
pub(super) struct Index {
    by_name: HashMap<String, i32>,
    by_alias: HashMap<String, BTreeSet<i32>>,
    /// Children in handle order, per parent (`None`: the roots).
    children: HashMap<Option<i32>, BTreeSet<i32>>,
    /// Per base, the numbers of names `base<n>`.
    plain: HashMap<String, Runs>,
    /// Per base, the numbers of names `base#<n>`.
    hash: HashMap<String, Runs>,
}

impl Index {
    /// Indexes every object.
    pub(super) fn build<'a>(objects: impl Iterator<Item = &'a Object>) -> Index {
        let mut index = Index::default();
        for o in objects {
            index.insert(o);
        }
        index
    }

    /// Indexes a new object.
    pub(super) fn insert(&mut self, o: &Object) {
        self.add_name(&o.name, o.handle);
        self.by_alias
            .entry(o.alias.clone())
            .or_default()
            .insert(o.handle);
        self.children.entry(o.parent).or_default().insert(o.handle);
    }

    /// Forgets an object (as it was indexed).
    pub(super) fn remove(&mut self, o: &Object) {
        self.remove_name(&o.name, o.handle);
        if let Some(set) = self.by_alias.get_mut(&o.alias) {
            set.remove(&o.handle);
            if set.is_empty() {
                self.by_alias.remove(&o.alias);
            }
        }
        if let Some(set) = self.children.get_mut(&o.parent) {
            set.remove(&o.handle);
            if set.is_empty() {
                self.children.remove(&o.parent);
            }
        }
    }

    /// `handle` moves from parent `from` to parent `to`.
    pub(super) fn reparent(&mut self, handle: i32, from: Option<i32>, to: Option<i32>) {
        if let Some(set) = self.children.get_mut(&from) {
            set.remove(&handle);
            if set.is_empty() {
                self.children.remove(&from);
            }
        }
        self.children.entry(to).or_default().insert(handle);
    }

    fn add_name(&mut self, name: &str, handle: i32) {
        self.by_name.insert(name.to_string(), handle);
        if let Some((base, n)) = split_plain(name) {
            self.plain.entry(base.to_string()).or_default().insert(n);
        }
        if let Some((base, n)) = split_hash(name) {
            self.hash.entry(base.to_string()).or_default().insert(n);
        }
    }

    fn remove_name(&mut self, name: &str, handle: i32) {
        if self.by_name.get(name) != Some(&handle) {
            return;
        }
        self.by_name.remove(name);
        for (split, runs) in [
            (
                split_plain as fn(&str) -> Option<(&str, u64)>,
                &mut self.plain,
            ),
            (split_hash, &mut self.hash),
        ] {
            if let Some((base, n)) = split(name)
                && let Some(r) = runs.get_mut(base)
            {
                r.remove(n);
                if r.is_empty() {
                    runs.remove(base);
                }
            }
        }
    }

    /// The object named `name`.
    pub(super) fn named(&self, name: &str) -> Option<i32> {
        self.by_name.get(name).copied()
    }

    /// Objects with this alias, in handle order.
    pub(super) fn with_alias(&self, alias: &str) -> impl Iterator<Item = i32> + '_ {
        self.by_alias.get(alias).into_iter().flatten().copied()
    }

    /// Children of `parent` (`None`: the roots), in handle order.
    pub(super) fn children(&self, parent: Option<i32>) -> impl Iterator<Item = i32> + '_ {
        self.children.get(&parent).into_iter().flatten().copied()
    }

    /// How many children `parent` has (`None`: how many roots).
    pub(super) fn child_count(&self, parent: Option<i32>) -> usize {
        self.children.get(&parent).map_or(0, BTreeSet::len)
    }

    /// The lowest `n >= from` such that no object is named `base{sep}{n}` (`sep` is `""` or
    /// `"#"`; a plain `base` never ends in a digit).
    pub(super) fn first_free(&self, base: &str, sep: &str, from: u64) -> u64 {
        let runs = if sep == "#" { &self.hash } else { &self.plain };
        runs.get(base).map_or(from, |r| r.first_free(from))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_merge_split_and_find_the_first_gap() {
        let mut r = Runs::default();
        for n in [0, 1, 2, 4, 5, 3] {
            r.insert(n);
        }
        assert_eq!(r.0, BTreeMap::from([(0, 5)]));
        assert_eq!(
            (r.first_free(0), r.first_free(3), r.first_free(9)),
            (6, 6, 9)
        );
        r.remove(2);
        assert_eq!(r.0, BTreeMap::from([(0, 1), (3, 5)]));
        assert_eq!(
            (r.first_free(0), r.first_free(2), r.first_free(4)),
            (2, 2, 6)
        );
        r.remove(0);
        r.remove(5);
        r.remove(7);
        assert_eq!(r.0, BTreeMap::from([(1, 1), (3, 4)]));
        r.insert(u64::MAX);
        assert_eq!(r.first_free(u64::MAX), u64::MAX);
    }
}
