//! One segment object, parsed fast: the shape this crate writes,
//! `{"x": N, "y": N, "z": N, "yaw": N}` (spaces or tabs between tokens, no line break, so
//! the reader need not count lines inside it), with numbers
//! read exactly as serde_json reads them. Anything else is left to serde, which accepts
//! every valid spelling and words every error.

use crate::layout::Pose;

/// Powers of ten that are exact in an `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The segment in `bytes` (one JSON value, trimmed), or `None` when it is not in the fast
/// shape: the caller then asks serde.
pub(super) fn parse_fast(bytes: &[u8]) -> Option<Pose> {
    let mut cursor = Cursor { bytes, at: 0 };
    cursor.expect(b'{')?;
    let x = cursor.field(b"\"x\"")?;
    cursor.expect(b',')?;
    let y = cursor.field(b"\"y\"")?;
    cursor.expect(b',')?;
    let z = cursor.field(b"\"z\"")?;
    cursor.expect(b',')?;
    let yaw = cursor.field(b"\"yaw\"")?;
    cursor.expect(b'}')?;
    (cursor.at == bytes.len()).then_some(Pose { x, y, z, yaw })
}

/// A position in the bytes of one segment.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn skip_space(&mut self) {
        while let Some(b' ' | b'\t') = self.bytes.get(self.at) {
            self.at += 1;
        }
    }

    /// Whitespace, then exactly `token`.
    fn expect_all(&mut self, token: &[u8]) -> Option<()> {
        self.skip_space();
        let end = self.at + token.len();
        (self.bytes.get(self.at..end)? == token).then(|| self.at = end)
    }

    fn expect(&mut self, byte: u8) -> Option<()> {
        self.expect_all(&[byte])
    }

    /// `"key": number`.
    fn field(&mut self, key: &[u8]) -> Option<f64> {
        self.expect_all(key)?;
        self.expect(b':')?;
        self.skip_space();
        let start = self.at;
        if let Some(value) = self.simple_decimal() {
            return Some(value);
        }
        self.at = start;
        while let Some(b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E') = self.bytes.get(self.at) {
            self.at += 1;
        }
        number(&self.bytes[start..self.at])
    }

    /// A number `-?(0|[1-9][0-9]*)(\.[0-9]+)?` of at most 15 digits, not followed by an
    /// exponent, read in one pass: the integer of its digits divided by a power of ten,
    /// both exact, so the one IEEE division is correctly rounded. `None` (the cursor
    /// anywhere) for any other token.
    fn simple_decimal(&mut self) -> Option<f64> {
        let negative = self.bytes.get(self.at) == Some(&b'-');
        if negative {
            self.at += 1;
        }
        let mut mantissa: u64 = 0;
        let mut count = 0;
        let first = *self.bytes.get(self.at)?;
        if !first.is_ascii_digit() {
            return None;
        }
        while let Some(&b) = self.bytes.get(self.at).filter(|b| b.is_ascii_digit()) {
            mantissa = mantissa * 10 + u64::from(b - b'0');
            count += 1;
            self.at += 1;
        }
        if first == b'0' && count > 1 {
            return None;
        }
        let mut decimals = 0;
        if self.bytes.get(self.at) == Some(&b'.') {
            self.at += 1;
            while let Some(&b) = self.bytes.get(self.at).filter(|b| b.is_ascii_digit()) {
                mantissa = mantissa * 10 + u64::from(b - b'0');
                count += 1;
                decimals += 1;
                self.at += 1;
            }
            if decimals == 0 {
                return None;
            }
        }
        if count > 15
            || matches!(
                self.bytes.get(self.at),
                Some(b'e' | b'E' | b'.' | b'+' | b'-')
            )
        {
            return None;
        }
        let value = mantissa as f64 / POW10[decimals];
        Some(if negative { -value } else { value })
    }
}

/// A JSON number token as an `f64`, correctly rounded (as serde_json's `float_roundtrip`
/// reads it), or `None` when the token is not a JSON number or is out of range.
fn number(token: &[u8]) -> Option<f64> {
    if !is_json_number(token) {
        return None;
    }
    let value: f64 = std::str::from_utf8(token).ok()?.parse().ok()?;
    value.is_finite().then_some(value)
}

/// The JSON number grammar: `-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?`.
fn is_json_number(token: &[u8]) -> bool {
    let mut i = 0;
    let at = |i: usize| token.get(i).copied();
    let digits = |mut i: usize| {
        let start = i;
        while at(i).is_some_and(|b| b.is_ascii_digit()) {
            i += 1;
        }
        (i > start).then_some(i)
    };
    if at(i) == Some(b'-') {
        i += 1;
    }
    match at(i) {
        Some(b'0') => i += 1,
        Some(b'1'..=b'9') => match digits(i) {
            Some(next) => i = next,
            None => return false,
        },
        _ => return false,
    }
    if at(i) == Some(b'.') {
        match digits(i + 1) {
            Some(next) => i = next,
            None => return false,
        }
    }
    if let Some(b'e' | b'E') = at(i) {
        i += 1;
        if let Some(b'+' | b'-') = at(i) {
            i += 1;
        }
        match digits(i) {
            Some(next) => i = next,
            None => return false,
        }
    }
    i == token.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn serde(text: &str) -> Option<Pose> {
        serde_json::from_str(text).ok()
    }

    #[test]
    fn the_written_shape_is_read_fast_and_as_serde_reads_it() {
        for text in [
            r#"{"x": -3.75, "y": -4.0, "z": 0.001, "yaw": 1.570796}"#,
            r#"{"x":0,"y":-0.0,"z":1e-6,"yaw":-3.141593}"#,
            "{ \"x\" : 12345.678901 ,\t \"y\": 0.30000000000000004, \"z\": 2.5E-7, \"yaw\": 1E2 }",
            r#"{"x": 9999.999999, "y": 123456789012345678, "z": 0.1, "yaw": 0.7}"#,
            r#"{"x": -0, "y": -0.000, "z": -12, "yaw": 0.1234567890123456789}"#,
        ] {
            let fast = parse_fast(text.as_bytes()).unwrap_or_else(|| panic!("{text}"));
            let reference = serde(text).unwrap();
            for (a, b) in [
                (fast.x, reference.x),
                (fast.y, reference.y),
                (fast.z, reference.z),
                (fast.yaw, reference.yaw),
            ] {
                assert_eq!(a.to_bits(), b.to_bits(), "{text}");
            }
        }
    }

    #[test]
    fn other_shapes_and_bad_numbers_are_left_to_serde() {
        for text in [
            r#"{"y": 1, "x": 2, "z": 3, "yaw": 4}"#,
            r#"{"x": 1, "y": 2, "z": 3}"#,
            r#"{"x": 1, "y": 2, "z": 3, "yaw": 4, "w": 5}"#,
            r#"{"x": 01, "y": 2, "z": 3, "yaw": 4}"#,
            r#"{"x": 1., "y": 2, "z": 3, "yaw": 4}"#,
            r#"{"x": .5, "y": 2, "z": 3, "yaw": 4}"#,
            r#"{"x": +1, "y": 2, "z": 3, "yaw": 4}"#,
            r#"{"x": 1e400, "y": 2, "z": 3, "yaw": 4}"#,
            r#"{"x": "1", "y": 2, "z": 3, "yaw": 4}"#,
            r#"{"x": 1, "y": 2, "z": 3, "yaw": 4} x"#,
            r#"[1, 2, 3, 4]"#,
            "{\"x\": 1,\n\"y\": 2, \"z\": 3, \"yaw\": 4}",
        ] {
            assert_eq!(parse_fast(text.as_bytes()), None, "{text}");
        }
    }
}
