//! Several calls made by one request: a Lua program (`sim.executeLuaCode`, which both real
//! builds have) that calls each function in turn under `pcall` and answers, per call,
//! `{true, results...}` or `{false, message}`. Each request costs the add-on its receive,
//! its Lua CBOR decoding, a coroutine resume and its reply, 0.1-0.2 ms however little the
//! function does; inside one program a call costs about 12 µs: ten reads of parents and
//! poses took 0.26 ms on the real 4.10.0, against 1.5 ms one request each
//! (`docs/measurements.md`, "Calls made in one request").
//!
//! [`calls_code`] writes the program, [`parse_calls`] reads it back (the emulator runs no Lua:
//! it answers exactly these programs), [`answers`] reads its answer. Arguments are written as
//! Lua literals: integers, finite floats, text and bytes ([`literal`]), booleans, arrays, and
//! maps whose keys are names; anything else (a null, a float that is not finite) cannot be
//! written, and the calls are then made one request each.

use ciborium::Value;
use vrep_maze_core::coppelia::lua::literal;

/// The program making `calls` in order; `None` when an argument cannot be written.
pub fn calls_code(calls: &[(&str, Vec<Value>)]) -> Option<String> {
    let mut code = String::from(HEAD);
    for (func, args) in calls {
        if !is_function_name(func) {
            return None;
        }
        code.push_str("{\"");
        code.push_str(func);
        code.push_str("\", ");
        write_value(&mut code, &Value::Array(args.clone()))?;
        code.push_str("},\n");
    }
    code.push_str(BODY);
    Some(code)
}

/// The calls of a program [`calls_code`] wrote; `None` for any other program.
pub fn parse_calls(code: &str) -> Option<Vec<(String, Vec<Value>)>> {
    let mut rest = code.strip_prefix(HEAD)?;
    let mut calls = Vec::new();
    while let Some(entry) = rest.strip_prefix("{\"") {
        let (func, after) = entry.split_once("\", ")?;
        if !is_function_name(func) {
            return None;
        }
        let (args, after) = read_value(after)?;
        let Value::Array(args) = args else {
            return None;
        };
        calls.push((func.to_string(), args));
        rest = after.strip_prefix("},\n")?;
    }
    (rest == BODY).then_some(calls)
}

/// The outcome of each of `count` calls in the answer of a [`calls_code`] program, `(true,
/// {{true, ...}, {false, message}, ...})`: a call's return values, or what it failed with.
/// `None` for a program that failed as a whole, or an answer of another shape.
pub fn answers(values: &[Value], count: usize) -> Option<Vec<Result<Vec<Value>, String>>> {
    let (Some(Value::Bool(true)), Some(Value::Array(each))) = (values.first(), values.get(1))
    else {
        return None;
    };
    if each.len() != count {
        return None;
    }
    each.iter()
        .map(|one| match one.as_array()?.split_first()? {
            (Value::Bool(true), results) => Some(Ok(results.to_vec())),
            (Value::Bool(false), [Value::Text(message)]) => Some(Err(message.clone())),
            _ => None,
        })
        .collect()
}

/// The answer [`answers`] reads, from each call's outcome (what the emulator replies).
pub fn answer(outcomes: Vec<Result<Vec<Value>, String>>) -> Vec<Value> {
    let each = outcomes
        .into_iter()
        .map(|o| match o {
            Ok(mut results) => {
                results.insert(0, Value::Bool(true));
                Value::Array(results)
            }
            Err(message) => Value::Array(vec![Value::Bool(false), Value::Text(message)]),
        })
        .collect();
    vec![Value::Bool(true), Value::Array(each)]
}

/// What a call to a function the simulator lacks fails with, inside the program as over the
/// remote API.
pub fn no_such_function(func: &str) -> String {
    format!("No such function: {func}")
}

const HEAD: &str = "local C = {\n";

const BODY: &str = "}
local out = {}
for i, c in ipairs(C) do
local f = _G
for part in string.gmatch(c[1], '[^.]+') do f = type(f) == 'table' and f[part] or nil end
if type(f) == 'function' then
out[i] = {pcall(f, table.unpack(c[2]))}
else
out[i] = {false, 'No such function: ' .. c[1]}
end
end
return out";

/// `sim.getObject` and the like: names separated by dots.
fn is_function_name(func: &str) -> bool {
    !func.is_empty()
        && func
            .split('.')
            .all(|part| is_name(part) && !part.is_empty())
}

/// A Lua name: a letter or `_`, then letters, digits or `_`.
fn is_name(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Appends `value` as a Lua literal; `None` for what cannot be written.
fn write_value(out: &mut String, value: &Value) -> Option<()> {
    match value {
        Value::Integer(i) => out.push_str(&i128::from(*i).to_string()),
        Value::Float(f) if f.is_finite() => out.push_str(&format!("{f:?}")),
        Value::Text(t) => literal::write(out, t.as_bytes()),
        Value::Bytes(b) => literal::write(out, b),
        Value::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
        Value::Array(items) => {
            out.push('{');
            for (k, item) in items.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                write_value(out, item)?;
            }
            out.push('}');
        }
        Value::Map(pairs) if !pairs.is_empty() => {
            out.push('{');
            for (k, (key, item)) in pairs.iter().enumerate() {
                let key = key.as_text().filter(|k| is_name(k))?;
                if k > 0 {
                    out.push_str(", ");
                }
                out.push_str(key);
                out.push_str(" = ");
                write_value(out, item)?;
            }
            out.push('}');
        }
        _ => return None,
    }
    Some(())
}

/// The literal [`write_value`] put at the start of `text`, and the text after it. Text comes
/// back as text when it is UTF-8 (as the add-on decodes a CBOR text string into a Lua
/// string and a Lua string reads back as text).
fn read_value(text: &str) -> Option<(Value, &str)> {
    if text.starts_with('"') {
        let (bytes, rest) = literal::read(text)?;
        let value = match String::from_utf8(bytes) {
            Ok(t) => Value::Text(t),
            Err(e) => Value::Bytes(e.into_bytes()),
        };
        return Some((value, rest));
    }
    if let Some(rest) = text.strip_prefix('{') {
        return read_table(rest);
    }
    for (word, value) in [("true", true), ("false", false)] {
        if let Some(rest) = text.strip_prefix(word) {
            return Some((Value::Bool(value), rest));
        }
    }
    let end = text
        .find(|c: char| !(c.is_ascii_alphanumeric() || "+-.".contains(c)))
        .unwrap_or(text.len());
    let (number, rest) = text.split_at(end);
    let value = if number.contains(['.', 'e']) {
        Value::Float(number.parse().ok().filter(|f: &f64| f.is_finite())?)
    } else {
        Value::Integer(number.parse::<i64>().ok()?.into())
    };
    Some((value, rest))
}

/// The key of a map entry at the start of `text` (`name = `) and the text after ` = `. Looks
/// no further than the name, so reading a program stays linear in its length.
fn keyed_entry(text: &str) -> Option<(&str, &str)> {
    let end = text
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(text.len());
    let (key, rest) = text.split_at(end);
    Some((key, rest.strip_prefix(" = ")?)).filter(|_| is_name(key))
}

/// An array or a map, after its `{`.
fn read_table(text: &str) -> Option<(Value, &str)> {
    if let Some(rest) = text.strip_prefix('}') {
        return Some((Value::Array(vec![]), rest));
    }
    let keyed = keyed_entry(text).is_some();
    let (mut items, mut pairs) = (vec![], vec![]);
    let mut rest = text;
    loop {
        if keyed {
            let (key, after) = keyed_entry(rest)?;
            let (value, after) = read_value(after)?;
            pairs.push((Value::Text(key.to_string()), value));
            rest = after;
        } else {
            let (value, after) = read_value(rest)?;
            items.push(value);
            rest = after;
        }
        if let Some(after) = rest.strip_prefix(", ") {
            rest = after;
        } else {
            let rest = rest.strip_prefix('}')?;
            let table = if keyed {
                Value::Map(pairs)
            } else {
                Value::Array(items)
            };
            return Some((table, rest));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::zmq_api::cbor::{self, float_array, int};

    fn calls() -> Vec<(&'static str, Vec<Value>)> {
        vec![
            (
                "sim.getObject",
                vec![
                    Value::Text("/Maze/Line \"x\"".into()),
                    cbor::map([("noError", Value::Bool(true))]),
                ],
            ),
            ("sim.getObjectPose", vec![int(12), int(-1)]),
            (
                "sim.setObjectPose",
                vec![int(12), float_array(&[0.5, -1e-7, 2.0]), int(-1)],
            ),
            ("sim.getInt32Signal", vec![Value::Bytes(vec![0, 255, b'a'])]),
            ("sim.getSimulationState", vec![]),
            ("sim.getObjectsInTree", vec![Value::Array(vec![])]),
        ]
    }

    #[test]
    fn a_program_reads_back_as_the_calls_it_was_written_from() {
        let calls = calls();
        let code = calls_code(&calls).unwrap();
        assert!(code.is_ascii());
        let back = parse_calls(&code).unwrap();
        let back: Vec<(&str, Vec<Value>)> =
            back.iter().map(|(f, a)| (f.as_str(), a.clone())).collect();
        assert_eq!(back, calls);
        assert!(
            code.contains("{\"sim.getObjectPose\", {12, -1}},\n"),
            "{code}"
        );
        assert!(code.contains("{noError = true}"), "{code}");
    }

    #[test]
    fn what_cannot_be_written_is_refused_and_other_programs_do_not_parse() {
        for args in [
            vec![Value::Null],
            vec![Value::Float(f64::NAN)],
            vec![cbor::map([("not a name", int(1))])],
            vec![Value::Map(vec![(int(1), int(2))])],
        ] {
            assert_eq!(
                calls_code(&[("sim.getObject", args.clone())]),
                None,
                "{args:?}"
            );
        }
        assert_eq!(calls_code(&[("sim.get Object", vec![])]), None);
        let code = calls_code(&calls()).unwrap();
        for changed in [
            code.replace("pcall(f,", "f("),
            code.replace("{12, -1}", "{12, -1"),
            code.replace("noError = true", "noError = maybe"),
            "return 1".to_string(),
        ] {
            assert_eq!(parse_calls(&changed), None, "{changed}");
        }
    }

    #[test]
    fn answers_come_back_call_by_call() {
        let outcomes = vec![
            Ok(vec![int(7)]),
            Err("in sim.getObjectPose: object does not exist.".to_string()),
            Ok(vec![]),
        ];
        let reply = answer(outcomes.clone());
        assert_eq!(answers(&reply, 3), Some(outcomes));
        assert_eq!(answers(&reply, 2), None);
        let failed = [Value::Bool(false), Value::Text("compilation error".into())];
        assert_eq!(answers(&failed, 3), None);
    }
}
