//! Writing layout JSON. Everything but the segments goes through serde with the
//! [`ShallowPretty`] formatter; the segments, which are nearly all of a big layout's bytes,
//! are written straight from an iterator, with the same shortest-float routine serde_json
//! uses (`zmij`), so the bytes are exactly what serde would write and no segment list has
//! to exist in memory.

use std::io::{self, Write};

use serde::Serialize;

use super::parallel;
use super::pretty::ShallowPretty;
use crate::layout::geometry::{round_half_away, round_um};
use crate::layout::{Layout, Pose};

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
///
/// Threads share the work, so a big layout is written at disk speed: one takes the
/// segments from the iterator (computing them, for a generator), others format them, and
/// this one writes the text (see [`parallel`]).
pub fn write_layout_parts<W: Write>(
    head: &Layout,
    segments: impl IntoIterator<Item = Pose, IntoIter: Send>,
    mut writer: W,
) -> io::Result<()> {
    let prefix = head_without_segments(head)?;
    writer.write_all(&prefix[..prefix.len() - EMPTY_SEGMENTS_TAIL.len()])?;
    writer.write_all(b"\"segments\": [")?;
    let segments = segments.into_iter();
    let any = parallel::write_segments(segments, &mut writer, write_batch)?;
    writer.write_all(if any { b"\n  ]\n}\n" } else { b"]\n}\n" })?;
    writer.flush()
}

/// The head serialized with no segments: ends with [`EMPTY_SEGMENTS_TAIL`].
fn head_without_segments(head: &Layout) -> io::Result<Vec<u8>> {
    let empty = head.without_segments();
    let mut bytes = Vec::new();
    let mut serializer =
        serde_json::Serializer::with_formatter(&mut bytes, ShallowPretty::default());
    empty.serialize(&mut serializer).map_err(io::Error::other)?;
    debug_assert!(
        bytes.ends_with(EMPTY_SEGMENTS_TAIL),
        "segments is the last field"
    );
    Ok(bytes)
}

/// A batch of segments, as serde writes them inside the segment list: each on its own
/// line, after a comma unless it is the very first of the list.
fn write_batch(text: &mut Vec<u8>, batch: &[Pose], first: bool) {
    for (i, pose) in batch.iter().enumerate() {
        text.extend_from_slice(if first && i == 0 {
            b"\n    "
        } else {
            b",\n    "
        });
        write_pose(text, pose);
    }
}

/// One segment, as serde writes a [`Pose`] inside the segment list.
fn write_pose(line: &mut Vec<u8>, pose: &Pose) {
    line.extend_from_slice(b"{\"x\": ");
    write_um(line, pose.x);
    line.extend_from_slice(b", \"y\": ");
    write_um(line, pose.y);
    line.extend_from_slice(b", \"z\": ");
    write_um(line, pose.z);
    line.extend_from_slice(b", \"yaw\": ");
    write_um(line, pose.yaw);
    line.push(b'}');
}

/// A number rounded to the micrometre in its shortest form; `null` when not finite, as
/// serde_json writes it.
fn write_um(out: &mut Vec<u8>, value: f64) {
    let micrometres = round_half_away(value * 1e6);
    if !micrometres.is_finite() {
        return out.extend_from_slice(b"null");
    }
    if !plain(micrometres) {
        return out.extend_from_slice(
            zmij::Buffer::new()
                .format_finite(round_um(value))
                .as_bytes(),
        );
    }
    if micrometres < 0.0 {
        out.push(b'-');
    }
    let micrometres = micrometres.abs() as u64;
    let (whole, mut fraction) = (micrometres / 1_000_000, micrometres % 1_000_000);
    out.extend_from_slice(itoa::Buffer::new().format(whole).as_bytes());
    out.push(b'.');
    let mut places = 6;
    while places > 1 && fraction % 10 == 0 {
        fraction /= 10;
        places -= 1;
    }
    let mut digits = [b'0'; 6];
    for slot in digits[..places].iter_mut().rev() {
        *slot = b'0' + (fraction % 10) as u8;
        fraction /= 10;
    }
    out.extend_from_slice(&digits[..places]);
}

/// `true` when a value of `micrometres` (a whole number) is written as `[-]int.frac`, its
/// shortest form as zmij writes it: zero, and magnitudes from 1 mm up to 10^7 m; smaller
/// ones take an exponent, and larger ones lie far beyond any floor. Segment coordinates are
/// all plain, and written this way several times faster than by zmij.
fn plain(micrometres: f64) -> bool {
    micrometres == 0.0 || (1e3..1e13).contains(&micrometres.abs())
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
        for (i, v) in [-0.0, 1e-6, 2.5e-7, 9_999.999_999_4, 0.1 + 0.2, f64::NAN]
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
    fn micrometre_numbers_are_what_zmij_writes() {
        let check = |micrometres: i64| {
            let value = micrometres as f64 / 1e6;
            let mut ours = Vec::new();
            write_um(&mut ours, value);
            let theirs = zmij::Buffer::new()
                .format_finite(round_um(value))
                .to_string();
            assert_eq!(String::from_utf8(ours).unwrap(), theirs, "{micrometres}");
        };
        for micrometres in -300_000..=300_000 {
            check(micrometres);
        }
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..300_000 {
            // xorshift: magnitudes up to 10^13 micrometres (10,000 km), both signs.
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            check((x % 20_000_000_000_001) as i64 - 10_000_000_000_000);
        }
    }

    #[test]
    fn an_empty_segment_list_is_written_as_serde_writes_it() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(1, 1).unwrap(),
            Algorithm::Dfs,
            1,
        ))
        .unwrap();
        assert!(layout.segments.is_empty());
        let mut ours = Vec::new();
        write_layout(&layout, &mut ours).unwrap();
        assert_eq!(ours, serde_bytes(&layout));
    }
}
