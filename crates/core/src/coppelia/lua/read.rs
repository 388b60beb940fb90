//! The program that reads every mesh of a list back in one request, and its answer's packing.
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

/// The program that reads the meshes `handles` as [`read_meshes_code`] does and, per mesh,
/// what a person sees of it: `{v1, i1, pose1, colour1, layer1, v2, ...}`, the pose as
/// `sim.getObjectPose(h, -1)` gives it (world, x y z qx qy qz qw), the ambient-diffuse colour
/// as `sim.getShapeColor(h, "", 0)` and the visibility layer as
/// `sim.getObjectInt32Param(h, 10)` (both real builds answered these inside one program,
/// `docs/measurements.md`, "Kept meshes read back in one request").
pub fn read_dressed_code(handles: &[i32]) -> String {
    let list: Vec<String> = handles.iter().map(i32::to_string).collect();
    format!("{READ_HEAD}{}{DRESSED_TAIL}", list.join(","))
}

/// The handles of a program [`read_dressed_code`] wrote, `None` for any other program.
pub fn parse_read_dressed(code: &str) -> Option<Vec<i32>> {
    let list = code.strip_prefix(READ_HEAD)?.strip_suffix(DRESSED_TAIL)?;
    if list.is_empty() {
        return Some(Vec::new());
    }
    list.split(',').map(|h| h.parse().ok()).collect()
}

/// Entries per mesh in a [`read_dressed_code`] answer.
pub const DRESSED_ENTRIES: usize = 5;

const DRESSED_TAIL: &str = "}) do local v, i = sim.getShapeMesh(h) local _, c = sim.getShapeColor(h, '', 0) \
out[#out + 1] = sim.packFloatTable(v) out[#out + 1] = sim.packInt32Table(i) \
out[#out + 1] = sim.getObjectPose(h, -1) out[#out + 1] = c \
out[#out + 1] = sim.getObjectInt32Param(h, 10) end return out";

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
        let dressed = read_dressed_code(&[7, 12]);
        assert_eq!(parse_read_dressed(&dressed), Some(vec![7, 12]));
        assert_eq!(parse_read_meshes(&dressed), None);
        assert_eq!(parse_read_dressed(&code), None);
    }
}
