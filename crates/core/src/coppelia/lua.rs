//! The one Lua program our ZeroMQ client asks CoppeliaSim to run (`sim.executeLuaCode`), and
//! how its answer is packed: every mesh of a list read back in one request.
//!
//! `sim.getShapeMesh` over the remote API costs its reply's encoding: on the real 4.10.0 a
//! mesh of 1,000 triangles answered in 32-36 ms (its reply carries normals), so the 47
//! meshes of a 50x50 wall maze took 1.55 s, against 40 ms for the same meshes read inside
//! the simulator and packed as binary strings (`sim.packFloatTable`, `sim.packInt32Table`)
//! in one `sim.executeLuaCode` (4.5.1: 175 ms, idle pass included; both builds have the
//! function; `docs/measurements.md`, "Meshes read back in one request"). The client writes
//! the program with [`read_meshes_code`]; the emulator, which runs no Lua, answers exactly
//! the programs [`parse_read_meshes`] recognises.

/// The program that reads the meshes `handles` and returns, per mesh, its vertices packed
/// as little-endian `f32` and its indices as little-endian `i32`: `{v1, i1, v2, i2, ...}`.
pub fn read_meshes_code(handles: &[i32]) -> String {
    let list: Vec<String> = handles.iter().map(i32::to_string).collect();
    format!("{READ_HEAD}{}{READ_TAIL}", list.join(","))
}

/// The handles of a program [`read_meshes_code`] wrote, `None` for any other program.
pub fn parse_read_meshes(code: &str) -> Option<Vec<i32>> {
    let list = code.strip_prefix(READ_HEAD)?.strip_suffix(READ_TAIL)?;
    if list.is_empty() {
        return Some(Vec::new());
    }
    list.split(',').map(|h| h.parse().ok()).collect()
}

/// `sim.packFloatTable`'s bytes: each number as a little-endian `f32`.
pub fn pack_floats(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// `sim.packInt32Table`'s bytes: each number as a little-endian `i32`.
pub fn pack_int32s(values: &[i32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// The numbers of a `sim.packFloatTable` string, `None` if its length is no multiple of 4.
pub fn unpack_floats(bytes: &[u8]) -> Option<Vec<f32>> {
    unpack(bytes, f32::from_le_bytes)
}

/// The numbers of a `sim.packInt32Table` string, `None` if its length is no multiple of 4.
pub fn unpack_int32s(bytes: &[u8]) -> Option<Vec<i32>> {
    unpack(bytes, i32::from_le_bytes)
}

fn unpack<T>(bytes: &[u8], from: fn([u8; 4]) -> T) -> Option<Vec<T>> {
    if !bytes.len().is_multiple_of(4) {
        return None;
    }
    Some(
        bytes
            .chunks_exact(4)
            .map(|c| from([c[0], c[1], c[2], c[3]]))
            .collect(),
    )
}

const READ_HEAD: &str = "local out = {} for _, h in ipairs({";
const READ_TAIL: &str = "}) do local v, i = sim.getShapeMesh(h) \
out[#out + 1] = sim.packFloatTable(v) out[#out + 1] = sim.packInt32Table(i) end return out";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_program_names_its_handles_and_nothing_else_parses() {
        let code = read_meshes_code(&[7, 12, -3]);
        assert_eq!(parse_read_meshes(&code), Some(vec![7, 12, -3]));
        assert_eq!(parse_read_meshes(&read_meshes_code(&[])), Some(vec![]));
        assert_eq!(parse_read_meshes("return 1 + 1"), None);
        assert_eq!(parse_read_meshes(&code.replace("12", "x")), None);
        assert_eq!(
            parse_read_meshes(&code.replace("packInt32", "packUInt8")),
            None
        );
    }

    #[test]
    fn packed_numbers_come_back_as_given() {
        let floats = [1.5f32, -25.475, 0.2];
        let bytes = pack_floats(&floats);
        // `sim.packFloatTable({1.5, 2})` on the real 4.5.1 answered 0000c03f 00000040
        assert_eq!(pack_floats(&[1.5, 2.0]), [0, 0, 0xc0, 0x3f, 0, 0, 0, 0x40]);
        assert_eq!(unpack_floats(&bytes).unwrap(), floats);
        assert_eq!(
            unpack_int32s(&pack_int32s(&[0, -1, 70000])).unwrap(),
            [0, -1, 70000]
        );
        assert_eq!(unpack_floats(&bytes[1..]), None);
    }
}
