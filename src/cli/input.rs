//! Reading a whole text file that is not a layout (a drawing to `import`, a scene dump to
//! `render`, a trajectory to `render --trajectory` or `serve --robot`): at most a bound that any real one stays under, refusing binary data at its
//! first NUL byte, so an endless or huge input (`/dev/zero`, a disk image) fails after a
//! bounded read with a message that says what it is.

use std::io::Read;
use std::path::Path;

use anyhow::{Context, Result, bail};

/// The most bytes of a trajectory CSV (`render --trajectory`, `serve --robot`): a row of
/// `t,x,y,yaw` takes about 40 bytes, so this holds over 80 hours of a run sampled 20 times a
/// second.
pub(crate) const MAX_TRAJECTORY_BYTES: usize = 256 << 20;

/// The text of a trajectory CSV file (`-`: standard input), within
/// [`MAX_TRAJECTORY_BYTES`].
pub(crate) fn read_trajectory_text(path: &Path) -> Result<String> {
    read_text(
        path,
        MAX_TRAJECTORY_BYTES,
        "a trajectory (CSV: t,x,y,yaw)",
        "a trajectory is read whole, so its size is bounded: 256 MiB holds over 80 hours at 20 samples a second",
    )
}

/// Bytes read at a time.
const CHUNK: usize = 1 << 20;

/// The text of `path` (`-` reads standard input) if it holds at most `limit` bytes and no
/// NUL byte; `what` says in errors what the file should be (`a text drawing of a maze`) and
/// `why` what bounds it.
pub(crate) fn read_text(path: &Path, limit: usize, what: &str, why: &str) -> Result<String> {
    let name = path.display();
    let mut reader: Box<dyn Read> = if path.as_os_str() == "-" {
        Box::new(std::io::stdin().lock())
    } else {
        Box::new(std::fs::File::open(path).with_context(|| format!("reading {name}"))?)
    };
    let mut bytes = Vec::new();
    loop {
        let before = bytes.len();
        let read = (&mut reader)
            .take(CHUNK as u64)
            .read_to_end(&mut bytes)
            .with_context(|| format!("reading {name}"))?;
        if let Some(at) = memchr::memchr(0, &bytes[before..]) {
            bail!(
                "{name}: binary data (a NUL byte at offset {}): not {what}",
                before + at
            );
        }
        if bytes.len() > limit {
            bail!("{name}: more than {} MiB: not {what} ({why})", limit >> 20);
        }
        if read == 0 {
            break;
        }
    }
    String::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "{name}: not UTF-8 text (byte {} is not): not {what}",
            e.utf8_error().valid_up_to()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nul_byte_or_too_many_bytes_are_refused_with_what_the_file_should_be() {
        let dir = tempfile::tempdir().unwrap();
        let binary = dir.path().join("b");
        std::fs::write(&binary, b"ab\0cd").unwrap();
        let e = read_text(&binary, 1 << 20, "a drawing", "-").unwrap_err();
        assert!(
            e.to_string()
                .contains("NUL byte at offset 2): not a drawing"),
            "{e}"
        );
        let big = dir.path().join("big");
        std::fs::write(&big, vec![b'#'; 3 << 20]).unwrap();
        let e = read_text(&big, 2 << 20, "a drawing", "the largest takes 1 MiB").unwrap_err();
        assert!(e.to_string().contains("more than 2 MiB"), "{e}");
        let text = dir.path().join("t");
        std::fs::write(&text, "+--+\n").unwrap();
        assert_eq!(
            read_text(&text, 1 << 20, "a drawing", "-").unwrap(),
            "+--+\n"
        );
    }
}
