//! Reading and writing layout JSON, byte for byte deterministic, at disk speed.
//!
//! Output: keys in declaration order, floats rounded to the micrometre and printed in
//! their shortest form (never `0.30000000000000004`), the top two levels indented and
//! every deeper value (one segment, one options map) on a single line, so a layout diffs
//! line by line. Segments stream in both directions ([`write_layout_parts`],
//! [`read_layout_with`]), so no step needs a big layout whole in memory.

mod parallel;
mod pretty;
mod read;
mod scan;
mod segment;
mod sink;
mod write;

use std::io;
use std::path::Path;

use serde::{Serialize, Serializer};

use super::Layout;
use super::geometry::round_um;

pub use read::{read_from, read_layout_with};
pub use sink::{Background, SegmentSink};
pub use write::{write_layout, write_layout_parts};

/// Serializes an `f64` rounded to the micrometre.
pub fn micrometres<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_f64(round_um(*value))
}

/// Serializes an `[f64; 2]` rounded to the micrometre.
pub fn micrometres_pair<S: Serializer>(value: &[f64; 2], serializer: S) -> Result<S::Ok, S::Error> {
    value.map(round_um).serialize(serializer)
}

/// `layout` as a layout JSON string.
pub fn to_string(layout: &Layout) -> String {
    let mut bytes = Vec::new();
    write_layout(layout, &mut bytes).expect("writing to memory cannot fail");
    String::from_utf8(bytes).expect("layout JSON is UTF-8")
}

/// Why a layout file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What the OS said.
        source: io::Error,
    },
    /// Not JSON, or JSON of the wrong shape: serde's message carries line and column.
    #[error("{path}:{line}:{column}: {message}")]
    Syntax {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong there.
        message: String,
    },
    /// Not a vrep-maze layout, or a version this build cannot read.
    #[error("{path}: {message}")]
    Format {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}

/// Reads and parses the layout at `path` (`-` reads standard input), segments and all.
pub fn read_layout(path: &Path) -> Result<Layout, ReadError> {
    let (mut layout, segments) = read_layout_with(path, |_| Vec::new())?;
    layout.segments = segments;
    Ok(layout)
}

/// Parses layout JSON; `name` is used in error messages.
pub fn parse_layout(text: &str, name: &str) -> Result<Layout, ReadError> {
    let (mut layout, segments) = read_from(text.as_bytes(), name, |_| Vec::new())?;
    layout.segments = segments;
    Ok(layout)
}

/// serde_json appends " at line L column C"; we print the position first instead.
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(at) => message[..at].to_string(),
        None => message.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    fn small() -> Layout {
        build_layout(&GenerateSpec::course(
            Grid::new(2, 2).unwrap(),
            Algorithm::Dfs,
            3,
        ))
        .unwrap()
    }

    #[test]
    fn output_is_shallow_pretty_and_round_trips() {
        let layout = small();
        let text = to_string(&layout);
        assert!(text.starts_with("{\n  \"format\": \"vrep-maze/layout\",\n  \"version\": 1,\n"));
        assert!(text.contains("\n    {\"x\": "), "{text}");
        assert!(
            text.contains("\"origin\": [0.0, 0.0]") || text.contains("\"origin\": [\n"),
            "{text}"
        );
        assert!(text.ends_with("]\n}\n"));
        assert_eq!(parse_layout(&text, "t").unwrap(), layout);
        assert_eq!(to_string(&parse_layout(&text, "t").unwrap()), text);
    }

    #[test]
    fn errors_name_file_line_and_column() {
        let text = to_string(&small());
        let truncated = &text[..text.len() / 2];
        let err = parse_layout(truncated, "m.json").unwrap_err().to_string();
        assert!(err.starts_with("m.json:"), "{err}");
        assert!(err.contains("EOF"), "{err}");
        let err = parse_layout(
            "{\"format\": \"vrep-maze/layout\", \"version\": 2}",
            "m.json",
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("layout version 2 is not supported"), "{err}");
        let err = parse_layout("{\"a\": 1}", "m.json")
            .unwrap_err()
            .to_string();
        assert!(err.contains("not a vrep-maze layout"), "{err}");
        let err = parse_layout("{\"a\": 1,}", "m.json")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("m.json:1:9:"), "{err}");
        let wrong_type = text.replacen("\"columns\": 2", "\"columns\": -2", 1);
        let err = parse_layout(&wrong_type, "m.json").unwrap_err().to_string();
        assert!(err.contains("invalid value: integer `-2`"), "{err}");
    }
}
