//! Splits a layout document as it is read: the bytes before the top-level `segments`
//! array (the head, small), the array's elements one at a time, and the bytes after it.
//! Only the JSON structure is tracked here (strings, nesting, the top-level keys); what
//! the bytes mean is serde's job, and [`super::segment`]'s for the common segment shape.

use std::io::{self, Read};

use super::segment::parse_fast;
use crate::layout::Pose;

/// Bytes read at a time.
const CHUNK: usize = 1 << 20;

/// The most bytes of a layout outside its segment list (the head before it and the tail
/// after it): 64 MiB, four times what the largest grid's fields take (a 4096x4096 grid's
/// passages are 4096 rows of 4096 digits, 17 MB written), so an endless or huge input
/// that is no layout (`/dev/zero`, a log) fails after a bounded read.
pub(super) const MAX_FIELDS_BYTES: usize = 64 << 20;
/// The most bytes one element of the segment list may take, with the white space before
/// the next one: 64 KiB, hundreds of times what a segment spelled out with its four
/// numbers takes.
pub(super) const MAX_ELEMENT_BYTES: usize = 64 << 10;

/// `` `{` `` for a printable ASCII byte, `byte 0x00` for any other.
pub(super) fn shown_byte(byte: u8) -> String {
    if byte.is_ascii_graphic() {
        format!("`{}`", byte as char)
    } else {
        format!("byte 0x{byte:02x}")
    }
}

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
    /// Fails at once on bytes no JSON holds (a control character, a byte order mark, a
    /// first byte other than `{`), and after [`MAX_FIELDS_BYTES`].
    pub fn head(&mut self, head: &mut Vec<u8>) -> Result<bool, ScanError> {
        let mut depth = 0usize;
        let mut in_string = false;
        let mut escaped = false;
        let mut key_start = None;
        let mut expect_key = false;
        let mut segments_next = false;
        let mut last_key_was_segments = false;
        let mut started = false;
        while let Some(byte) = self.peek()? {
            self.check_byte(byte, head.len(), started)?;
            started |= !byte.is_ascii_whitespace();
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

    /// Refuses `byte`, the next one after `read` bytes of the head (`started` once one was
    /// not white space), if no layout can hold it there.
    fn check_byte(&self, byte: u8, read: usize, started: bool) -> Result<(), ScanError> {
        let refuse = |message: String| Err(ScanError::Syntax(self.position(), message));
        if byte < 0x20 && !matches!(byte, b' ' | b'\n' | b'\r' | b'\t') {
            return refuse(format!(
                "control character 0x{byte:02x}: JSON holds none outside escapes (is this a layout file?)"
            ));
        }
        if !started && !byte.is_ascii_whitespace() && byte != b'{' {
            if byte == 0xEF {
                return refuse(
                    "the file starts with a UTF-8 byte order mark (EF BB BF), which JSON does not allow: save it without one".into(),
                );
            }
            return refuse(format!(
                "expected `{{` (a layout is a JSON object), found {}",
                shown_byte(byte)
            ));
        }
        if !started && read >= MAX_ELEMENT_BYTES {
            return refuse(format!(
                "more than {} KiB of white space and no `{{`: a layout is a JSON object (is this a layout file?)",
                MAX_ELEMENT_BYTES >> 10
            ));
        }
        if read >= MAX_FIELDS_BYTES {
            return refuse(format!(
                "more than {} MiB outside the segment list: no layout holds that much (is this a layout file?)",
                MAX_FIELDS_BYTES >> 20
            ));
        }
        Ok(())
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
    pub fn list_is_empty(&mut self) -> Result<bool, ScanError> {
        self.skip_space()?;
        Ok(self.peek()? == Some(b']'))
    }

    /// Consumes whitespace, at most [`MAX_ELEMENT_BYTES`] of it.
    fn skip_space(&mut self) -> Result<(), ScanError> {
        let mut skipped = 0;
        loop {
            let rest = &self.buffer[self.at..];
            let space = rest
                .iter()
                .position(|b| !matches!(b, b' ' | b'\n' | b'\r' | b'\t'))
                .unwrap_or(rest.len());
            self.consumed(self.at, self.at + space);
            self.at += space;
            skipped += space;
            if skipped > MAX_ELEMENT_BYTES {
                return Err(ScanError::Syntax(
                    self.position(),
                    format!(
                        "more than {} KiB of white space in the segment list (is this a layout file?)",
                        MAX_ELEMENT_BYTES >> 10
                    ),
                ));
            }
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
            if scanned > MAX_ELEMENT_BYTES {
                return Err(ScanError::Syntax(
                    self.position(),
                    format!(
                        "a segment longer than {} KiB: no layout holds one (is this a layout file?)",
                        MAX_ELEMENT_BYTES >> 10
                    ),
                ));
            }
            if !self.fill()? {
                return Err(ScanError::Syntax(
                    self.position_of(self.buffer.len()),
                    "EOF while parsing a list".into(),
                ));
            }
        }
    }

    /// Everything left, at most `limit` bytes of it.
    pub fn rest(&mut self, tail: &mut Vec<u8>, limit: usize) -> Result<(), ScanError> {
        loop {
            tail.extend_from_slice(&self.buffer[self.at..]);
            self.at = self.buffer.len();
            if tail.len() > limit {
                return Err(ScanError::Syntax(
                    self.position(),
                    format!(
                        "more than {} MiB outside the segment list: no layout holds that much (is this a layout file?)",
                        MAX_FIELDS_BYTES >> 20
                    ),
                ));
            }
            if !self.fill()? {
                return Ok(());
            }
        }
    }
}
