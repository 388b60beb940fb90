//! The Lua programs our ZeroMQ client asks CoppeliaSim to run (`sim.executeLuaCode`, which
//! both real builds have), and how their data is packed: [`read`] reads every mesh of a list
//! back in one request, [`create`] makes and dresses a batch of meshes in one request. The
//! emulator runs no Lua: it answers exactly the programs these modules write and parse.
//!
//! Both programs move mesh data as binary strings (`sim.packFloatTable`,
//! `sim.unpackInt32Table`, ...), which the simulator turns into tables in C, rather than as
//! CBOR arrays, which its add-on decodes item by item in Lua ([`literal`] writes them into a
//! program's text).

pub mod create;
pub mod literal;
pub mod read;

pub use create::{CreateMeshes, LuaMesh, create_meshes_code, parse_create_meshes};
pub use read::{
    DRESSED_ENTRIES, parse_read_dressed, parse_read_meshes, read_dressed_code, read_meshes_code,
};

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

#[cfg(test)]
mod tests {
    use super::*;

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
