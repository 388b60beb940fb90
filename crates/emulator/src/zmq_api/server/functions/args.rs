//! Positional arguments of one call, read with CoppeliaSim-like error texts
//! (`in sim.getObject: argument 1 is not correct (expected a string).`).

use ciborium::Value;

use crate::zmq_api::cbor;

/// What every "the handle names no object" error ends with.
const NO_OBJECT: &str = "object does not exist.";

/// One call's function name (full and dotted, for error texts) and its arguments. A CBOR null
/// counts as a missing argument, as Lua's `nil` does.
pub(super) struct Args<'a> {
    /// The full dotted name, e.g. `sim.getObject`.
    pub(super) func: &'a str,
    args: &'a [Value],
}

impl<'a> Args<'a> {
    /// Wraps the arguments of a call to `func`.
    pub(super) fn new(func: &'a str, args: &'a [Value]) -> Self {
        Args { func, args }
    }

    /// The error for argument `i` (0-based) not being `what`.
    pub(super) fn bad(&self, i: usize, what: &str) -> String {
        format!(
            "in {}: argument {} is not correct (expected {what}).",
            self.func,
            i + 1
        )
    }

    /// The error for a handle that names no object.
    pub(super) fn no_object(&self) -> String {
        format!("in {}: {NO_OBJECT}", self.func)
    }

    /// Argument `i`, unless missing or null.
    pub(super) fn get(&self, i: usize) -> Option<&'a Value> {
        self.args.get(i).filter(|v| !matches!(v, Value::Null))
    }

    /// Argument `i` as a 32-bit integer.
    pub(super) fn int(&self, i: usize) -> Result<i32, String> {
        self.get(i)
            .and_then(cbor::int32)
            .ok_or_else(|| self.bad(i, "an integer"))
    }

    /// Argument `i` as a 32-bit integer, `default` when missing.
    pub(super) fn int_or(&self, i: usize, default: i32) -> Result<i32, String> {
        if self.get(i).is_none() {
            Ok(default)
        } else {
            self.int(i)
        }
    }

    /// Argument `i` as a string.
    pub(super) fn text(&self, i: usize) -> Result<&'a str, String> {
        self.get(i)
            .and_then(cbor::text)
            .ok_or_else(|| self.bad(i, "a string"))
    }

    /// Argument `i` as a table of 3 numbers (a position, Euler angles, a size, a colour).
    pub(super) fn vec3(&self, i: usize) -> Result<[f64; 3], String> {
        self.get(i)
            .and_then(cbor::numbers::<3>)
            .ok_or_else(|| self.bad(i, "a table of 3 numbers"))
    }

    /// Argument `i` as a table of object handles.
    pub(super) fn handles(&self, i: usize) -> Result<Vec<i32>, String> {
        self.get(i)
            .and_then(cbor::handles)
            .ok_or_else(|| self.bad(i, "a table of handles"))
    }

    /// Argument `i` as a table of numbers (a mesh's vertices), each as `f32`.
    pub(super) fn floats(&self, i: usize) -> Result<Vec<f32>, String> {
        self.get(i)
            .and_then(cbor::array)
            .and_then(|v| {
                v.iter()
                    .map(|x| cbor::number(x).map(|f| f as f32))
                    .collect()
            })
            .ok_or_else(|| self.bad(i, "a table of numbers"))
    }

    /// Argument `i` as a table of 32-bit integers (a mesh's indices).
    pub(super) fn ints(&self, i: usize) -> Result<Vec<i32>, String> {
        self.get(i)
            .and_then(cbor::array)
            .and_then(|v| v.iter().map(cbor::int32).collect())
            .ok_or_else(|| self.bad(i, "a table of integers"))
    }

    /// Whether argument `i` is a table (tells the 4.6+ argument order from the 4.5 one).
    pub(super) fn is_table(&self, i: usize) -> bool {
        matches!(self.get(i), Some(Value::Array(_)))
    }
}
