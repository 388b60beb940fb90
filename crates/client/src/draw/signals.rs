//! The scene signals this tool keeps, named in one place.
//!
//! CoppeliaSim 4.10 stores a signal as the scene property `signal.ILEGACY.<name>` (integer)
//! or `signal.SLEGACY.<name>` (string) and silently drops a name that is not a valid property
//! name: ASCII letters, digits, `_` and `.` only (coppeliaSimLib@coppeliasim-v4.10.0-rev0
//! `simInternal.cpp:653-665` `isPropertyNameValid`; `../shared/spec/real-coppeliasim-4.10.md`
//! "Signals are scene properties now"). Versions before this one named their signals
//! `vrep-maze.*`, which 4.10 drops; the names here are `vrep_maze.*`, valid on every version.
//! A scene drawn by an older version (on 4.5.1, which keeps any name) still has its records
//! under the old names: they are read when the new ones are absent (the copy record: merged
//! with the new one, `record::CopyRecord::merged`), and removed when the new ones are
//! written, so nothing stale survives.
//!
//! String signal values are Rust strings, so always valid UTF-8: 4.10's add-on never answers
//! the read of a string signal that is not (`../shared/spec/real-coppeliasim-4.10.md` "The
//! remote APIs").

/// One signal: the name written and read, and the name an older version used for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Signal {
    /// The name written (a valid property name).
    pub name: &'static str,
    /// The name versions before it used (read when `name` is absent, removed when it is
    /// written).
    pub old: &'static str,
}

/// Integer signal: the token of the run drawing into the scene ([`super::lease`]).
pub const LEASE: Signal = Signal {
    name: "vrep_maze.lease",
    old: "vrep-maze.lease",
};

/// String signal: the record of the copies this tool pasted ([`super::record`]).
pub const COPIES: Signal = Signal {
    name: "vrep_maze.copies",
    old: "vrep-maze.copies",
};

/// Integer signal: the user's idle rate while `apply` or `clear` runs with it raised.
pub const SAVED_IDLE_FPS: Signal = Signal {
    name: "vrep_maze.saved_idle_fps",
    old: "vrep-maze.saved_idle_fps",
};

/// Integer signals: where the line template stood before the first `apply` ([`super::home`]):
/// its handle, x, y, z (micrometres) and three Euler angles (microradians) in the floor frame.
pub const HOME: [Signal; 7] = [
    Signal {
        name: "vrep_maze.template_home.handle",
        old: "vrep-maze.template_home.handle",
    },
    Signal {
        name: "vrep_maze.template_home.x_um",
        old: "vrep-maze.template_home.x_um",
    },
    Signal {
        name: "vrep_maze.template_home.y_um",
        old: "vrep-maze.template_home.y_um",
    },
    Signal {
        name: "vrep_maze.template_home.z_um",
        old: "vrep-maze.template_home.z_um",
    },
    Signal {
        name: "vrep_maze.template_home.alpha_urad",
        old: "vrep-maze.template_home.alpha_urad",
    },
    Signal {
        name: "vrep_maze.template_home.beta_urad",
        old: "vrep-maze.template_home.beta_urad",
    },
    Signal {
        name: "vrep_maze.template_home.gamma_urad",
        old: "vrep-maze.template_home.gamma_urad",
    },
];

/// Integer signals: the floor's size before `apply --resize-floor` grew it
/// ([`super::floor`]): its handle, then its size along x and y, millimetres (up to
/// 2,000 km). New with this version, so without older names.
pub const FLOOR_SIZE: [&str; 3] = [
    "vrep_maze.floor_size.handle",
    "vrep_maze.floor_size.x_mm",
    "vrep_maze.floor_size.y_mm",
];

/// Integer signals: where the start marker stood before the first `apply`
/// ([`super::markers_home`]), as [`HOME`] keeps the line template's: its handle, x, y, z
/// (micrometres) and three Euler angles (microradians) in the floor frame. New with this
/// version, so without older names.
pub const START_HOME: [&str; 7] = [
    "vrep_maze.start_home.handle",
    "vrep_maze.start_home.x_um",
    "vrep_maze.start_home.y_um",
    "vrep_maze.start_home.z_um",
    "vrep_maze.start_home.alpha_urad",
    "vrep_maze.start_home.beta_urad",
    "vrep_maze.start_home.gamma_urad",
];

/// Integer signals: where the end marker stood before the first `apply`, as
/// [`START_HOME`].
pub const END_HOME: [&str; 7] = [
    "vrep_maze.end_home.handle",
    "vrep_maze.end_home.x_um",
    "vrep_maze.end_home.y_um",
    "vrep_maze.end_home.z_um",
    "vrep_maze.end_home.alpha_urad",
    "vrep_maze.end_home.beta_urad",
    "vrep_maze.end_home.gamma_urad",
];

/// The names to read for `signals`: every new name, then every old one.
pub fn names_to_read(signals: &[Signal]) -> Vec<&'static str> {
    let new = signals.iter().map(|s| s.name);
    new.chain(signals.iter().map(|s| s.old)).collect()
}

/// The value of one signal from its new and old names' values: the new one, else the old.
pub fn newest<T>(new: Option<T>, old: Option<T>) -> Option<T> {
    new.or(old)
}

/// The integer-signal writes that set (`Some`) or clear (`None`) each signal, then clear
/// every old name.
pub fn int_writes(signals: &[(Signal, Option<i32>)]) -> Vec<(&'static str, Option<i32>)> {
    let new = signals.iter().map(|(s, v)| (s.name, *v));
    new.chain(signals.iter().map(|(s, _)| (s.old, None)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CoppeliaSim 4.10's rule (coppeliaSimLib@coppeliasim-v4.10.0-rev0 `simInternal.cpp:653`).
    fn is_property_name(name: &str) -> bool {
        name.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.')
    }

    #[test]
    fn every_name_is_a_property_name_and_every_old_one_is_not() {
        let all: Vec<Signal> = [LEASE, COPIES, SAVED_IDLE_FPS]
            .into_iter()
            .chain(HOME)
            .collect();
        let mut names = std::collections::HashSet::new();
        for s in &all {
            assert!(is_property_name(s.name), "{}", s.name);
            assert!(!is_property_name(s.old), "{}", s.old);
            assert_eq!(s.old.replace('-', "_"), s.name);
            assert!(names.insert(s.name), "{} twice", s.name);
        }
        for name in FLOOR_SIZE.into_iter().chain(START_HOME).chain(END_HOME) {
            assert!(is_property_name(name), "{name}");
            assert!(names.insert(name), "{name} twice");
        }
    }

    #[test]
    fn new_names_are_read_first_and_old_ones_removed_on_write() {
        assert_eq!(
            names_to_read(&HOME[..2]),
            [HOME[0].name, HOME[1].name, HOME[0].old, HOME[1].old]
        );
        assert_eq!(newest(Some(1), Some(2)), Some(1));
        assert_eq!(newest(None, Some(2)), Some(2));
        assert_eq!(
            int_writes(&[(LEASE, Some(7)), (COPIES, None)]),
            [
                (LEASE.name, Some(7)),
                (COPIES.name, None),
                (LEASE.old, None),
                (COPIES.old, None)
            ]
        );
    }
}
