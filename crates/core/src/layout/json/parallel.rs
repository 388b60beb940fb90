//! The segment list of a big layout, formatted on several threads and written in order.
//!
//! Formatting the numbers is most of the work of writing a layout (a 4096 x 4096 maze has
//! 33 million segments, 2 GB of text), so one thread takes the segments from their
//! iterator in batches and deals them round to the formatting threads in turn, and the
//! calling thread collects the texts in the same turn and writes them: the text is the
//! same whatever the number of threads and however fast each one runs.

use std::io::{self, Write};
use std::num::NonZero;
use std::sync::mpsc::{self, Receiver};
use std::thread;

use crate::layout::Pose;

/// Segments in one batch (about 4 MB of text).
const BATCH: usize = 1 << 16;
/// Batches waiting for or at one formatting thread, at most.
const QUEUE: usize = 2;
/// Formatting threads at most: beyond this the disk is the limit.
const MAX_FORMATTERS: usize = 4;

/// Writes `segments`, batch by batch as `format` writes a batch (told whether it is the
/// first); `false` if there were none.
pub(super) fn write_segments<W: Write>(
    segments: impl Iterator<Item = Pose> + Send,
    writer: &mut W,
    format: fn(&mut Vec<u8>, &[Pose], bool),
) -> io::Result<bool> {
    let formatters = thread::available_parallelism()
        .map_or(1, NonZero::get)
        .min(MAX_FORMATTERS);
    thread::scope(|scope| {
        let mut batch_outs = Vec::with_capacity(formatters);
        let mut text_ins: Vec<Receiver<Vec<u8>>> = Vec::with_capacity(formatters);
        for turn in 0..formatters {
            let (batch_out, batch_in) = mpsc::sync_channel::<Vec<Pose>>(QUEUE);
            let (text_out, text_in) = mpsc::sync_channel(QUEUE);
            scope.spawn(move || {
                for (round, batch) in batch_in.into_iter().enumerate() {
                    let mut text = Vec::with_capacity(batch.len() * 64);
                    format(&mut text, &batch, turn == 0 && round == 0);
                    if text_out.send(text).is_err() {
                        return; // the writer stopped
                    }
                }
            });
            batch_outs.push(batch_out);
            text_ins.push(text_in);
        }
        scope.spawn(move || {
            let mut segments = segments.peekable();
            for batch_out in batch_outs.iter().cycle() {
                if segments.peek().is_none() {
                    return;
                }
                let batch: Vec<Pose> = segments.by_ref().take(BATCH).collect();
                if batch_out.send(batch).is_err() {
                    return; // the writer stopped
                }
            }
        });
        // The first turn with no text is the end: every later one has none either.
        let mut any = false;
        for text_in in text_ins.iter().cycle() {
            let Ok(text) = text_in.recv() else {
                return Ok(any);
            };
            writer.write_all(&text)?;
            any = true;
        }
        unreachable!("cycling over at least one formatter never ends by itself")
    })
}
