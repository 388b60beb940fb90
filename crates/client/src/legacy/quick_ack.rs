//! Reading a server's reply without holding back our acknowledgements.
//!
//! CoppeliaSim's legacy server sends a reply of several packets one `send()` a packet, with
//! Nagle's algorithm on (no TCP_NODELAY, `../shared/spec/legacy-remote-api.md` §2): each
//! packet after the first waits until the previous one is acknowledged. Linux delays an
//! acknowledgement up to 40 ms, so every packet after the first of a reply cost about 40 ms
//! (`docs/measurements.md` "Replies of several packets": `simxGetObjectGroupData` of 40
//! objects' paths, two packets, 44 ms against 2.2 ms for one packet). Asking the kernel to
//! acknowledge at once (`TCP_QUICKACK`) before each read takes that wait away; the option does
//! not stay set, so it is asked again at every read. Elsewhere reads are plain.

use std::io::{self, Read};
use std::net::TcpStream;

/// Reads from a stream, acknowledging what arrives at once where the system allows it.
pub struct QuickAck<'a>(pub &'a TcpStream);

impl Read for QuickAck<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        #[cfg(any(target_os = "linux", target_os = "android"))]
        {
            // a refusal only leaves the delay as it was
            let _ = socket2::SockRef::from(self.0).set_tcp_quickack(true);
        }
        let mut stream = self.0;
        stream.read(buf)
    }
}
