//! The request and reply maps of both protocol generations (see `zmq-remote-api.md`).
//!
//! Protocol 1 (CoppeliaSim 4.3 to 4.5): `{func, args}` → `{success, ret}` or
//! `{success: false, error}`. Protocol 2 (4.6 on): `{func, args, uuid, ver, lang, argsL}` →
//! `{ret}`, `{err}`, or a server-initiated `{func: "_*wait*_" | "_*repeat*_" | callback, args}`.

use ciborium::Value;

use super::cbor::{self, CborError};

/// `func` of the answer to a wait or a callback.
pub const EXECUTED: &str = "_*executed*_";
/// `func` of a server asking the client to confirm and read again.
pub const WAIT: &str = "_*wait*_";
/// `func` of a server asking the client to resend its request.
pub const REPEAT: &str = "_*repeat*_";
/// `func` of a client saying goodbye.
pub const END: &str = "_*end*_";
/// The protocol-2 server's answer to a request without `uuid` (an older client).
pub const VERSION_MISMATCH: &str =
    "The client ZeroMQ remote API version does not match CoppeliaSim's version";

/// A protocol generation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Protocol {
    /// CoppeliaSim 4.3 to 4.5.1: `{success, ret | error}` replies, no uuid, no wait loop.
    V1,
    /// CoppeliaSim 4.6 and later: `{ret | err | func}` replies, uuid required.
    V2,
}

impl std::fmt::Display for Protocol {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Protocol::V1 => "1",
            Protocol::V2 => "2",
        })
    }
}

/// A request as a client sends it.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// Dotted function name, e.g. `sim.getObject`, or a reserved `_*...*_` value.
    pub func: String,
    /// Positional arguments.
    pub args: Vec<Value>,
    /// Client id (protocol 2).
    pub uuid: Option<String>,
    /// `ver`, `lang`, `timeout` fields (the Python client sends them on its first request only).
    pub ver: Option<i64>,
    /// Client language tag.
    pub lang: Option<String>,
    /// Argument count (protocol 2; lets the server keep trailing nils).
    pub args_len: Option<usize>,
}

impl Request {
    /// A protocol-2 request with every field (what our client always sends).
    pub fn v2(func: &str, args: Vec<Value>, uuid: &str) -> Request {
        Request {
            func: func.to_string(),
            args_len: Some(args.len()),
            args,
            uuid: Some(uuid.to_string()),
            ver: Some(2),
            lang: Some("rust".into()),
        }
    }

    /// A protocol-1 request: just `func` and `args`.
    pub fn v1(func: &str, args: Vec<Value>) -> Request {
        Request {
            func: func.to_string(),
            args,
            uuid: None,
            ver: None,
            lang: None,
            args_len: None,
        }
    }

    /// The CBOR map.
    pub fn to_value(&self) -> Value {
        let mut pairs = vec![
            ("func", Value::Text(self.func.clone())),
            ("args", Value::Array(self.args.clone())),
        ];
        if let Some(u) = &self.uuid {
            pairs.push(("uuid", Value::Text(u.clone())));
        }
        if let Some(v) = self.ver {
            pairs.push(("ver", cbor::int(v)));
        }
        if let Some(l) = &self.lang {
            pairs.push(("lang", Value::Text(l.clone())));
        }
        if let Some(n) = self.args_len {
            pairs.push(("argsL", cbor::int(n as i64)));
        }
        cbor::map(pairs)
    }

    /// Encoded bytes.
    pub fn encode(&self) -> Vec<u8> {
        cbor::encode(&self.to_value())
    }

    /// Parses a request map (server side). `args` may be missing (= empty), an array, or an
    /// empty map; `argsL` longer than `args` pads with nils.
    pub fn from_value(value: &Value) -> Result<Request, CborError> {
        if !matches!(value, Value::Map(_)) {
            return Err(CborError(format!(
                "request is not a map: {}",
                cbor::describe(value)
            )));
        }
        let func = cbor::get(value, "func")
            .and_then(cbor::text)
            .ok_or_else(|| CborError("request without a text 'func'".into()))?
            .to_string();
        let mut args = match cbor::get(value, "args") {
            None | Some(Value::Null) => vec![],
            Some(a) => cbor::array(a)
                .ok_or_else(|| CborError(format!("'args' is not an array: {}", cbor::describe(a))))?
                .to_vec(),
        };
        let args_len = cbor::get(value, "argsL")
            .and_then(cbor::integer)
            .and_then(|n| usize::try_from(n).ok());
        if let Some(n) = args_len
            && n > args.len()
            && n <= 4096
        {
            args.resize(n, Value::Null);
        }
        Ok(Request {
            func,
            args,
            uuid: cbor::get(value, "uuid")
                .and_then(cbor::text)
                .map(str::to_string),
            ver: cbor::get(value, "ver").and_then(cbor::integer),
            lang: cbor::get(value, "lang")
                .and_then(cbor::text)
                .map(str::to_string),
            args_len,
        })
    }
}

/// A reply, as the client loop sees it.
#[derive(Debug, Clone, PartialEq)]
pub enum Reply {
    /// Success with the function's return values (empty for none).
    Ret(Vec<Value>),
    /// The function failed; the message has `_=NL=_` / `_=TB=_` decoded.
    Err(String),
    /// `_*wait*_`: confirm with `_*executed*_` and read again.
    Wait,
    /// `_*repeat*_`: resend the original request.
    Repeat,
    /// A callback the server wants run (we register none).
    Callback(String),
}

/// Turns the server's newline/tab tokens back into characters.
pub fn demangle(message: &str) -> String {
    message.replace("_=NL=_", "\n").replace("_=TB=_", "\t")
}

/// Replaces newlines and tabs with the server's tokens (what the Lua server does).
pub fn mangle(message: &str) -> String {
    message.replace('\n', "_=NL=_").replace('\t', "_=TB=_")
}

/// The return values of `ret`: an array, an empty map (Lua's empty table), or a map with
/// integer keys 1..n (a Lua table with holes).
fn ret_values(ret: &Value) -> Result<Vec<Value>, CborError> {
    if let Some(items) = cbor::array(ret) {
        return Ok(items.to_vec());
    }
    if let Value::Map(pairs) = ret {
        let mut indexed = Vec::with_capacity(pairs.len());
        for (k, v) in pairs {
            match cbor::integer(k) {
                Some(i) if (1..=4096).contains(&i) => indexed.push((i as usize, v.clone())),
                _ => {
                    return Err(CborError(format!(
                        "'ret' is a map with key {}",
                        cbor::describe(k)
                    )));
                }
            }
        }
        let n = indexed.iter().map(|(i, _)| *i).max().unwrap_or(0);
        let mut out = vec![Value::Null; n];
        for (i, v) in indexed {
            out[i - 1] = v;
        }
        return Ok(out);
    }
    Err(CborError(format!(
        "'ret' is neither an array nor a map: {}",
        cbor::describe(ret)
    )))
}

fn error_text(v: Option<&Value>) -> String {
    match v {
        Some(v) => match cbor::text(v) {
            Some(t) => demangle(t),
            None => cbor::describe(v),
        },
        None => "unknown error (no message)".into(),
    }
}

/// Parses a reply map; also returns the protocol generation the reply's shape reveals.
pub fn parse_reply(value: &Value) -> Result<(Reply, Protocol), CborError> {
    if !matches!(value, Value::Map(_)) {
        return Err(CborError(format!(
            "reply is not a map: {}",
            cbor::describe(value)
        )));
    }
    if let Some(success) = cbor::get(value, "success") {
        let ok =
            cbor::boolean(success).ok_or_else(|| CborError("'success' is not a boolean".into()))?;
        let reply = if ok {
            Reply::Ret(
                cbor::get(value, "ret")
                    .map(ret_values)
                    .transpose()?
                    .unwrap_or_default(),
            )
        } else {
            Reply::Err(error_text(
                cbor::get(value, "error").or_else(|| cbor::get(value, "err")),
            ))
        };
        return Ok((reply, Protocol::V1));
    }
    if let Some(err) = cbor::get(value, "err") {
        return Ok((Reply::Err(error_text(Some(err))), Protocol::V2));
    }
    if let Some(ret) = cbor::get(value, "ret") {
        return Ok((Reply::Ret(ret_values(ret)?), Protocol::V2));
    }
    if let Some(func) = cbor::get(value, "func") {
        let f = cbor::text(func)
            .ok_or_else(|| CborError("'func' of a reply is not a string".into()))?;
        let reply = match f {
            WAIT => Reply::Wait,
            REPEAT => Reply::Repeat,
            other => Reply::Callback(other.to_string()),
        };
        return Ok((reply, Protocol::V2));
    }
    Err(CborError(format!(
        "reply has none of ret, err, success, func: {}",
        cbor::describe(value)
    )))
}

/// A success reply in the given protocol. Lua's empty table is encoded as an empty map.
pub fn ret_reply(protocol: Protocol, values: Vec<Value>) -> Value {
    let ret = if values.is_empty() {
        Value::Map(vec![])
    } else {
        Value::Array(values)
    };
    match protocol {
        Protocol::V1 => cbor::map([("success", Value::Bool(true)), ("ret", ret)]),
        Protocol::V2 => cbor::map([("ret", ret)]),
    }
}

/// An error reply in the given protocol (newlines and tabs mangled as the Lua server does).
pub fn err_reply(protocol: Protocol, message: &str) -> Value {
    let m = Value::Text(mangle(message));
    match protocol {
        Protocol::V1 => cbor::map([("success", Value::Bool(false)), ("error", m)]),
        Protocol::V2 => cbor::map([("err", m)]),
    }
}

/// A server-initiated `{func, args: []}` (wait or repeat).
pub fn func_reply(func: &str) -> Value {
    cbor::map([
        ("func", Value::Text(func.into())),
        ("args", Value::Array(vec![])),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn request_matches_the_spec_vector() {
        let uuid = "8a7e3cf4-0000-4000-8000-000000000000";
        let r = Request::v2("sim.getInt32Param", vec![cbor::int(26)], uuid);
        let mut want = vec![0xa6, 0x64];
        want.extend(b"func");
        want.push(0x71);
        want.extend(b"sim.getInt32Param");
        want.push(0x64);
        want.extend(b"args");
        want.extend([0x81, 0x18, 0x1a, 0x64]);
        want.extend(b"uuid");
        want.extend([0x78, 0x24]);
        want.extend(uuid.as_bytes());
        want.push(0x63);
        want.extend(b"ver");
        want.extend([0x02, 0x64]);
        want.extend(b"lang");
        want.push(0x64);
        want.extend(b"rust");
        want.push(0x65);
        want.extend(b"argsL");
        want.push(0x01);
        assert_eq!(r.encode(), want);
        assert_eq!(
            Request::from_value(&cbor::decode(&want).unwrap()).unwrap(),
            r
        );
    }

    #[test]
    fn replies_of_both_generations() {
        let v2 = |v: Value| parse_reply(&v).unwrap();
        assert_eq!(
            v2(cbor::map([("ret", Value::Map(vec![]))])),
            (Reply::Ret(vec![]), Protocol::V2)
        );
        assert_eq!(
            v2(cbor::map([("ret", Value::Array(vec![cbor::int(7)]))])).0,
            Reply::Ret(vec![cbor::int(7)])
        );
        assert_eq!(
            v2(cbor::map([("err", Value::Text("a_=NL=_b_=TB=_c".into()))])).0,
            Reply::Err("a\nb\tc".into())
        );
        assert_eq!(
            v2(cbor::map([
                ("success", Value::Bool(false)),
                ("error", Value::Bytes(b"No such function: sim.x".to_vec()))
            ])),
            (Reply::Err("No such function: sim.x".into()), Protocol::V1)
        );
        assert_eq!(v2(func_reply(WAIT)).0, Reply::Wait);
        assert_eq!(v2(func_reply(REPEAT)).0, Reply::Repeat);
        let holes = cbor::map([("ret", Value::Map(vec![(cbor::int(2), cbor::int(5))]))]);
        assert_eq!(v2(holes).0, Reply::Ret(vec![Value::Null, cbor::int(5)]));
        assert!(parse_reply(&cbor::map([("ret", Value::Text("x".into()))])).is_err());
        assert!(parse_reply(&cbor::int(3)).is_err());
        assert!(parse_reply(&cbor::map([])).is_err());
    }

    #[test]
    fn args_len_pads_trailing_nils() {
        let v = cbor::map([
            ("func", Value::Text("f".into())),
            ("args", Value::Array(vec![])),
            ("argsL", cbor::int(2)),
        ]);
        assert_eq!(
            Request::from_value(&v).unwrap().args,
            vec![Value::Null, Value::Null]
        );
    }
}

#[cfg(test)]
mod fuzz {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Any bytes: decoding and reply parsing return a result, never panic.
        #[test]
        fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..256)) {
            if let Ok(v) = cbor::decode(&bytes) {
                let _ = parse_reply(&v);
                let _ = Request::from_value(&v);
            }
        }

        /// Valid maps with a random `ret`/`err`/`success` payload: parsed or rejected, never a panic.
        #[test]
        fn arbitrary_reply_maps_never_panic(key in "(ret|err|success|func|error)", n in any::<i64>(), s in ".{0,20}") {
            for payload in [Value::Integer(n.into()), Value::Text(s.clone()), Value::Array(vec![Value::Text(s.clone())]),
                            Value::Map(vec![(Value::Integer(n.into()), Value::Null)]), Value::Bool(n % 2 == 0)] {
                let _ = parse_reply(&cbor::map([(key.as_str(), payload)]));
            }
        }
    }
}
