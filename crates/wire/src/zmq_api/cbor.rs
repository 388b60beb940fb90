//! CBOR values on the ZeroMQ remote API wire: encoding, tolerant decoding and typed accessors.
//!
//! Decoding accepts what CoppeliaSim's Lua encoders produce: strings as text *or* byte strings,
//! floats of any width (half, single, double), integers where floats are expected, and CBOR
//! tags (unwrapped, e.g. the 4.11 `simCBOR` handle tag). Nothing here panics on bad input.

use ciborium::Value;

/// A malformed CBOR message.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct CborError(pub String);

/// Encodes one CBOR item.
pub fn encode(value: &Value) -> Vec<u8> {
    let mut out = Vec::with_capacity(64);
    // Writing into a Vec cannot fail, and every `Value` is encodable.
    ciborium::ser::into_writer(value, &mut out).unwrap_or_default();
    out
}

/// Decodes exactly one CBOR item (trailing bytes are an error) and unwraps every tag.
pub fn decode(bytes: &[u8]) -> Result<Value, CborError> {
    if bytes.is_empty() {
        return Err(CborError("empty message (expected one CBOR item)".into()));
    }
    let mut reader = bytes;
    let value: Value = ciborium::de::from_reader(&mut reader)
        .map_err(|e| CborError(format!("malformed CBOR ({} bytes): {e}", bytes.len())))?;
    if !reader.is_empty() {
        return Err(CborError(format!(
            "{} trailing bytes after the CBOR item",
            reader.len()
        )));
    }
    Ok(untag(value))
}

/// Removes CBOR tags, recursively.
pub fn untag(value: Value) -> Value {
    match value {
        Value::Tag(_, inner) => untag(*inner),
        Value::Array(items) => Value::Array(items.into_iter().map(untag).collect()),
        Value::Map(pairs) => Value::Map(
            pairs
                .into_iter()
                .map(|(k, v)| (untag(k), untag(v)))
                .collect(),
        ),
        other => other,
    }
}

/// A map with text keys, in the given order.
pub fn map<'a>(pairs: impl IntoIterator<Item = (&'a str, Value)>) -> Value {
    Value::Map(
        pairs
            .into_iter()
            .map(|(k, v)| (Value::Text(k.to_string()), v))
            .collect(),
    )
}

/// The value under a text (or byte-string) key of a map.
pub fn get<'a>(value: &'a Value, key: &str) -> Option<&'a Value> {
    match value {
        Value::Map(pairs) => pairs
            .iter()
            .find(|(k, _)| text(k) == Some(key))
            .map(|(_, v)| v),
        _ => None,
    }
}

/// A string sent as text or as a UTF-8 byte string.
pub fn text(value: &Value) -> Option<&str> {
    match value {
        Value::Text(s) => Some(s),
        Value::Bytes(b) => std::str::from_utf8(b).ok(),
        _ => None,
    }
}

/// A number: a float of any width or an integer.
pub fn number(value: &Value) -> Option<f64> {
    match value {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(i128::from(*i) as f64),
        _ => None,
    }
}

/// An integer, also accepted as a float with an integral value (Lua 5.3 may send `3.0`).
pub fn integer(value: &Value) -> Option<i64> {
    match value {
        Value::Integer(i) => i64::try_from(i128::from(*i)).ok(),
        Value::Float(f) if f.fract() == 0.0 && f.abs() < 9.0e15 => Some(*f as i64),
        _ => None,
    }
}

/// A handle or enum (`i32`).
pub fn int32(value: &Value) -> Option<i32> {
    integer(value).and_then(|i| i32::try_from(i).ok())
}

/// A boolean (Lua truthiness is not applied: only CBOR booleans).
pub fn boolean(value: &Value) -> Option<bool> {
    match value {
        Value::Bool(b) => Some(*b),
        _ => None,
    }
}

/// An array of numbers of exactly `N` elements.
pub fn numbers<const N: usize>(value: &Value) -> Option<[f64; N]> {
    let items = array(value)?;
    if items.len() != N {
        return None;
    }
    let mut out = [0.0; N];
    for (o, v) in out.iter_mut().zip(items) {
        *o = number(v)?;
    }
    Some(out)
}

/// The elements of an array; an empty map counts as an empty array (Lua's `{}`).
pub fn array(value: &Value) -> Option<&[Value]> {
    match value {
        Value::Array(items) => Some(items),
        Value::Map(pairs) if pairs.is_empty() => Some(&[]),
        _ => None,
    }
}

/// An array of handles.
pub fn handles(value: &Value) -> Option<Vec<i32>> {
    array(value)?.iter().map(int32).collect()
}

/// A float array value.
pub fn float_array(values: &[f64]) -> Value {
    Value::Array(values.iter().map(|x| Value::Float(*x)).collect())
}

/// An integer value.
pub fn int(i: i64) -> Value {
    Value::Integer(i.into())
}

/// A short human-readable rendering of a value for error messages.
pub fn describe(value: &Value) -> String {
    let mut s = format!("{value:?}");
    if s.len() > 120 {
        let cut = (0..=117)
            .rev()
            .find(|i| s.is_char_boundary(*i))
            .unwrap_or(0);
        s.truncate(cut);
        s.push_str("...");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_of_every_width_and_ints() {
        // f16 1.5, f32 0.25, f64 -2.0, int 3
        for (hex, want) in [
            ("f93e00", 1.5),
            ("fa3e800000", 0.25),
            ("fbc000000000000000", -2.0),
            ("03", 3.0),
        ] {
            let v = decode(&hex_bytes(hex)).unwrap();
            assert_eq!(number(&v), Some(want), "{hex}");
        }
        assert_eq!(integer(&decode(&hex_bytes("fa40400000")).unwrap()), Some(3));
    }

    #[test]
    fn strings_as_text_or_bytes_and_tags_unwrapped() {
        assert_eq!(text(&decode(&hex_bytes("634c696e")).unwrap()), Some("Lin"));
        assert_eq!(text(&decode(&hex_bytes("434c696e")).unwrap()), Some("Lin"));
        // tag 4294999999 (simCBOR handle) around 17
        let v = decode(&hex_bytes("db00000000ffff7ebf11")).unwrap();
        assert_eq!(int32(&v), Some(17));
        assert!(
            array(&decode(&hex_bytes("a0")).unwrap())
                .unwrap()
                .is_empty()
        );
    }

    #[test]
    fn malformed_is_an_error_not_a_panic() {
        for bad in [
            "",
            "ff",
            "a1",
            "9f01",
            "0102",
            "5bffffffffffffffff",
            "7a0000ffff61",
        ] {
            assert!(decode(&hex_bytes(bad)).is_err(), "{bad}");
        }
    }

    fn hex_bytes(s: &str) -> Vec<u8> {
        (0..s.len())
            .step_by(2)
            .map(|i| u8::from_str_radix(&s[i..i + 2], 16).unwrap())
            .collect()
    }
}
