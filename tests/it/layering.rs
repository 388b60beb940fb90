//! The layering rule of ARCHITECTURE.md, kept by a test: client side and emulator side of
//! each protocol share only their codec and `coppelia`, never each other's modules.

use std::path::{Path, PathBuf};

/// Client-side modules: the two clients, their drawing backends, and the drawing port.
const CLIENT_SIDE: &[&str] = &[
    "legacy::client",
    "legacy::backend",
    "legacy::follow",
    "zmq_api::client",
    "zmq_api::backend",
    "zmq_api::follow",
    "draw",
];

/// Emulator-side modules: the simulator model and the two servers.
const EMULATOR_SIDE: &[&str] = &["sim", "legacy::server", "zmq_api::server"];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a source file: `src/legacy/server/mod.rs` is `legacy::server`.
fn module_of(file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src()).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

/// Every module path the file names with `crate::` or `super::` (groups in braces expanded
/// one level), made absolute.
fn referenced_modules(text: &str, module: &[String]) -> Vec<String> {
    let mut found = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if !text.is_char_boundary(i) {
            i += 1;
            continue;
        }
        let rest = &text[i..];
        let starts_path = (rest.starts_with("crate::") || rest.starts_with("super::"))
            && (i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_'));
        if !starts_path {
            i += 1;
            continue;
        }
        let len = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':'))
            .unwrap_or(rest.len());
        let mut path: Vec<&str> = rest[..len].split("::").filter(|s| !s.is_empty()).collect();
        // `file` is the module itself; `super` is its parent (a mod.rs's module is its folder)
        let mut base: Vec<String> = module.to_vec();
        if path.first() == Some(&"crate") {
            base.clear();
            path.remove(0);
        }
        while path.first() == Some(&"super") {
            base.pop();
            path.remove(0);
        }
        let prefix: Vec<String> = base
            .into_iter()
            .chain(path.iter().map(|s| s.to_string()))
            .collect();
        let after = &rest[len..];
        if after.starts_with('{') {
            let group = &after[1..after.find('}').unwrap_or(after.len())];
            for item in group.split(',') {
                let name = item.trim().split("::").next().unwrap_or("").trim();
                if !name.is_empty() && name != "self" {
                    found.push(format!("{}::{name}", prefix.join("::")));
                }
            }
        }
        found.push(prefix.join("::"));
        i += len.max(1);
    }
    found
}

fn within(module: &str, area: &str) -> bool {
    module == area || module.starts_with(&format!("{area}::"))
}

/// Files of `side` that name a module of `forbidden`, as "file: module" lines.
fn violations(side: &[&str], forbidden: &[&str]) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut out = Vec::new();
    for file in files {
        let module = module_of(&file);
        let name = module.join("::");
        if !side.iter().any(|area| within(&name, area)) {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        for used in referenced_modules(&text, &module) {
            if forbidden.iter().any(|area| within(&used, area)) {
                out.push(format!("{}: {used}", file.display()));
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

#[test]
fn the_client_side_never_names_the_emulator() {
    let found = violations(CLIENT_SIDE, EMULATOR_SIDE);
    assert!(
        found.is_empty(),
        "client side uses the emulator:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_emulator_never_names_the_client_side() {
    let found = violations(EMULATOR_SIDE, CLIENT_SIDE);
    assert!(
        found.is_empty(),
        "emulator uses the client side:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_checker_sees_paths_of_every_form() {
    let m = |s: &str| s.split("::").map(String::from).collect::<Vec<_>>();
    let found = referenced_modules(
        "use super::client::Client;\nuse crate::sim::{Clock, frame};\nlet x = super::super::draw::apply();",
        &m("legacy::server::execute"),
    );
    for expected in [
        "legacy::server::client::Client",
        "sim",
        "sim::Clock",
        "sim::frame",
        "legacy::draw::apply",
    ] {
        assert!(
            found.iter().any(|f| f == expected),
            "{expected} not in {found:?}"
        );
    }
    assert!(within("legacy::server::execute", "legacy::server"));
    assert!(!within("legacy::serverx", "legacy::server"));
}
