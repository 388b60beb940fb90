//! Legacy remote API bytes: packets, the 18-byte message header and 26-byte command blocks.
//!
//! Everything is little-endian. Decoders never panic: malformed input is a [`WireError`].

use std::io::{Read, Write};

/// Default maximum packet size (header included).
pub const MAX_PACKET_SIZE: usize = 1300;
/// Packet header size: marker 1, payload length, packets left after this one (3 × u16).
const PACKET_HEADER_SIZE: usize = 6;
/// Message header size (`SIMX_HEADER_SIZE`).
const MESSAGE_HEADER_SIZE: usize = 18;
/// Command header size (`SIMX_SUBHEADER_SIZE`).
const BLOCK_HEADER_SIZE: usize = 26;
/// Protocol version (`SIMX_VERSION`).
const VERSION: u8 = 11;
/// Largest message we accept (a guard against garbage lengths).
const MAX_MESSAGE_SIZE: usize = 64 << 20;

/// Bits of a command block's `status` byte (spec §5.1, offset 24).
pub mod status {
    /// Request: keep this command beside stored ones of the same identity instead of
    /// replacing them (copy-paste uses it so that several copies in one message all happen).
    pub const DO_NOT_OVERWRITE: u8 = 0x01;
    /// Reply: the command failed on the server side.
    pub const REMOTE_ERROR: u8 = 0x01;
}

/// Bits of the server-state byte of a reply header (spec §4).
pub mod server_state {
    /// The simulation is not stopped (running or paused).
    pub const NOT_STOPPED: u8 = 0x01;
    /// The simulation is paused.
    pub const PAUSED: u8 = 0x02;
    /// Real-time simulation mode is on (never set by our server).
    pub const REAL_TIME: u8 = 0x04;
}

impl From<std::io::Error> for WireError {
    fn from(e: std::io::Error) -> WireError {
        WireError::Io(e)
    }
}

/// Malformed bytes or a failed transport.
#[derive(Debug, thiserror::Error)]
pub enum WireError {
    /// Socket error (includes timeouts as `WouldBlock`/`TimedOut`; printed in the message, so
    /// not a `source`).
    #[error("connection error: {0}")]
    Io(std::io::Error),
    /// A packet header that is not a little-endian legacy packet header.
    #[error(
        "bad packet header (marker {marker:#06x}, length {length}): not a legacy remote API peer?"
    )]
    BadPacket {
        /// First 16-bit word (must be 1).
        marker: u16,
        /// Announced payload length.
        length: u16,
    },
    /// Message shorter than its header.
    #[error("message of {0} bytes is shorter than the 18-byte header")]
    ShortMessage(usize),
    /// Unsupported protocol version.
    #[error("unsupported protocol version {0} (expected 11)")]
    BadVersion(u8),
    /// A command block with an impossible size or layout.
    #[error("bad command block at offset {offset}: {why}")]
    BadBlock {
        /// Offset of the block in the message.
        offset: usize,
        /// What is wrong.
        why: String,
    },
    /// A message larger than 64 MiB (a guard against garbage lengths).
    #[error("message too large ({0} bytes)")]
    TooLarge(usize),
}

/// The 18-byte message header.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MessageHeader {
    /// Message ID (client: counter from 0; server: ID of the latest client message before the
    /// pass that produced the results, or -1).
    pub message_id: i32,
    /// Client time in ms (26-bit), echoed by the server.
    pub client_time: i32,
    /// Server time in ms (server replies only).
    pub server_time: i32,
    /// Low 16 bits of the scene's unique ID (server replies only).
    pub scene_id: u16,
    /// Server state bits (see [`server_state`]): simulation not stopped, paused, real-time.
    pub server_state: u8,
}

/// One command block (request or reply).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Block {
    /// Raw command ID (low 16 bits) plus operation mode (high bits).
    pub cmd: u32,
    /// Streaming period / split size (requests), 0 in replies.
    pub delay: u16,
    /// Simulation time in ms (replies).
    pub sim_time: i32,
    /// Request: [`status::DO_NOT_OVERWRITE`]. Reply: [`status::REMOTE_ERROR`].
    pub status: u8,
    /// Identification data (part of the identity).
    pub id_data: Vec<u8>,
    /// Pure data (arguments or results).
    pub data: Vec<u8>,
    /// Full size when this block is one chunk of a split command, else `None`.
    pub split: Option<SplitInfo>,
}

/// Chunk information of a split command block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SplitInfo {
    /// Size of the complete command block.
    pub full_size: i32,
    /// Offset of this chunk inside the complete pure data.
    pub offset: i32,
}

impl Block {
    /// Raw command ID (operation mode removed).
    pub fn raw_id(&self) -> u16 {
        (self.cmd & 0xFFFF) as u16
    }

    /// Operation mode bits (`cmd - raw ID`).
    pub fn opmode(&self) -> u32 {
        self.cmd & 0xFFFF_0000
    }

    /// The identity of a command: raw ID and identification data. The server's input list
    /// keeps one command per identity (unless told not to overwrite), and a client matches
    /// replies to requests by it.
    pub fn identity(&self) -> (u16, Vec<u8>) {
        (self.raw_id(), self.id_data.clone())
    }

    /// Encoded size in bytes.
    pub fn encoded_len(&self) -> usize {
        BLOCK_HEADER_SIZE + self.id_data.len() + self.data.len()
    }

    /// Appends the encoded block.
    fn encode_into(&self, out: &mut Vec<u8>) {
        let mem = self.encoded_len() as i32;
        let (full, off1) = match self.split {
            Some(s) => (s.full_size, s.offset),
            None => (mem, 0),
        };
        out.extend_from_slice(&mem.to_le_bytes());
        out.extend_from_slice(&full.to_le_bytes());
        out.extend_from_slice(&(self.id_data.len() as u16).to_le_bytes());
        out.extend_from_slice(&off1.to_le_bytes());
        out.extend_from_slice(&self.cmd.to_le_bytes());
        out.extend_from_slice(&self.delay.to_le_bytes());
        out.extend_from_slice(&self.sim_time.to_le_bytes());
        out.push(self.status);
        out.push(0);
        out.extend_from_slice(&self.id_data);
        out.extend_from_slice(&self.data);
    }
}

/// Length of the identification data of a command, from its raw ID's class (as both the C
/// client and the server compute it; `pdata_offset0` is not trusted).
fn id_data_len(raw_id: u16, rest: &[u8]) -> Result<usize, String> {
    let cstr = |from: usize| -> Result<usize, String> {
        rest.get(from..)
            .and_then(|r| r.iter().position(|&b| b == 0))
            .map(|n| n + 1)
            .ok_or_else(|| "string identification data without NUL terminator".to_string())
    };
    let need = |n: usize| {
        if rest.len() >= n {
            Ok(n)
        } else {
            Err(format!("needs {n} bytes of identification data"))
        }
    };
    match raw_id {
        0x0000..=0x0FFF => Ok(0),
        0x1000..=0x1FFF => need(4),
        0x2000..=0x2FFF => need(8),
        0x3000..=0x33FF => cstr(0),
        0x3400..=0x34FF => {
            need(4)?;
            let a = cstr(4)?;
            let b = cstr(4 + a)?;
            Ok(4 + a + b)
        }
        _ => Err(format!("command ID {raw_id:#06x} is in a reserved range")),
    }
}

/// A whole message.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Message {
    /// The 18-byte header (IDs, times, server state).
    pub header: MessageHeader,
    /// Command blocks in order.
    pub blocks: Vec<Block>,
}

impl Message {
    /// Encodes header and blocks (CRC 0, version 11).
    pub fn encode(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(
            MESSAGE_HEADER_SIZE + self.blocks.iter().map(Block::encoded_len).sum::<usize>(),
        );
        out.extend_from_slice(&0u16.to_le_bytes());
        out.push(VERSION);
        out.extend_from_slice(&self.header.message_id.to_le_bytes());
        out.extend_from_slice(&self.header.client_time.to_le_bytes());
        out.extend_from_slice(&self.header.server_time.to_le_bytes());
        out.extend_from_slice(&self.header.scene_id.to_le_bytes());
        out.push(self.header.server_state);
        for b in &self.blocks {
            b.encode_into(&mut out);
        }
        out
    }

    /// Decodes a message (header + blocks).
    pub fn decode(bytes: &[u8]) -> Result<Message, WireError> {
        if bytes.len() < MESSAGE_HEADER_SIZE {
            return Err(WireError::ShortMessage(bytes.len()));
        }
        if bytes[2] != VERSION {
            return Err(WireError::BadVersion(bytes[2]));
        }
        let header = MessageHeader {
            message_id: i32_at(bytes, 3),
            client_time: i32_at(bytes, 7),
            server_time: i32_at(bytes, 11),
            scene_id: u16::from_le_bytes([bytes[15], bytes[16]]),
            server_state: bytes[17],
        };
        let mut blocks = Vec::new();
        let mut off = MESSAGE_HEADER_SIZE;
        while off < bytes.len() {
            let bad = |why: String| WireError::BadBlock { offset: off, why };
            let rest = &bytes[off..];
            if rest.len() < BLOCK_HEADER_SIZE {
                return Err(bad(format!(
                    "{} trailing bytes, less than a 26-byte command header",
                    rest.len()
                )));
            }
            let mem = i32_at(rest, 0);
            let full = i32_at(rest, 4);
            if mem < BLOCK_HEADER_SIZE as i32 || mem as usize > rest.len() {
                return Err(bad(format!("block size {mem} outside 26..={}", rest.len())));
            }
            let mem = mem as usize;
            let off1 = i32_at(rest, 10);
            let cmd = u32::from_le_bytes([rest[14], rest[15], rest[16], rest[17]]);
            let body = &rest[BLOCK_HEADER_SIZE..mem];
            let idn = id_data_len((cmd & 0xFFFF) as u16, body).map_err(bad)?;
            let split = if full as usize != mem || off1 != 0 {
                if full < mem as i32 || off1 < 0 {
                    return Err(bad(format!(
                        "split chunk with full size {full}, offset {off1}"
                    )));
                }
                Some(SplitInfo {
                    full_size: full,
                    offset: off1,
                })
            } else {
                None
            };
            blocks.push(Block {
                cmd,
                delay: u16::from_le_bytes([rest[18], rest[19]]),
                sim_time: i32_at(rest, 20),
                status: rest[24],
                id_data: body[..idn].to_vec(),
                data: body[idn..].to_vec(),
                split,
            });
            off += mem;
        }
        Ok(Message { header, blocks })
    }
}

fn i32_at(b: &[u8], at: usize) -> i32 {
    i32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// Splits a message into packets of at most `max_packet` bytes (all but the last full-sized,
/// as the C client's receive buffer requires) and writes them, one write per packet.
pub fn write_message(
    w: &mut impl Write,
    message: &[u8],
    max_packet: usize,
) -> Result<(), WireError> {
    let chunk = max_packet.saturating_sub(PACKET_HEADER_SIZE).max(1);
    let count = message.len().div_ceil(chunk).max(1);
    let mut packet = Vec::with_capacity(max_packet);
    for (i, part) in message.chunks(chunk).enumerate() {
        packet.clear();
        packet.extend_from_slice(&1u16.to_le_bytes());
        packet.extend_from_slice(&(part.len() as u16).to_le_bytes());
        packet.extend_from_slice(&((count - 1 - i) as u16).to_le_bytes());
        packet.extend_from_slice(part);
        w.write_all(&packet)?;
    }
    w.flush()?;
    Ok(())
}

/// Encodes a message into packet bytes (what [`write_message`] writes).
pub fn packetize(message: &[u8], max_packet: usize) -> Vec<u8> {
    let mut out = Vec::new();
    write_message(&mut out, message, max_packet).expect("writing to a Vec cannot fail");
    out
}

/// Reads packets until the last one of a message and returns the message bytes.
pub fn read_message(r: &mut impl Read) -> Result<Vec<u8>, WireError> {
    let mut message = Vec::new();
    loop {
        let mut h = [0u8; PACKET_HEADER_SIZE];
        r.read_exact(&mut h)?;
        let marker = u16::from_le_bytes([h[0], h[1]]);
        let length = u16::from_le_bytes([h[2], h[3]]);
        let left = u16::from_le_bytes([h[4], h[5]]);
        if marker != 1 || length == 0 || length as usize > 30_000 {
            return Err(WireError::BadPacket { marker, length });
        }
        let start = message.len();
        if start + length as usize > MAX_MESSAGE_SIZE {
            return Err(WireError::TooLarge(start + length as usize));
        }
        message.resize(start + length as usize, 0);
        r.read_exact(&mut message[start..])?;
        if left == 0 {
            return Ok(message);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Decodes a byte stream of packets into messages.
    fn decode_stream(mut bytes: &[u8]) -> Result<Vec<Message>, WireError> {
        let mut out = Vec::new();
        while !bytes.is_empty() {
            out.push(Message::decode(&read_message(&mut bytes)?)?);
        }
        Ok(out)
    }

    fn hex(s: &str) -> Vec<u8> {
        s.split_whitespace()
            .map(|b| u8::from_str_radix(b, 16).unwrap())
            .collect()
    }

    fn request(cmd: u32, id: &[u8], data: &[u8]) -> Block {
        Block {
            cmd,
            delay: 0,
            sim_time: 0,
            status: 0,
            id_data: id.to_vec(),
            data: data.to_vec(),
            split: None,
        }
    }

    fn msg(id: i32, time: i32, blocks: Vec<Block>) -> Message {
        Message {
            header: MessageHeader {
                message_id: id,
                client_time: time,
                ..Default::default()
            },
            blocks,
        }
    }

    /// Spec section 13: keep-alive.
    #[test]
    fn vector_keep_alive() {
        let bytes = packetize(&msg(0, 1000, vec![]).encode(), MAX_PACKET_SIZE);
        assert_eq!(
            bytes,
            hex("01 00 12 00 00 00 00 00 0b 00 00 00 00 e8 03 00 00 00 00 00 00 00 00 00")
        );
    }

    /// Spec section 13: get handle of "Floor" and its reply.
    #[test]
    fn vector_get_object_handle() {
        let req = msg(7, 0x12345, vec![request(0x0001_3001, b"Floor\0", &[])]);
        let want = hex(
            "01 00 32 00 00 00 00 00 0b 07 00 00 00 45 23 01 00 00 00 00 00 00 00 00 20 00 00 00 20 00 00 00
             06 00 00 00 00 00 01 30 01 00 00 00 00 00 00 00 00 00 46 6c 6f 6f 72 00",
        );
        assert_eq!(packetize(&req.encode(), MAX_PACKET_SIZE), want);
        assert_eq!(decode_stream(&want).unwrap(), vec![req]);
        let reply = hex(
            "01 00 36 00 00 00 00 00 0b 07 00 00 00 45 23 01 00 88 13 00 00 03 00 00 24 00 00 00 24 00 00 00
             06 00 00 00 00 00 01 30 01 00 00 00 00 00 00 00 00 00 46 6c 6f 6f 72 00 10 00 00 00",
        );
        let m = &decode_stream(&reply).unwrap()[0];
        assert_eq!(
            m.header,
            MessageHeader {
                message_id: 7,
                client_time: 0x12345,
                server_time: 5000,
                scene_id: 3,
                server_state: 0
            }
        );
        assert_eq!(m.blocks[0].data, 16i32.to_le_bytes());
        assert_eq!(packetize(&m.encode(), MAX_PACKET_SIZE), reply);
    }

    /// Spec section 13: set position (oneshot) and get position (streaming + 100 ms).
    #[test]
    fn vector_positions() {
        let mut data = (-1i32).to_le_bytes().to_vec();
        for v in [0.1f32, 0.2, 0.3] {
            data.extend_from_slice(&v.to_le_bytes());
        }
        let set = msg(
            8,
            0x12350,
            vec![request(0x101B, &16i32.to_le_bytes(), &data)],
        );
        let want = hex(
            "01 00 40 00 00 00 00 00 0b 08 00 00 00 50 23 01 00 00 00 00 00 00 00 00 2e 00 00 00 2e 00 00 00
             04 00 00 00 00 00 1b 10 00 00 00 00 00 00 00 00 00 00 10 00 00 00 ff ff ff ff cd cc cc 3d cd cc
             4c 3e 9a 99 99 3e",
        );
        assert_eq!(packetize(&set.encode(), MAX_PACKET_SIZE), want);
        let mut id = 16i32.to_le_bytes().to_vec();
        id.extend_from_slice(&(-1i32).to_le_bytes());
        let mut get = request(0x0002_200E, &id, &[]);
        get.delay = 100;
        let want = hex(
            "01 00 34 00 00 00 00 00 0b 09 00 00 00 55 23 01 00 00 00 00 00 00 00 00 22 00 00 00 22 00 00 00
             08 00 00 00 00 00 0e 20 02 00 64 00 00 00 00 00 00 00 10 00 00 00 ff ff ff ff",
        );
        assert_eq!(
            packetize(
                &msg(9, 0x12355, vec![get.clone()]).encode(),
                MAX_PACKET_SIZE
            ),
            want
        );
        assert_eq!(decode_stream(&want).unwrap()[0].blocks[0], get);
    }

    #[test]
    fn large_message_splits_into_full_packets() {
        let blocks = (0..200)
            .map(|i: i32| request(0x101B, &i.to_le_bytes(), &[0u8; 16]))
            .collect();
        let m = msg(3, 1, blocks);
        let bytes = packetize(&m.encode(), MAX_PACKET_SIZE);
        let mut rest = &bytes[..];
        let mut sizes = vec![];
        while !rest.is_empty() {
            let len = u16::from_le_bytes([rest[2], rest[3]]) as usize;
            sizes.push(len);
            rest = &rest[6 + len..];
        }
        assert!(sizes[..sizes.len() - 1].iter().all(|&s| s == 1294));
        assert_eq!(decode_stream(&bytes).unwrap(), vec![m]);
    }

    #[test]
    fn kill_block_has_int_payload_as_pure_data() {
        let kill = hex(
            "1e 00 00 00 1e 00 00 00 04 00 00 00 00 00 0a 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00",
        );
        let mut bytes = msg(1, 0, vec![]).encode();
        bytes.extend_from_slice(&kill);
        let m = Message::decode(&bytes).unwrap();
        assert_eq!(m.blocks[0].raw_id(), 0x000A);
        assert!(m.blocks[0].id_data.is_empty());
        assert_eq!(m.blocks[0].data, [0, 0, 0, 0]);
    }

    #[test]
    fn garbage_is_an_error() {
        assert!(matches!(
            decode_stream(b"HTTP/1.1 200 OK\r\n"),
            Err(WireError::BadPacket { .. })
        ));
        assert!(matches!(
            Message::decode(&[0; 5]),
            Err(WireError::ShortMessage(5))
        ));
        let mut m = msg(1, 0, vec![]).encode();
        m.extend_from_slice(&[0xff; 30]);
        assert!(matches!(
            Message::decode(&m),
            Err(WireError::BadBlock { .. })
        ));
        let mut m = msg(1, 0, vec![]).encode();
        m[2] = 3;
        assert!(matches!(Message::decode(&m), Err(WireError::BadVersion(3))));
    }

    proptest! {
        #[test]
        fn decoders_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
            let _ = decode_stream(&bytes);
            let _ = Message::decode(&bytes);
        }

        #[test]
        fn decoders_never_panic_on_mutated_messages(flips in proptest::collection::vec((0usize..120, any::<u8>()), 1..6)) {
            let mut bytes = msg(5, 9, vec![
                request(0x3001, b"Line\0", &[]),
                request(0x200C, &[109, 0, 0, 0, 2, 0, 0, 0], &[]),
                request(0x3401, b"\x01\0\0\0a\0b\0", &[1, 2]),
            ]).encode();
            for (at, v) in flips {
                let n = bytes.len();
                bytes[at % n] = v;
            }
            let _ = Message::decode(&bytes);
        }

        #[test]
        fn encode_decode_round_trip(id in any::<i32>(), handle in any::<i32>(), data in proptest::collection::vec(any::<u8>(), 0..3000)) {
            let m = msg(id, 7, vec![request(0x101B, &handle.to_le_bytes(), &data), request(0x3001, b"x\0", &[])]);
            let bytes = packetize(&m.encode(), MAX_PACKET_SIZE);
            prop_assert_eq!(decode_stream(&bytes).unwrap(), vec![m]);
        }
    }
}
