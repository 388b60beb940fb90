//! Files keep their permissions: a file replaced with `-o` keeps its mode (and owner), and
//! nothing is written where the user could not write the file in place. The other-user
//! cases run the binary as `nobody` through `setpriv` when the tests run as root; elsewhere
//! they are skipped (saying so).

use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::Path;
use std::process::Command;

use crate::support::bin;

/// The replacing commands, writing to `out`.
fn writers(out: &str) -> Vec<Vec<String>> {
    let golden = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/kruskal-9x9-seed42.json");
    let drawing = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/drawn-4x4.txt");
    [
        vec!["generate", "--seed", "1", "-o", out],
        vec!["render", golden, "--format", "svg", "-o", out],
        vec!["render", golden, "--format", "ascii", "-o", out],
        vec!["import", drawing, "-o", out],
    ]
    .into_iter()
    .map(|a| a.into_iter().map(String::from).collect())
    .collect()
}

fn mode(path: &Path) -> u32 {
    std::fs::metadata(path).unwrap().permissions().mode() & 0o7777
}

#[test]
fn a_replaced_file_keeps_its_mode() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for args in writers(out.to_str().unwrap()) {
        for wanted in [0o600, 0o640, 0o664, 0o755] {
            std::fs::write(&out, "old").unwrap();
            std::fs::set_permissions(&out, std::fs::Permissions::from_mode(wanted)).unwrap();
            bin().args(&args).assert().success();
            assert_ne!(std::fs::read(&out).unwrap(), b"old", "{args:?}");
            assert_eq!(mode(&out), wanted, "{args:?}");
        }
    }
    // batch replaces its layouts and manifest the same way
    let data = dir.path().join("data");
    let batch = |seeds: &str| {
        bin()
            .args(["batch", "--seeds", seeds, "--out-dir"])
            .arg(&data)
            .assert()
            .success();
    };
    batch("1");
    let manifest = data.join("manifest.jsonl");
    std::fs::set_permissions(&manifest, std::fs::Permissions::from_mode(0o600)).unwrap();
    batch("1..3");
    assert_eq!(mode(&manifest), 0o600);
}

/// Whether these tests run as root (so `setpriv` can run the binary as another user).
fn root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}

/// Runs the binary as `nobody` (uid and gid 65534) with `args`; its exit code and stderr.
fn as_nobody(args: &[String]) -> (Option<i32>, String) {
    let out = Command::new("setpriv")
        .args(["--reuid=65534", "--regid=65534", "--clear-groups"])
        .arg(assert_cmd::cargo::cargo_bin("vrep-maze"))
        .envs(crate::support::cli::away_from_defaults())
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn another_users_file_is_never_replaced_where_it_could_not_be_written() {
    if !root() || Command::new("setpriv").arg("--version").output().is_err() {
        eprintln!("skipped: needs root and setpriv to run as another user");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    // a folder everyone may write in, holding root's files
    std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o777)).unwrap();
    let out = dir.path().join("root-owned");
    for args in writers(out.to_str().unwrap()) {
        // read-only for everyone: refused, the file as it was
        std::fs::write(&out, "old").unwrap();
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
        let (code, stderr) = as_nobody(&args);
        assert_eq!(code, Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains("Permission denied"), "{args:?}: {stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), b"old", "{args:?}");
        let meta = std::fs::metadata(&out).unwrap();
        assert_eq!((meta.uid(), meta.mode() & 0o777), (0, 0o444), "{args:?}");
        // writable by everyone: written, and still root's with its mode
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o666)).unwrap();
        let (code, stderr) = as_nobody(&args);
        assert_eq!(code, Some(0), "{args:?}: {stderr}");
        assert_ne!(std::fs::read(&out).unwrap(), b"old", "{args:?}");
        let meta = std::fs::metadata(&out).unwrap();
        assert_eq!(
            (meta.uid(), meta.gid(), meta.mode() & 0o777),
            (0, 0, 0o666),
            "{args:?}"
        );
        std::fs::remove_file(&out).unwrap();
    }
    // root replacing a read-only file of its own (as root may): the mode is kept
    std::fs::write(&out, "old").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
    bin()
        .args(&writers(out.to_str().unwrap())[0])
        .assert()
        .success();
    assert_eq!(mode(&out), 0o444);
}
