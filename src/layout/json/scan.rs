//! Splits a layout document as it is read: the bytes before the top-level `segments`
//! array (the head, small), the array's elements one at a time, and the bytes after it.
//! Only the JSON structure is tracked here (strings, nesting, the top-level keys); what
//! the bytes mean is serde's job, and [`super::segment`]'s for the common segment shape.

use std::io::{self, Read};

use super::segment::parse_fast;
use crate::layout::Pose;

/// Bytes read at a time.
const CHUNK: usize = 1 << 20;

/// Where a byte lies, as serde_json counts: 1-based line and column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Position {
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

/// One element of the segment list.
pub(super) enum Element<'a> {
    /// A segment in the shape this crate writes, already parsed.
    Segment(Pose),
    /// Anything else, trimmed, for serde to read or refuse.
    Other(&'a [u8]),
}

/// A structural error in the segment list, at a position.
#[derive(Debug)]
pub(super) enum ScanError {
    /// The reader failed.
    Io(io::Error),
    /// Not JSON.
    Syntax(Position, String),
}

impl From<io::Error> for ScanError {
    fn from(e: io::Error) -> Self {
        ScanError::Io(e)
    }
}

/// A reader's bytes, buffered in big chunks, with the position of the next byte.
pub(super) struct Source<R> {
    reader: R,
    buffer: Vec<u8>,
    /// Next unread byte in `buffer`.
    at: usize,
    eof: bool,
    /// Absolute offset of `buffer[0]`.
    base: usize,
    line: usize,
    /// Absolute offset of the first byte of the current line.
    line_start: usize,
    /// The line of the segment list's `[`.
    list_line: usize,
}

impl<R: Read> Source<R> {
    /// Starts reading `reader`.
    pub fn new(reader: R) -> Self {
        Self {
            reader,
            buffer: Vec::with_capacity(CHUNK),
            at: 0,
            eof: false,
            base: 0,
            line: 1,
            line_start: 0,
            list_line: 1,
        }
    }

    /// Position of the next unread byte.
    pub fn position(&self) -> Position {
        self.position_of(self.at)
    }

    fn position_of(&self, at: usize) -> Position {
        Position {
            line: self.line,
            column: self.base + at - self.line_start + 1,
        }
    }

    /// Reads more bytes, keeping `buffer[self.at..]`; `false` at the end of the input.
    fn fill(&mut self) -> io::Result<bool> {
        if self.eof {
            return Ok(false);
        }
        self.buffer.drain(..self.at);
        self.base += self.at;
        self.at = 0;
        let read = (&mut self.reader)
            .take(CHUNK as u64)
            .read_to_end(&mut self.buffer)?;
        self.eof = read == 0;
        Ok(read > 0)
    }

    /// The next byte, consumed; `None` at the end of the input.
    fn next_byte(&mut self) -> io::Result<Option<u8>> {
        if self.at == self.buffer.len() && !self.fill()? {
            return Ok(None);
        }
        let byte = self.buffer[self.at];
        self.consumed(self.at, self.at + 1);
        self.at += 1;
        Ok(Some(byte))
    }

    /// The next byte, not consumed.
    fn peek(&mut self) -> io::Result<Option<u8>> {
        if self.at == self.buffer.len() && !self.fill()? {
            return Ok(None);
        }
        Ok(Some(self.buffer[self.at]))
    }

    /// Counts the lines of `buffer[from..to]`, which is being consumed.
    fn consumed(&mut self, from: usize, to: usize) {
        for (k, &b) in self.buffer[from..to].iter().enumerate() {
            if b == b'\n' {
                self.line += 1;
                self.line_start = self.base + from + k + 1;
            }
        }
    }

    /// Copies bytes into the head up to the value of the top-level `"segments"` key. When
    /// that value is an array, its `[` is consumed and the result is `true`; otherwise the
    /// whole input is the head.
    pub fn head(&mut self, head: &mut Vec<u8>) -> io::Result<bool> {
        let mut depth = 0usize;
        let mut in_string = false;
        let mut escaped = false;
        let mut key_start = None;
        let mut expect_key = false;
        let mut segments_next = false;
        let mut last_key_was_segments = false;
        while let Some(byte) = self.peek()? {
            if segments_next && !matches!(byte, b' ' | b'\n' | b'\r' | b'\t') {
                segments_next = false;
                if byte == b'[' {
                    self.next_byte()?;
                    self.list_line = self.line;
                    return Ok(true);
                }
            }
            self.next_byte()?;
            head.push(byte);
            if in_string {
                if escaped {
                    escaped = false;
                } else if byte == b'\\' {
                    escaped = true;
                } else if byte == b'"' {
                    in_string = false;
                    if let Some(start) = key_start.take() {
                        last_key_was_segments = &head[start..] == b"\"segments\"";
                    }
                }
                continue;
            }
            match byte {
                b'"' => {
                    in_string = true;
                    if depth == 1 && expect_key {
                        key_start = Some(head.len() - 1);
                        expect_key = false;
                    }
                }
                b'{' | b'[' => {
                    depth += 1;
                    expect_key = depth == 1 && byte == b'{';
                }
                b'}' | b']' => depth = depth.saturating_sub(1),
                b',' if depth == 1 => expect_key = true,
                b':' if depth == 1 => {
                    segments_next = last_key_was_segments;
                    last_key_was_segments = false;
                }
                _ => {}
            }
        }
        Ok(false)
    }

    /// Hands each element of the segment list (after its `[`) to `each` with its position,
    /// through the closing `]`. Returns the number of line breaks inside the list.
    pub fn elements(
        &mut self,
        mut each: impl FnMut(Element, Position) -> Result<(), ScanError>,
    ) -> Result<usize, ScanError> {
        if self.list_is_empty()? {
            self.next_byte()?;
            return Ok(self.line - self.list_line);
        }
        loop {
            let start = self.at;
            let position = self.position_of(start);
            match self.element()? {
                (end, Some(pose)) => {
                    // A fast-read segment holds no line break: nothing to count.
                    self.at = end;
                    each(Element::Segment(pose), position)?;
                }
                (end, None) => {
                    let start = self.at;
                    self.consumed(start, end);
                    self.at = end;
                    each(Element::Other(&self.buffer[start..end]), position)?;
                }
            }
            self.skip_space()?;
            let position = self.position();
            match self.next_byte()? {
                Some(b',') => {
                    self.skip_space()?;
                    if self.peek()? == Some(b']') {
                        return Err(ScanError::Syntax(self.position(), "trailing comma".into()));
                    }
                }
                Some(b']') => return Ok(self.line - self.list_line),
                Some(_) => {
                    return Err(ScanError::Syntax(position, "expected `,` or `]`".into()));
                }
                None => {
                    return Err(ScanError::Syntax(
                        position,
                        "EOF while parsing a list".into(),
                    ));
                }
            }
        }
    }

    /// Whether the segment list (its `[` consumed by [`head`](Self::head)) has no element:
    /// only whitespace before its `]`. Consumes that whitespace.
    pub fn list_is_empty(&mut self) -> io::Result<bool> {
        self.skip_space()?;
        Ok(self.peek()? == Some(b']'))
    }

    /// Consumes whitespace.
    fn skip_space(&mut self) -> io::Result<()> {
        loop {
            let rest = &self.buffer[self.at..];
            let space = rest
                .iter()
                .position(|b| !matches!(b, b' ' | b'\n' | b'\r' | b'\t'))
                .unwrap_or(rest.len());
            self.consumed(self.at, self.at + space);
            self.at += space;
            if self.at < self.buffer.len() || !self.fill()? {
                return Ok(());
            }
        }
    }

    /// The end (in `buffer`) of the value starting at the next byte, without trailing
    /// whitespace, and the segment when it is one in the shape this crate writes; nothing
    /// is consumed (a refill may move the value to the start of the buffer). A segment is
    /// found with one search for its `}`; anything else is walked byte by byte.
    fn element(&mut self) -> Result<(usize, Option<Pose>), ScanError> {
        let mut scanned = 0;
        let mut depth = 0usize;
        let mut in_string = false;
        let mut escaped = false;
        loop {
            let rest = &self.buffer[self.at..];
            if scanned == 0
                && rest.first() == Some(&b'{')
                && let Some(close) = memchr::memchr(b'}', rest)
                && let Some(pose) = parse_fast(&rest[..=close])
            {
                return Ok((self.at + close + 1, Some(pose)));
            }
            let mut end = None;
            for (k, &b) in rest.iter().enumerate().skip(scanned) {
                if in_string {
                    if escaped {
                        escaped = false;
                    } else if b == b'\\' {
                        escaped = true;
                    } else if b == b'"' {
                        in_string = false;
                    }
                    continue;
                }
                match b {
                    b'"' => in_string = true,
                    b'{' | b'[' => depth += 1,
                    b'}' | b']' if depth > 0 => depth -= 1,
                    b',' | b']' if depth == 0 => {
                        end = Some(k);
                        break;
                    }
                    _ => {}
                }
            }
            if let Some(end) = end {
                let trimmed = rest[..end]
                    .iter()
                    .rposition(|b| !matches!(b, b' ' | b'\n' | b'\r' | b'\t'))
                    .map_or(0, |last| last + 1);
                if trimmed == 0 {
                    return Err(ScanError::Syntax(self.position(), "expected value".into()));
                }
                return Ok((self.at + trimmed, None));
            }
            scanned = rest.len();
            if !self.fill()? {
                return Err(ScanError::Syntax(
                    self.position_of(self.buffer.len()),
                    "EOF while parsing a list".into(),
                ));
            }
        }
    }

    /// Everything left.
    pub fn rest(&mut self, tail: &mut Vec<u8>) -> io::Result<()> {
        loop {
            tail.extend_from_slice(&self.buffer[self.at..]);
            self.at = self.buffer.len();
            if !self.fill()? {
                return Ok(());
            }
        }
    }
}
