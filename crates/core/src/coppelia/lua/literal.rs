//! Lua string literals that carry any bytes (packed numbers, names) in a program's text:
//! printable ASCII as it is, every other byte as a `\xHH` escape (Lua 5.2 and later, as both
//! real builds run). The text stays ASCII, so it is a valid CBOR text string, and a `\xHH`
//! takes exactly two digits, so no following character is swallowed.

use std::fmt::Write;

/// Appends `bytes` as a double-quoted Lua literal to `out`.
pub fn write(out: &mut String, bytes: &[u8]) {
    out.reserve(bytes.len() * 4 + 2);
    out.push('"');
    for &b in bytes {
        if kept(b) {
            out.push(char::from(b));
        } else {
            // writing to a String cannot fail
            let _ = write!(out, "\\x{b:02x}");
        }
    }
    out.push('"');
}

/// The bytes of the literal [`fn@write`] put at the start of `text`, and the text after it;
/// `None` for anything [`fn@write`] does not write.
pub fn read(text: &str) -> Option<(Vec<u8>, &str)> {
    let body = text.strip_prefix('"')?.as_bytes();
    let mut bytes = Vec::with_capacity(body.len() / 3);
    let mut i = 0;
    while let Some(&b) = body.get(i) {
        match b {
            b'"' => return Some((bytes, &text[i + 2..])),
            b'\\' => {
                let hex = body.get(i + 1..i + 4)?;
                let digits = hex.strip_prefix(b"x")?;
                let digits = std::str::from_utf8(digits).ok()?;
                let byte = u8::from_str_radix(digits, 16).ok()?;
                // only lower-case digits, and only for bytes kept otherwise
                if kept(byte) || digits.bytes().any(|d| d.is_ascii_uppercase()) {
                    return None;
                }
                bytes.push(byte);
                i += 4;
            }
            _ if kept(b) => {
                bytes.push(b);
                i += 1;
            }
            _ => return None,
        }
    }
    None
}

/// Whether a byte is written as itself: printable ASCII but the quote and the backslash.
fn kept(b: u8) -> bool {
    (0x20..0x7f).contains(&b) && b != b'"' && b != b'\\'
}

#[cfg(test)]
mod tests {
    use super::*;

    fn literal(bytes: &[u8]) -> String {
        let mut s = String::new();
        write(&mut s, bytes);
        s
    }

    #[test]
    fn every_byte_comes_back_and_the_text_is_plain_ascii() {
        let all: Vec<u8> = (0..=255).collect();
        let text = literal(&all);
        assert!(text.bytes().all(|b| (0x20..0x7f).contains(&b)), "{text}");
        let followed = format!("{text}, 7");
        let (back, rest) = read(&followed).unwrap();
        assert_eq!(back, all);
        assert_eq!(rest, ", 7");
    }

    #[test]
    fn printable_text_stays_readable_and_escapes_take_two_digits() {
        assert_eq!(literal(b"Line_1"), "\"Line_1\"");
        assert_eq!(literal(b"a\"b\\c\n1"), "\"a\\x22b\\x5cc\\x0a1\"");
        assert_eq!(literal(&[0, b'7']), "\"\\x007\"");
    }

    #[test]
    fn what_the_writer_never_writes_does_not_parse() {
        for text in [
            "no quote",
            "\"unterminated",
            "\"\\n\"",
            "\"\\x4\"",
            "\"\\x41\"",
            "\"\\xAB\"",
            "\"tab\there\"",
            "\"é\"",
        ] {
            assert_eq!(read(text), None, "{text}");
        }
    }
}
