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

/// The empty segment list in the serialized head, a top-level field (indented once): the
/// writer splices the segments in between its brackets. Fields after it (a wall layout's
/// `walls`) follow the list as serde wrote them.
const EMPTY_SEGMENTS: &[u8] = b"\n  \"segments\": []";

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
/// this one writes the text (see the private `layout::json::parallel` module).
pub fn write_layout_parts<W: Write>(
    head: &Layout,
    segments: impl IntoIterator<Item = Pose, IntoIter: Send>,
    mut writer: W,
) -> io::Result<()> {
    let (before, after) = head_around_segments(head)?;
    writer.write_all(&before)?;
    let segments = segments.into_iter();
    let any = parallel::write_segments(segments, &mut writer, write_batch)?;
    writer.write_all(if any { b"\n  ]" } else { b"]" })?;
    writer.write_all(&after)?;
    writer.write_all(b"\n")?;
    writer.flush()
}

/// The head serialized with no segments, split inside the empty list: the text up to and
/// including `[`, and the text from `]` on (without the final newline).
fn head_around_segments(head: &Layout) -> io::Result<(Vec<u8>, Vec<u8>)> {
    let empty = head.without_segments();
    let mut bytes = Vec::new();
    let mut serializer =
        serde_json::Serializer::with_formatter(&mut bytes, ShallowPretty::default());
    empty.serialize(&mut serializer).map_err(io::Error::other)?;
    let at = memchr::memmem::find(&bytes, EMPTY_SEGMENTS)
        .ok_or_else(|| io::Error::other("the layout has no segment list"))?;
    let open = at + EMPTY_SEGMENTS.len() - 1;
    let mut after = bytes.split_off(open);
    after.remove(0); // the `]`, written after the segments
    Ok((bytes, after))
}

/// A batch of segments, as serde writes them inside the segment list: each on its own
/// line, after a comma unless it is the very first of the list.
fn write_batch(text: &mut Vec<u8>, batch: &[Pose], first: bool) {
    // Values repeat: one height and a heading per direction in a generated layout, and
    // along a row of an unturned maze three values of y. Those are formatted once.
    let (mut ys, mut heights, mut headings) = (Recent::new(), Recent::new(), Recent::new());
    for (i, pose) in batch.iter().enumerate() {
        text.extend_from_slice(if first && i == 0 {
            b"\n    "
        } else {
            b",\n    "
        });
        text.extend_from_slice(b"{\"x\": ");
        write_um(text, pose.x);
        text.extend_from_slice(b", \"y\": ");
        ys.write(text, pose.y);
        text.extend_from_slice(b", \"z\": ");
        heights.write(text, pose.z);
        text.extend_from_slice(b", \"yaw\": ");
        headings.write(text, pose.yaw);
        text.push(b'}');
    }
}

/// The texts of the last [`RECENT`] distinct values [`write_um`] wrote for one field.
struct Recent {
    /// Value (as bits), text and its length; replaced oldest first.
    texts: [(u64, [u8; TEXT], usize); RECENT],
    next: usize,
}

/// Values a [`Recent`] keeps.
const RECENT: usize = 4;
/// Longest text [`write_um`] writes (zmij's longest, `-1.2345678901234567e-308`).
const TEXT: usize = 24;

impl Recent {
    fn new() -> Self {
        // No value is NaN with these bits and length 0: a slot that never matches.
        Self {
            texts: [(f64::NAN.to_bits(), [0; TEXT], 0); RECENT],
            next: 0,
        }
    }

    /// Writes `value` as [`write_um`] does, from memory when it was among the last.
    #[inline]
    fn write(&mut self, out: &mut Vec<u8>, value: f64) {
        let bits = value.to_bits();
        if let Some((_, text, len)) = self.texts.iter().find(|t| t.0 == bits && t.2 > 0) {
            return out.extend_from_slice(&text[..*len]);
        }
        let at = out.len();
        write_um(out, value);
        let written = &out[at..];
        let slot = &mut self.texts[self.next];
        slot.0 = bits;
        slot.1[..written.len()].copy_from_slice(written);
        slot.2 = written.len();
        self.next = (self.next + 1) % RECENT;
    }
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
    // Digits from the right into a buffer, copied out at once: `-`, the metres, `.` and
    // the six micrometre places without trailing zeros (one kept).
    let mut buffer = [0u8; 24];
    let mut at = buffer.len();
    let mut put = |byte: u8| {
        at -= 1;
        buffer[at] = byte;
    };
    let magnitude = micrometres.abs() as u64;
    let (mut whole, mut fraction) = (magnitude / 1_000_000, magnitude % 1_000_000);
    let mut places = 6;
    while places > 1 && fraction % 10 == 0 {
        fraction /= 10;
        places -= 1;
    }
    for _ in 0..places {
        put(b'0' + (fraction % 10) as u8);
        fraction /= 10;
    }
    put(b'.');
    loop {
        put(b'0' + (whole % 10) as u8);
        whole /= 10;
        if whole == 0 {
            break;
        }
    }
    if micrometres < 0.0 {
        put(b'-');
    }
    out.extend_from_slice(&buffer[at..]);
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
            // Heights are remembered by value: each awkward one twice, apart.
            layout.segments[i].z = v;
            layout.segments[i + 10].z = v;
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
