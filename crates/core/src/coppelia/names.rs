//! How CoppeliaSim names pasted copies, the one rule our drawing (which tells copies of a
//! template from other objects) and our emulator (which names the copies it pastes) share.
//!
//! CoppeliaSim 4.5.1 was observed to name the copies of `Line` `Line0`, `Line1`, ... and a
//! copy of `Line5` `Line6` ([`Naming::Plain`]: counting up from the original's number, or 0,
//! to the first free name); the 4.x core sources also have the `Line#0` form
//! ([`Naming::Hash`]). A number is written as Rust writes it: `Line07` is no copy's name.

/// How pasted copies are named.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Naming {
    /// `Line` -> `Line0`, `Line1` -> `Line2`.
    #[default]
    Plain,
    /// `Line` -> `Line#0`, `Line#0` -> `Line#1`.
    Hash,
}

/// `Line7` -> (`Line`, 7): a plain copy name (the digits must be how 7 is written).
pub fn split_plain(name: &str) -> Option<(&str, u64)> {
    let base = name.trim_end_matches(|c: char| c.is_ascii_digit());
    canonical(&name[base.len()..]).map(|n| (base, n))
}

/// `Line#7` -> (`Line`, 7): a hash copy name.
pub fn split_hash(name: &str) -> Option<(&str, u64)> {
    let (base, digits) = name.rsplit_once('#')?;
    canonical(digits).map(|n| (base, n))
}

/// What the copies of the object `name` are named after under `naming`: the base, the
/// separator before the number, and the first number to try (the original's number plus
/// one, or 0).
pub fn copy_parts(name: &str, naming: Naming) -> (&str, &'static str, u64) {
    match naming {
        Naming::Plain => {
            let base = name.trim_end_matches(|c: char| c.is_ascii_digit());
            let start = name[base.len()..]
                .parse::<u64>()
                .map(|n| n + 1)
                .unwrap_or(0);
            (base, "", start)
        }
        Naming::Hash => match name.rsplit_once('#') {
            Some((b, n)) if !n.is_empty() && n.bytes().all(|c| c.is_ascii_digit()) => {
                (b, "#", n.parse::<u64>().map(|n| n + 1).unwrap_or(0))
            }
            _ => (name, "#", 0),
        },
    }
}

/// True if `name` is a copy of the object named `original` under either naming: `Line0`,
/// `Line17` or `Line#0` of `Line`; `Line6` of `Line5`; `Seg#3` of `Seg#0`.
pub fn is_copy_of(name: &str, original: &str) -> bool {
    name != original
        && [Naming::Plain, Naming::Hash].into_iter().any(|naming| {
            let (base, sep, _) = copy_parts(original, naming);
            let split = if sep.is_empty() {
                split_plain(name)
            } else {
                split_hash(name)
            };
            split.is_some_and(|(b, _)| b == base)
        })
}

/// The number `digits` writes, if `format!("{n}")` writes it the same way.
fn canonical(digits: &str) -> Option<u64> {
    let n: u64 = digits.parse().ok()?;
    (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) && n.to_string() == digits)
        .then_some(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copy_names_split_only_as_they_are_written() {
        assert_eq!(split_plain("Line12"), Some(("Line", 12)));
        assert_eq!(split_plain("Line0"), Some(("Line", 0)));
        assert_eq!(split_plain("Line"), None);
        assert_eq!(split_plain("Line07"), None);
        assert_eq!(split_plain("7"), Some(("", 7)));
        assert_eq!(split_plain("L99999999999999999999999"), None);
        assert_eq!(split_hash("Line#3"), Some(("Line", 3)));
        assert_eq!(split_hash("A#b#0"), Some(("A#b", 0)));
        assert_eq!(split_hash("Line#"), None);
        assert_eq!(split_hash("Line3"), None);
    }

    #[test]
    fn copies_count_up_from_the_originals_number() {
        assert_eq!(copy_parts("Line", Naming::Plain), ("Line", "", 0));
        assert_eq!(copy_parts("Line5", Naming::Plain), ("Line", "", 6));
        assert_eq!(copy_parts("Line", Naming::Hash), ("Line", "#", 0));
        assert_eq!(copy_parts("Seg#0", Naming::Hash), ("Seg", "#", 1));
        assert_eq!(copy_parts("a#b", Naming::Hash), ("a#b", "#", 0));
    }

    #[test]
    fn a_copy_is_named_after_its_original_under_either_naming() {
        for (name, original) in [
            ("Line0", "Line"),
            ("Line17", "Line"),
            ("Line#0", "Line"),
            ("Line6", "Line5"),
            ("Line0", "Line5"),
            ("Seg#3", "Seg#0"),
        ] {
            assert!(is_copy_of(name, original), "{name} of {original}");
        }
        for (name, original) in [
            ("Line", "Line"),
            ("Line07", "Line"),
            ("Lines0", "Line"),
            ("Line#", "Line"),
            ("Start0", "Line"),
            ("LineA", "Line"),
        ] {
            assert!(!is_copy_of(name, original), "{name} of {original}");
        }
    }
}
