//! Writing layout JSON. Everything but the segments goes through serde with the
//! [`ShallowPretty`] formatter; the segments, which are nearly all of a big layout's bytes,
//! are written straight from an iterator, with the same shortest-float routine serde_json
//! uses (`zmij`), so the bytes are exactly what serde would write and no segment list has
//! to exist in memory.

use std::io::{self, BufWriter, Write};

use serde::Serialize;

use super::pretty::ShallowPretty;
use crate::layout::geometry::round_um;
use crate::layout::{Layout, Pose};

/// Output buffer: big writes keep a multi-gigabyte layout at disk speed.
const BUFFER: usize = 1 << 20;

/// How the serialized head ends when `segments` is empty: the writer splices the segments in
/// before the `]`. `segments` is the last field of [`Layout`], so this is always the tail.
const EMPTY_SEGMENTS_TAIL: &[u8] = b"\"segments\": []\n}";

/// Writes `layout` as layout JSON (with a final newline).
pub fn write_layout<W: Write>(layout: &Layout, writer: W) -> io::Result<()> {
    write_layout_parts(layout, layout.segments.iter().copied(), writer)
}

/// Writes the layout whose fields are `head`'s and whose segments are `segments` (the
/// ones in `head.segments` are ignored): what [`write_layout`] writes for the whole layout.
/// `segments` is consumed as it is written, so a generator can compute them on the fly.
pub fn write_layout_parts<W: Write>(
    head: &Layout,
    segments: impl IntoIterator<Item = Pose>,
    writer: W,
) -> io::Result<()> {
    let mut out = BufWriter::with_capacity(BUFFER, writer);
    let prefix = head_without_segments(head)?;
    out.write_all(&prefix[..prefix.len() - EMPTY_SEGMENTS_TAIL.len()])?;
    out.write_all(b"\"segments\": [")?;
    let mut any = false;
    for pose in segments {
        out.write_all(if any { b",\n    " } else { b"\n    " })?;
        write_pose(&mut out, &pose)?;
        any = true;
    }
    out.write_all(if any { b"\n  ]\n}\n" } else { b"]\n}\n" })?;
    out.flush()
}

/// The head serialized with no segments: ends with [`EMPTY_SEGMENTS_TAIL`].
fn head_without_segments(head: &Layout) -> io::Result<Vec<u8>> {
    let empty = head.without_segments();
    let mut bytes = Vec::new();
    let mut serializer = serde_json::Serializer::with_formatter(&mut bytes, ShallowPretty::default());
    empty
        .serialize(&mut serializer)
        .map_err(io::Error::other)?;
    debug_assert!(bytes.ends_with(EMPTY_SEGMENTS_TAIL), "segments is the last field");
    Ok(bytes)
}

/// One segment on one line, as serde writes a [`Pose`] inside the segment list.
fn write_pose(out: &mut impl Write, pose: &Pose) -> io::Result<()> {
    out.write_all(b"{\"x\": ")?;
    write_um(out, pose.x)?;
    out.write_all(b", \"y\": ")?;
    write_um(out, pose.y)?;
    out.write_all(b", \"z\": ")?;
    write_um(out, pose.z)?;
    out.write_all(b", \"yaw\": ")?;
    write_um(out, pose.yaw)?;
    out.write_all(b"}")
}

/// A number rounded to the micrometre in its shortest form; `null` when not finite, as
/// serde_json writes it.
fn write_um(out: &mut impl Write, value: f64) -> io::Result<()> {
    let value = round_um(value);
    if value.is_finite() {
        out.write_all(zmij::Buffer::new().format_finite(value).as_bytes())
    } else {
        out.write_all(b"null")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    /// What plain serde writes: the reference the hand-written segments must equal.
    fn serde_bytes(layout: &Layout) -> Vec<u8> {
        let mut bytes = Vec::new();
        let mut serializer =
            serde_json::Serializer::with_formatter(&mut bytes, ShallowPretty::default());
        layout.serialize(&mut serializer).unwrap();
        bytes.push(b'\n');
        bytes
    }

    #[test]
    fn segments_are_written_exactly_as_serde_writes_them() {
        let mut spec = GenerateSpec::course(Grid::new(7, 5).unwrap(), Algorithm::Prim, 9);
        spec.geometry.rotation = 0.3;
        let mut layout = build_layout(&spec).unwrap();
        // Awkward numbers: negative zero, tiny, huge, not micrometre-round, not finite.
        for (i, v) in [-0.0, 1e-6, 2.5e-7, 9999.999_999_4, 0.1 + 0.2, f64::NAN]
            .into_iter()
            .enumerate()
        {
            layout.segments[i].x = v;
            layout.segments[i].yaw = -v;
        }
        let mut ours = Vec::new();
        write_layout(&layout, &mut ours).unwrap();
        assert_eq!(
            String::from_utf8(ours).unwrap(),
            String::from_utf8(serde_bytes(&layout)).unwrap()
        );
    }

    #[test]
    fn an_empty_segment_list_is_written_as_serde_writes_it() {
        let layout =
            build_layout(&GenerateSpec::course(Grid::new(1, 1).unwrap(), Algorithm::Dfs, 1))
                .unwrap();
        assert!(layout.segments.is_empty());
        let mut ours = Vec::new();
        write_layout(&layout, &mut ours).unwrap();
        assert_eq!(ours, serde_bytes(&layout));
    }
}
