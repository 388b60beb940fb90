//! Where a layout's segments go as they are read ([`SegmentSink`]): kept in a list, or
//! handed in batches to a sink working on its own thread ([`Background`]), so reading and
//! what the sink does run side by side.

use std::sync::mpsc;
use std::thread;

use crate::layout::Pose;

/// Receives a layout's segments as they are read.
pub trait SegmentSink {
    /// Called once per segment, in file order; `index` counts from 0.
    fn segment(&mut self, index: usize, pose: Pose);
}

/// Keeps every segment: what [`read_layout`](super::read_layout) uses.
impl SegmentSink for Vec<Pose> {
    fn segment(&mut self, _index: usize, pose: Pose) {
        self.push(pose);
    }
}

/// Segments handed to a [`Background`] sink at a time.
const BATCH: usize = 1 << 16;

/// A sink that works on its own thread, so reading and what the sink does run side by
/// side: segments are handed over in batches. [`finish`](Background::finish) returns the
/// sink once it has seen every segment.
pub struct Background<S> {
    batch: Vec<Pose>,
    /// Index of the batch's first segment.
    first: usize,
    to_sink: Option<mpsc::SyncSender<(usize, Vec<Pose>)>>,
    sink: thread::JoinHandle<S>,
}

impl<S: SegmentSink + Send + 'static> Background<S> {
    /// Starts `sink` on its own thread.
    pub fn new(mut sink: S) -> Self {
        let (to_sink, batches) = mpsc::sync_channel::<(usize, Vec<Pose>)>(4);
        let sink = thread::spawn(move || {
            for (first, batch) in batches {
                for (k, pose) in batch.into_iter().enumerate() {
                    sink.segment(first + k, pose);
                }
            }
            sink
        });
        Self {
            batch: Vec::with_capacity(BATCH),
            first: 0,
            to_sink: Some(to_sink),
            sink,
        }
    }

    /// Hands over the segments not sent yet; `false` if the sink's thread is gone.
    fn send(&mut self) -> bool {
        let batch = std::mem::replace(&mut self.batch, Vec::with_capacity(BATCH));
        let first = self.first;
        self.first += batch.len();
        self.to_sink
            .as_ref()
            .is_some_and(|to_sink| to_sink.send((first, batch)).is_ok())
    }

    /// The sink, once it has seen every segment. A panic on its thread resumes here.
    pub fn finish(mut self) -> S {
        self.send();
        self.to_sink = None;
        self.sink
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    }
}

impl<S: SegmentSink + Send + 'static> SegmentSink for Background<S> {
    fn segment(&mut self, _index: usize, pose: Pose) {
        self.batch.push(pose);
        if self.batch.len() == BATCH && !self.send() {
            // The sink's thread died: `finish` reports its panic.
            self.batch.clear();
        }
    }
}
