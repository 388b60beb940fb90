//! Reading and writing layout JSON, byte for byte deterministic.
//!
//! Output: keys in declaration order, floats rounded to the micrometre and printed in
//! their shortest form (never `0.30000000000000004`), the top two levels indented and
//! every deeper value (one segment, one options map) on a single line, so a layout diffs
//! line by line.

use std::fs::File;
use std::io::{self, BufReader, BufWriter, Read, Write};
use std::path::Path;

use serde::{Deserialize, Serialize, Serializer};
use serde_json::ser::Formatter;

use super::geometry::round_um;
use super::{FORMAT, Layout, VERSION};

/// Serializes an `f64` rounded to the micrometre.
pub fn micrometres<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_f64(round_um(*value))
}

/// Serializes an `[f64; 2]` rounded to the micrometre.
pub fn micrometres_pair<S: Serializer>(value: &[f64; 2], serializer: S) -> Result<S::Ok, S::Error> {
    value.map(round_um).serialize(serializer)
}

/// Writes `layout` as layout JSON (with a final newline).
pub fn write_layout<W: Write>(layout: &Layout, writer: W) -> io::Result<()> {
    let mut writer = BufWriter::new(writer);
    let mut serializer =
        serde_json::Serializer::with_formatter(&mut writer, ShallowPretty::default());
    layout
        .serialize(&mut serializer)
        .map_err(io::Error::other)?;
    writer.write_all(b"\n")?;
    writer.flush()
}

/// `layout` as a layout JSON string.
pub fn to_string(layout: &Layout) -> String {
    let mut bytes = Vec::new();
    write_layout(layout, &mut bytes).expect("writing to memory cannot fail");
    String::from_utf8(bytes).expect("serde_json writes UTF-8")
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

/// Just the fields that say what a file is, read before the rest.
#[derive(Deserialize)]
struct Header {
    format: Option<serde_json::Value>,
    version: Option<serde_json::Value>,
}

/// Reads and parses the layout at `path` (`-` reads standard input).
pub fn read_layout(path: &Path) -> Result<Layout, ReadError> {
    let name = path.display().to_string();
    let mut text = String::new();
    let result = if name == "-" {
        io::stdin().read_to_string(&mut text)
    } else {
        File::open(path).and_then(|f| BufReader::new(f).read_to_string(&mut text))
    };
    result.map_err(|source| ReadError::Io {
        path: name.clone(),
        source,
    })?;
    parse_layout(&text, &name)
}

/// Parses layout JSON; `name` is used in error messages.
pub fn parse_layout(text: &str, name: &str) -> Result<Layout, ReadError> {
    let syntax = |e: serde_json::Error| ReadError::Syntax {
        path: name.to_string(),
        line: e.line(),
        column: e.column(),
        message: strip_position(&e.to_string()),
    };
    let header: Header = serde_json::from_str(text).map_err(syntax)?;
    let format_error = |message: String| ReadError::Format {
        path: name.to_string(),
        message,
    };
    match header.format {
        Some(serde_json::Value::String(f)) if f == FORMAT => {}
        Some(other) => {
            return Err(format_error(format!(
                "format is {other}, not \"{FORMAT}\": not a vrep-maze layout"
            )));
        }
        None => {
            return Err(format_error(format!(
                "no \"format\": \"{FORMAT}\" field: not a vrep-maze layout"
            )));
        }
    }
    match header.version {
        Some(serde_json::Value::Number(v)) if v.as_u64() == Some(u64::from(VERSION)) => {}
        Some(v) => {
            return Err(format_error(format!(
                "layout version {v} is not supported (this vrep-maze reads version {VERSION})"
            )));
        }
        None => return Err(format_error("no \"version\" field".to_string())),
    }
    serde_json::from_str(text).map_err(syntax)
}

/// serde_json appends " at line L column C"; we print the position first instead.
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(at) => message[..at].to_string(),
        None => message.to_string(),
    }
}

/// A JSON formatter that indents the top two levels and writes deeper values inline.
#[derive(Debug, Default)]
struct ShallowPretty {
    depth: usize,
    has_value: Vec<bool>,
}

const PRETTY_DEPTH: usize = 2;

impl ShallowPretty {
    fn pretty(&self) -> bool {
        self.depth <= PRETTY_DEPTH
    }

    fn open<W: ?Sized + Write>(&mut self, writer: &mut W, bracket: &[u8]) -> io::Result<()> {
        self.depth += 1;
        self.has_value.push(false);
        writer.write_all(bracket)
    }

    fn close<W: ?Sized + Write>(&mut self, writer: &mut W, bracket: &[u8]) -> io::Result<()> {
        let had_value = self.has_value.pop().unwrap_or(false);
        if self.pretty() && had_value {
            self.newline(writer, self.depth - 1)?;
        }
        self.depth -= 1;
        writer.write_all(bracket)
    }

    fn item<W: ?Sized + Write>(&mut self, writer: &mut W, first: bool) -> io::Result<()> {
        if let Some(flag) = self.has_value.last_mut() {
            *flag = true;
        }
        if !first {
            writer.write_all(if self.pretty() { b"," } else { b", " })?;
        }
        if self.pretty() {
            self.newline(writer, self.depth)?;
        }
        Ok(())
    }

    fn newline<W: ?Sized + Write>(&self, writer: &mut W, depth: usize) -> io::Result<()> {
        writer.write_all(b"\n")?;
        for _ in 0..depth {
            writer.write_all(b"  ")?;
        }
        Ok(())
    }
}

impl Formatter for ShallowPretty {
    fn begin_array<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.open(writer, b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.close(writer, b"]")
    }

    fn begin_array_value<W: ?Sized + Write>(
        &mut self,
        writer: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.item(writer, first)
    }

    fn end_array_value<W: ?Sized + Write>(&mut self, _writer: &mut W) -> io::Result<()> {
        Ok(())
    }

    fn begin_object<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.open(writer, b"{")
    }

    fn end_object<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.close(writer, b"}")
    }

    fn begin_object_key<W: ?Sized + Write>(
        &mut self,
        writer: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.item(writer, first)
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        writer.write_all(b": ")
    }

    fn end_object_value<W: ?Sized + Write>(&mut self, _writer: &mut W) -> io::Result<()> {
        Ok(())
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
