//! Every export ending and `--format` name appears where users read them: `export --help`,
//! the manual's `export` sections and Python's `Layout.export` docstring. The lists come
//! from `Format::ALL` and the ROS map's endings, so a new format missed in one place fails
//! here.

use std::path::Path;

use clap::{CommandFactory, ValueEnum};
use vrep_maze::cli::Cli;
use vrep_maze::export::{Format, Target, ros_map};

/// Every ending `export` takes: each format's, then the ROS map's.
fn endings() -> Vec<&'static str> {
    Format::ALL
        .iter()
        .flat_map(|f| f.file_endings())
        .chain(&ros_map::FILE_ENDINGS)
        .copied()
        .collect()
}

/// `text` from the line that starts with `from` to the next that starts with `to`.
fn section<'a>(text: &'a str, from: &str, to: &str) -> &'a str {
    let start = text.find(from).unwrap_or_else(|| panic!("no {from:?}"));
    let end = text[start..].find(to).map_or(text.len(), |e| start + e);
    &text[start..end]
}

#[test]
fn every_ending_and_format_name_appears_where_users_read_them() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cli = Cli::command();
    let help = cli
        .find_subcommand_mut("export")
        .expect("an export command")
        .render_long_help()
        .to_string();
    let manual = std::fs::read_to_string(root.join("docs/manual.md")).unwrap();
    let manual = section(&manual, "### `export`", "### `batch`");
    let python = std::fs::read_to_string(root.join("python/src/layout.rs")).unwrap();
    let python = section(&python, "/// Writes the maze for a simulator", "fn export(");
    for ending in endings() {
        for (place, text) in [
            ("export --help", help.as_str()),
            ("the manual", manual),
            ("Layout.export", python),
        ] {
            assert!(text.contains(ending), "{place} does not name {ending}");
        }
    }
    for format in Format::ALL {
        let name = format
            .to_possible_value()
            .expect("a value")
            .get_name()
            .to_string();
        assert!(
            manual.contains(&format!("`{name}`")),
            "the manual's --format list does not name {name}"
        );
    }
}

#[test]
fn every_ending_chooses_its_target() {
    for format in Format::ALL {
        for ending in format.file_endings() {
            let path = format!("maze{ending}");
            assert_eq!(
                Target::from_path(Path::new(&path)),
                Some(Target::Format(format))
            );
        }
    }
    for ending in ros_map::FILE_ENDINGS {
        let path = format!("maze{}", ending.to_uppercase());
        assert_eq!(Target::from_path(Path::new(&path)), Some(Target::RosMap));
    }
    assert_eq!(Target::from_path(Path::new("maze.xml")), None);
}
