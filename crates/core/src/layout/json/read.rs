//! Reading layout JSON as a stream: the file is parsed as it is read (never held as text),
//! and the segments go one by one to a [`SegmentSink`] instead of into a list, so a
//! multi-gigabyte layout is checked or rendered in memory proportional to its grid.
//!
//! [`scan`](super::scan) splits the document: the head (every field but `segments`, a
//! few megabytes at most) is read by serde; the segments, nearly all the bytes, are read
//! fast ([`segment`](super::segment)) or, in any other spelling, by serde. A layout's
//! fields may come in any order. When every other field comes before `segments` (as this
//! crate writes them), the sink is made from them before the first segment and the
//! segments stream through it; otherwise they are kept until the end of the document and
//! then replayed into the sink.

use std::fmt;
use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

use serde::de::{self, Deserializer, IgnoredAny, MapAccess, Visitor};

use super::ReadError;
use super::scan::{Element, MAX_FIELDS_BYTES, Position, ScanError, Source};
use super::sink::SegmentSink;
use crate::layout::limits::{MAX_SEGMENTS, MAX_SEGMENTS_PER_PASSAGE};
use crate::layout::{
    Endpoint, FORMAT, FloorSpec, GeneratorInfo, GridSpec, Layout, LineSpec, Pose, PostSpec, Style,
    VERSION, WallSpec,
};
use crate::maze::Metrics;

/// Reads the layout at `path` (`-` reads standard input), streaming its segments into the
/// sink that `sink_for` makes from the rest of the layout. Returns that rest (its
/// `segments` empty) and the sink.
pub fn read_layout_with<S: SegmentSink>(
    path: &Path,
    sink_for: impl FnOnce(&Layout) -> S,
) -> Result<(Layout, S), ReadError> {
    let name = path.display().to_string();
    if name == "-" {
        return read_from(io::stdin().lock(), &name, sink_for);
    }
    let file = File::open(path).map_err(|source| ReadError::Io {
        path: name.clone(),
        source,
    })?;
    read_from(file, &name, sink_for)
}

/// [`read_layout_with`] from any reader; `name` is used in error messages.
pub fn read_from<S: SegmentSink>(
    reader: impl Read,
    name: &str,
    sink_for: impl FnOnce(&Layout) -> S,
) -> Result<(Layout, S), ReadError> {
    let io_error = |source: io::Error| ReadError::Io {
        path: name.to_string(),
        source,
    };
    let scan_error = |e: ScanError| match e {
        ScanError::Io(source) => io_error(source),
        ScanError::Syntax(at, message) => syntax(name, at, message),
    };
    let mut source = Source::new(reader);
    let mut head = Vec::new();
    if !source.head(&mut head).map_err(scan_error)? {
        // No segment list to stream: serde reads (or refuses) the whole document.
        let fields = parse_fields(&head, name)?;
        return finish(fields, Vec::new(), name, sink_for);
    }
    // The head so far, closed, says whether the segments can stream.
    let mut probe = head.clone();
    probe.extend_from_slice(b"[]}");
    let early = parse_fields(&probe, name)?;
    if let Some(message) = early.refused {
        return Err(format_error(name, message));
    }
    // An empty list (a wall layout's) waits for the fields after it, which may be the
    // wall layout's own.
    let mut most = MAX_SEGMENTS;
    let mut segments = if early.complete() && !source.list_is_empty().map_err(scan_error)? {
        let layout = early.into_layout(name)?;
        most = most_segments(&layout.grid);
        Segments::Streaming(sink_for(&layout), Box::new(layout))
    } else {
        Segments::Kept(Vec::new(), sink_for)
    };
    let breaks = segments.read_list(&mut source, most).map_err(scan_error)?;
    let mut tail = Vec::new();
    source
        .rest(&mut tail, MAX_FIELDS_BYTES.saturating_sub(head.len()))
        .map_err(scan_error)?;
    if let Segments::Streaming(..) = &segments
        && tail.trim_ascii() == b"}"
    {
        let Segments::Streaming(sink, layout) = segments else {
            unreachable!("matched above")
        };
        return Ok((*layout, sink));
    }
    // Fields after the list (or junk): serde reads the document with the list left out;
    // the placeholder keeps line numbers true.
    head.push(b'[');
    head.resize(head.len() + breaks, b'\n');
    head.push(b']');
    head.extend_from_slice(&tail);
    let fields = parse_fields(&head, name)?;
    segments.finish_with(fields, name)
}

/// The most segments a layout of `grid` may hold: every passage drawn with the most
/// copies one may take, and never more than [`MAX_SEGMENTS`] (a bound on what is read).
fn most_segments(grid: &GridSpec) -> u64 {
    let passages = 2 * u64::from(grid.columns) * u64::from(grid.rows);
    passages
        .saturating_mul(MAX_SEGMENTS_PER_PASSAGE as u64)
        .min(MAX_SEGMENTS)
}

/// A wall layout's own fields (style, wall template, walls, post template, posts).
type WallFields<'a> = (
    Style,
    &'a Option<WallSpec>,
    &'a [Pose],
    &'a Option<PostSpec>,
    &'a [Pose],
);

/// The fields of `layout` that only a wall layout sets.
fn wall_fields(layout: &Layout) -> WallFields<'_> {
    (
        layout.style,
        &layout.wall,
        &layout.walls,
        &layout.post,
        &layout.posts,
    )
}

/// Where the segments go while the list is read.
enum Segments<S, F> {
    /// Into the sink, made from the fields read before the list.
    Streaming(S, Box<Layout>),
    /// Kept, for a sink made once the fields after the list are read.
    Kept(Vec<Pose>, F),
}

impl<S: SegmentSink, F: FnOnce(&Layout) -> S> Segments<S, F> {
    /// Reads the segment list of `source` into these, refusing more than `most`; how many
    /// line breaks the list held.
    fn read_list<R: Read>(
        &mut self,
        source: &mut Source<R>,
        most: u64,
    ) -> Result<usize, ScanError> {
        let mut index = 0;
        source.elements(|element, at| {
            if index as u64 >= most {
                return Err(ScanError::Syntax(
                    at,
                    format!("more than {most} segments: no layout of this grid holds more"),
                ));
            }
            let pose = match element {
                Element::Segment(pose) => pose,
                Element::Other(bytes) => parse_segment(bytes, at)?,
            };
            match self {
                Segments::Streaming(sink, _) => sink.segment(index, pose),
                Segments::Kept(kept, _) => kept.push(pose),
            }
            index += 1;
            Ok(())
        })
    }

    /// The layout and its sink once `fields` (the whole document but the list) are read:
    /// a streamed layout must not gain a wall layout's fields after its segments.
    fn finish_with(self, fields: Fields, name: &str) -> Result<(Layout, S), ReadError> {
        match self {
            Segments::Streaming(sink, layout) => {
                // The head was complete, so a known field after the list is a duplicate,
                // which serde refused above, or one of a wall layout's, which cannot come
                // with segments (the sink saw a line layout); an unknown one is refused here.
                let whole = fields.into_layout(name)?;
                if wall_fields(&whole) != wall_fields(&layout) {
                    return Err(format_error(
                        name,
                        "a wall layout's fields (`style`, `wall`, `walls`, `post`, `posts`) follow line segments: a layout draws lines or walls, not both".to_string(),
                    ));
                }
                Ok((*layout, sink))
            }
            Segments::Kept(kept, sink_for) => finish(fields, kept, name, sink_for),
        }
    }
}

/// The layout from its `fields`, and a sink fed `kept` then any segments serde read.
fn finish<S: SegmentSink>(
    mut fields: Fields,
    kept: Vec<Pose>,
    name: &str,
    sink_for: impl FnOnce(&Layout) -> S,
) -> Result<(Layout, S), ReadError> {
    if let Some(message) = fields.refused.take() {
        return Err(format_error(name, message));
    }
    let read_by_serde = fields.segments.take();
    let scanned = !kept.is_empty();
    let layout = fields.into_layout(name)?;
    if read_by_serde.is_none() && !scanned {
        return Err(format_error(name, "missing field `segments`".to_string()));
    }
    let mut sink = sink_for(&layout);
    for (index, pose) in kept
        .into_iter()
        .chain(read_by_serde.into_iter().flatten())
        .enumerate()
    {
        sink.segment(index, pose);
    }
    Ok((layout, sink))
}

/// One segment serde reads from `bytes` (found at `at`): any spelling, or its error.
fn parse_segment(bytes: &[u8], at: Position) -> Result<Pose, ScanError> {
    serde_json::from_slice(bytes).map_err(|e| {
        let column = if e.line() == 1 {
            at.column + e.column().saturating_sub(1)
        } else {
            e.column()
        };
        let position = Position {
            line: at.line + e.line().saturating_sub(1),
            column,
        };
        ScanError::Syntax(position, super::strip_position(&e.to_string()))
    })
}

/// A syntax error at a position; at the very start, the file is no JSON at all.
fn syntax(name: &str, at: Position, message: String) -> ReadError {
    let message = if (at.line, at.column) == (1, 1) {
        format!(
            "not a layout: expected JSON (`{{\"format\": \"{}\", ...}}`): {message}",
            super::super::FORMAT
        )
    } else {
        message
    };
    ReadError::Syntax {
        path: name.to_string(),
        line: at.line,
        column: at.column,
        message,
    }
}

/// Not a layout this build reads.
fn format_error(name: &str, message: String) -> ReadError {
    ReadError::Format {
        path: name.to_string(),
        message,
    }
}

/// The fields of the layout document in `bytes`, read by serde.
fn parse_fields(bytes: &[u8], name: &str) -> Result<Fields, ReadError> {
    let mut deserializer = serde_json::Deserializer::from_slice(bytes);
    deserializer
        .deserialize_map(FieldsVisitor)
        .and_then(|fields| deserializer.end().map(|()| fields))
        .map_err(|e| {
            let at = Position {
                line: e.line(),
                column: e.column(),
            };
            syntax(name, at, super::strip_position(&e.to_string()))
        })
}

/// What a field is to the reading of a layout's head.
enum Kind {
    /// `format` and `version`: checked first, and say whether the rest is read.
    Header,
    /// Needed for a layout: missing, it is the error.
    Required,
    /// A wall layout's own: absent in a line layout.
    Optional,
    /// The segment list: streamed when the scanner finds it, checked at the end.
    Segments,
}

/// Declares the layout's fields once, each with the type it is read as and its [`Kind`],
/// in [`Layout`]'s order (the order serde's derived code names them in errors): [`Fields`]
/// holds them, [`Fields::read`] reads them and [`FIELDS`] lists them.
macro_rules! layout_fields {
    ($($(#[$doc:meta])* $name:ident: $type:ty, $kind:ident;)*) => {
        /// Every field of a layout and its kind, in [`Layout`]'s order.
        const FIELDS: &[(&str, Kind)] = &[$((stringify!($name), Kind::$kind)),*];

        /// The fields read so far.
        #[derive(Default)]
        struct Fields {
            $($(#[$doc])* $name: Option<$type>,)*
            /// The first key that is no layout field.
            unknown: Option<String>,
            /// Why this is not a layout this build reads (format or version).
            refused: Option<String>,
        }

        impl Fields {
            /// Reads the value of `key` from `map` if `key` names a layout field (a second
            /// value for it is refused); `false` if it names none.
            fn read<'de, A: MapAccess<'de>>(
                &mut self,
                key: &str,
                map: &mut A,
            ) -> Result<bool, A::Error> {
                match key {
                    $(stringify!($name) => {
                        if self.$name.is_some() {
                            return Err(de::Error::duplicate_field(stringify!($name)));
                        }
                        self.$name = Some(map.next_value()?);
                    })*
                    _ => return Ok(false),
                }
                Ok(true)
            }

            /// `true` if the field named `name` has been read.
            fn has(&self, name: &str) -> bool {
                match name {
                    $(stringify!($name) => self.$name.is_some(),)*
                    _ => false,
                }
            }
        }
    };
}

layout_fields! {
    format: serde_json::Value, Header;
    version: serde_json::Value, Header;
    style: Style, Optional;
    generator: GeneratorInfo, Required;
    grid: GridSpec, Required;
    floor: FloorSpec, Required;
    line: LineSpec, Required;
    wall: WallSpec, Optional;
    post: PostSpec, Optional;
    start: Endpoint, Required;
    end: Endpoint, Required;
    metrics: Metrics, Required;
    passage_encoding: String, Required;
    passages: Vec<String>, Required;
    /// Segments serde read (the list the scanner leaves out reads as empty).
    segments: Vec<Pose>, Segments;
    walls: Vec<Pose>, Optional;
    posts: Vec<Pose>, Optional;
}

impl Fields {
    /// The first field a layout needs (the header's too) that has not been read.
    fn missing(&self) -> Option<&'static str> {
        FIELDS
            .iter()
            .find(|(name, kind)| matches!(kind, Kind::Header | Kind::Required) && !self.has(name))
            .map(|(name, _)| *name)
    }

    /// `true` once every field a layout needs has been read.
    fn complete(&self) -> bool {
        self.missing().is_none()
    }

    /// The layout without segments; a wrong format or version, an unknown field or a
    /// missing one is the error.
    fn into_layout(self, name: &str) -> Result<Layout, ReadError> {
        let refuse = |message: String| format_error(name, message);
        let format = check_header(self.format.as_ref(), self.version.as_ref()).map_err(refuse)?;
        if let Some(key) = self.unknown {
            let expected: Vec<String> = FIELDS.iter().map(|(f, _)| format!("`{f}`")).collect();
            return Err(refuse(format!(
                "unknown field `{key}`, expected one of {}",
                expected.join(", ")
            )));
        }
        if let Some(field) = self.missing() {
            return Err(refuse(format!("missing field `{field}`")));
        }
        let read = "read: nothing is missing";
        Ok(Layout {
            format,
            version: VERSION,
            generator: self.generator.expect(read),
            grid: self.grid.expect(read),
            floor: self.floor.expect(read),
            line: self.line.expect(read),
            start: self.start.expect(read),
            end: self.end.expect(read),
            metrics: self.metrics.expect(read),
            passage_encoding: self.passage_encoding.expect(read),
            passages: self.passages.expect(read),
            segments: Vec::new(),
            style: self.style.unwrap_or_default(),
            wall: self.wall,
            walls: self.walls.unwrap_or_default(),
            post: self.post,
            posts: self.posts.unwrap_or_default(),
        })
    }
}

/// What is wrong with the `format` and `version` read so far, once it is certain.
fn header_problem(fields: &Fields) -> Option<String> {
    match (&fields.format, &fields.version) {
        (None, _) => None,
        (Some(_), None) => check_header(fields.format.as_ref(), Some(&VERSION.into())).err(),
        (Some(_), Some(_)) => check_header(fields.format.as_ref(), fields.version.as_ref()).err(),
    }
}

/// The `format` and `version` fields say this is a layout this build reads; returns the
/// format string.
fn check_header(
    format: Option<&serde_json::Value>,
    version: Option<&serde_json::Value>,
) -> Result<String, String> {
    match format {
        Some(serde_json::Value::String(f)) if f == FORMAT => {}
        Some(other) => {
            return Err(format!(
                "format is {other}, not \"{FORMAT}\": not a vrep-maze layout"
            ));
        }
        None => {
            return Err(format!(
                "no \"format\": \"{FORMAT}\" field: not a vrep-maze layout"
            ));
        }
    }
    match version {
        Some(serde_json::Value::Number(v)) if v.as_u64() == Some(u64::from(VERSION)) => {
            Ok(FORMAT.to_string())
        }
        Some(v) => Err(format!(
            "layout version {v} is not supported (this vrep-maze reads version {VERSION})"
        )),
        None => Err("no \"version\" field".to_string()),
    }
}

/// Reads the layout object into [`Fields`].
struct FieldsVisitor;

impl<'de> Visitor<'de> for FieldsVisitor {
    type Value = Fields;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a vrep-maze layout object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Fields, A::Error> {
        let mut fields = Fields::default();
        while let Some(key) = map.next_key::<String>()? {
            if !fields.read(&key, &mut map)? {
                // Not a layout field: an error, unless the file is no layout at all,
                // which the format check says better.
                fields.unknown.get_or_insert(key);
                map.next_value::<IgnoredAny>()?;
            }
            // Refuse a file that is no layout (or a newer one) before reading more.
            if let Some(message) = header_problem(&fields) {
                while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
                fields.refused = Some(message);
                return Ok(fields);
            }
        }
        Ok(fields)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::json::to_string;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    fn layout() -> Layout {
        build_layout(&GenerateSpec::course(
            Grid::new(4, 3).unwrap(),
            Algorithm::Kruskal,
            5,
        ))
        .unwrap()
    }

    /// A reader that hands out `step` bytes at a time: every chunk boundary is tried.
    struct Trickle<'a> {
        bytes: &'a [u8],
        step: usize,
    }

    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            let n = self.step.min(buf.len()).min(self.bytes.len());
            buf[..n].copy_from_slice(&self.bytes[..n]);
            self.bytes = &self.bytes[n..];
            Ok(n)
        }
    }

    /// A layout read by [`read`]: the head, the segments with their indices, and whether
    /// the sink was made from a complete head.
    type Outcome = (Layout, Vec<(usize, Pose)>, bool);

    /// Reads `text`, recording whether the sink was made before any segment arrived.
    fn read(text: &str, step: usize) -> Result<Outcome, ReadError> {
        struct Record(Vec<(usize, Pose)>, bool);
        impl SegmentSink for Record {
            fn segment(&mut self, index: usize, pose: Pose) {
                self.0.push((index, pose));
            }
        }
        let reader = Trickle {
            bytes: text.as_bytes(),
            step,
        };
        let (head, record) = read_from(reader, "t.json", |head| {
            Record(Vec::new(), !head.passages.is_empty())
        })?;
        Ok((head, record.0, record.1))
    }

    #[test]
    fn segments_stream_in_order_at_every_chunk_boundary() {
        let layout = layout();
        let text = to_string(&layout);
        for step in [1, 7, 64, 1 << 20] {
            let (head, segments, made_from_head) = read(&text, step).unwrap();
            assert!(made_from_head);
            assert_eq!(head, layout.without_segments());
            let poses: Vec<Pose> = segments.iter().map(|&(_, p)| p).collect();
            assert_eq!(poses, layout.segments, "step {step}");
            assert!(
                segments
                    .iter()
                    .enumerate()
                    .all(|(i, &(index, _))| i == index)
            );
        }
    }

    #[test]
    fn fields_after_the_segments_and_other_spellings_are_read_too() {
        let layout = layout();
        let value: serde_json::Value = serde_json::from_str(&to_string(&layout)).unwrap();
        let compact = serde_json::to_string(&value).unwrap();
        let mut object = value.as_object().unwrap().clone();
        let segments = object.remove("segments").unwrap();
        let mut reordered = serde_json::Map::new();
        reordered.insert("segments".into(), segments);
        reordered.extend(object);
        let pretty = serde_json::to_string_pretty(&reordered).unwrap();
        for text in [pretty, compact] {
            let (head, segments, _) = read(&text, 5).unwrap();
            assert_eq!(head, layout.without_segments());
            let poses: Vec<Pose> = segments.iter().map(|&(_, p)| p).collect();
            assert_eq!(poses, layout.segments);
        }
    }

    /// [`layout`] in walls, with posts of 0.05 m if `posts`.
    fn wall_layout(posts: bool) -> Layout {
        use crate::layout::walls::{WallOptions, into_walls, length_between_posts};
        let mut layout = layout();
        let grid = Grid::new(4, 3).unwrap();
        let maze = crate::layout::passages::decode(grid, &layout.passages).unwrap();
        let options = match posts {
            false => WallOptions::default(),
            true => WallOptions {
                length: length_between_posts(1.0, 0.05),
                posts: Some(0.05),
                ..WallOptions::default()
            },
        };
        into_walls(&mut layout, &maze, &options, true).unwrap();
        layout
    }

    #[test]
    fn a_wall_layouts_fields_are_read_wherever_they_stand() {
        let layout = wall_layout(true);
        let text = to_string(&layout);
        assert!(
            text.find("\n  \"walls\":") > text.find("\n  \"segments\":"),
            "written after"
        );
        assert!(
            text.find("\n  \"posts\":") > text.find("\n  \"walls\":"),
            "written after"
        );
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        let mut object = value.as_object().unwrap().clone();
        let style = object.remove("style").unwrap();
        let post = object.remove("post").unwrap();
        let mut moved = object.clone();
        // now after the segments too
        moved.insert("style".into(), style);
        moved.insert("post".into(), post);
        let moved = serde_json::to_string_pretty(&moved).unwrap();
        for text in [text, moved] {
            for step in [1, 64, 1 << 20] {
                let (head, segments, _) = read(&text, step).unwrap();
                assert_eq!(head, layout, "step {step}");
                assert!(segments.is_empty());
            }
        }
    }

    #[test]
    fn wall_fields_after_line_segments_are_refused() {
        let walls = serde_json::to_string(&wall_layout(false).walls).unwrap();
        let text = to_string(&layout());
        let mixed = text.replacen("  ]\n}", &format!("  ],\n  \"walls\": {walls}\n}}"), 1);
        let err = read(&mixed, 9).unwrap_err().to_string();
        assert!(err.contains("lines or walls, not both"), "{err}");
        let posts = serde_json::to_string(&wall_layout(true).posts).unwrap();
        for extra in [
            format!("\"posts\": {posts}"),
            "\"post\": {\"size\": 0.05}".to_string(),
        ] {
            let mixed = text.replacen("  ]\n}", &format!("  ],\n  {extra}\n}}"), 1);
            let err = read(&mixed, 9).unwrap_err().to_string();
            assert!(
                err.contains("(`style`, `wall`, `walls`, `post`, `posts`)"),
                "{err}"
            );
        }
        // the same layout with the fields before the segments reads, for validate to refuse
        let early = text.replacen(
            "\"segments\"",
            &format!("\"walls\": {walls},\n  \"segments\""),
            1,
        );
        let (head, segments, _) = read(&early, 9).unwrap();
        assert_eq!(head.walls.len(), wall_layout(false).walls.len());
        assert!(!segments.is_empty());
    }

    #[test]
    fn broken_segments_are_refused_with_their_line_and_column() {
        let text = to_string(&layout());
        let line_of = |needle: &str| text[..text.find(needle).unwrap()].lines().count();
        let broken = text.replacen("\"yaw\": 0.0}", "\"yaw\": \"east\"}", 1);
        let err = read(&broken, 9).unwrap_err().to_string();
        let line = line_of("\"yaw\": 0.0}");
        assert!(err.starts_with(&format!("t.json:{line}:")), "{err}");
        assert!(err.contains("invalid type: string \"east\""), "{err}");
        let err = read(&text.replacen("0.0},", "0.0}", 1), 9)
            .unwrap_err()
            .to_string();
        assert!(err.contains("expected `,` or `]`"), "{err}");
        let err = read(&text.replacen("0.0}\n  ]", "0.0},\n  ]", 1), 9)
            .unwrap_err()
            .to_string();
        assert!(err.contains("trailing comma"), "{err}");
        let err = read(&text[..text.len() - 20], 9).unwrap_err().to_string();
        assert!(err.contains("EOF"), "{err}");
        let extra = text.replacen("  ]\n}", "  ],\n  \"colour\": 1\n}", 1);
        let err = read(&extra, 9).unwrap_err().to_string();
        assert!(err.contains("unknown field `colour`"), "{err}");
        let twice = text.replacen("  ]\n}", "  ],\n  \"segments\": []\n}", 1);
        let err = read(&twice, 9).unwrap_err().to_string();
        assert!(err.contains("duplicate field `segments`"), "{err}");
    }

    #[test]
    fn the_heads_errors_name_the_fields_in_the_layouts_order() {
        let text = to_string(&layout());
        let error = |text: &str| read(text, 9).unwrap_err().to_string();
        let unknown = text.replacen("{\n", "{\n  \"colour\": 1,\n", 1);
        assert_eq!(
            error(&unknown),
            "t.json: unknown field `colour`, expected one of `format`, `version`, `style`, \
             `generator`, `grid`, `floor`, `line`, `wall`, `post`, `start`, `end`, `metrics`, \
             `passage_encoding`, `passages`, `segments`, `walls`, `posts`"
        );
        // the list is the one serde's derived code for `Layout` gives
        let serde_says = serde_json::from_str::<Layout>(&unknown).unwrap_err();
        assert!(error(&unknown).ends_with(&super::super::strip_position(&serde_says.to_string())));
        let mut object: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(&text).unwrap();
        object.remove("passages");
        object.remove("metrics");
        let without = serde_json::to_string(&object).unwrap();
        assert_eq!(error(&without), "t.json: missing field `metrics`");
        object.remove("format");
        let without = serde_json::to_string(&object).unwrap();
        assert_eq!(
            error(&without),
            "t.json: no \"format\": \"vrep-maze/layout\" field: not a vrep-maze layout"
        );
        let twice = text.replacen("{\n", "{\n  \"version\": 1,\n", 1);
        assert_eq!(error(&twice), "t.json:4:11: duplicate field `version`");
        let null = text.replacen("\"format\": \"vrep-maze/layout\"", "\"format\": null", 1);
        assert_eq!(
            error(&null),
            "t.json: format is null, not \"vrep-maze/layout\": not a vrep-maze layout"
        );
        let null_wall = text.replacen("{\n", "{\n  \"wall\": null,\n", 1);
        assert!(
            error(&null_wall).contains("invalid type: null"),
            "{}",
            error(&null_wall)
        );
    }
}
