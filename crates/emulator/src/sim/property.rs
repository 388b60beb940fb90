//! CoppeliaSim 4.10's rule for property names, which its signals follow: a signal is the
//! scene property `signal.ILEGACY.<name>` (integer) or `signal.SLEGACY.<name>` (string), and
//! a name that is not a valid property name is not stored, without any error
//! (`../shared/spec/real-coppeliasim-4.10.md` "Signals are scene properties now").

/// Whether CoppeliaSim 4.10 stores a property (so a signal) named `name`: every character an
/// ASCII letter or digit, `_` or `.` (coppeliaSimLib@coppeliasim-v4.10.0-rev0
/// `sourceCode/interfaces/simInternal.cpp:653-665` `isPropertyNameValid`, called by the
/// property setters the signal setters go through, `simInternal-old.cpp:8860-8879`; its
/// `std::isalnum` is the C locale's, ASCII only). The empty name passes, as there.
pub fn is_property_name(name: &str) -> bool {
    name.chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spec_table_holds() {
        // ../shared/spec/real-coppeliasim-4.10.md, the table of names
        for kept in ["vrep_maze.lease", "a.b.c", "ab", "vrepmaze", ""] {
            assert!(is_property_name(kept), "{kept}");
        }
        for dropped in ["vrep-maze.lease", "a-b", "a b", "é", "a/b", "a:b"] {
            assert!(!is_property_name(dropped), "{dropped}");
        }
    }
}
