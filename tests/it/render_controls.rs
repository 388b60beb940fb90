//! `render --crop`, `--px-per-m` and `--width`; without them the pictures are byte for byte
//! what `render` wrote before these options existed (`tests/fixtures/render/`, made by the
//! previous build).

use std::fs;
use std::path::{Path, PathBuf};

use predicates::str::contains;

use crate::support::bin;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn render(layout: &str, file: &str, extra: &[&str]) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let out: PathBuf = dir.path().join(file);
    bin()
        .arg("render")
        .arg(root().join("mazes").join(layout))
        .args(extra)
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .stderr(contains(format!("wrote {}", out.display())));
    fs::read(out).unwrap()
}

/// A PNG's width and height, from its header.
fn png_size(png: &[u8]) -> (u32, u32) {
    let word = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().unwrap());
    assert_eq!(&png[12..16], b"IHDR");
    (word(16), word(20))
}

/// An SVG's `width`, `height` and `viewBox` numbers.
fn svg_frame(svg: &[u8]) -> Vec<f64> {
    let text = String::from_utf8_lossy(svg);
    let head = text.lines().next().unwrap();
    let value = |name: &str| {
        let start = head.find(&format!("{name}=\"")).unwrap() + name.len() + 2;
        head[start..].split('"').next().unwrap().to_string()
    };
    [value("width"), value("height"), value("viewBox")]
        .join(" ")
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect()
}

#[test]
fn by_default_the_pictures_are_what_they_were() {
    let fixtures = root().join("tests/fixtures/render");
    for (layout, file, fixture) in [
        (
            "dfs-9x9-seed42.json",
            "m.svg",
            "dfs-9x9-seed42-solution.svg",
        ),
        (
            "dfs-9x9-seed42.json",
            "m.png",
            "dfs-9x9-seed42-solution.png",
        ),
        (
            "dfs-9x9-seed42-walls.json",
            "m.png",
            "dfs-9x9-seed42-walls-solution.png",
        ),
    ] {
        let made = render(layout, file, &["--solution"]);
        assert!(
            made == fs::read(fixtures.join(fixture)).unwrap(),
            "{fixture}"
        );
        // the default scale asked for explicitly gives the same bytes
        let px = if file.ends_with("svg") { "40" } else { "80" };
        let explicit = render(layout, file, &["--solution", "--px-per-m", px]);
        assert!(made == explicit, "{fixture} at --px-per-m {px}");
    }
}

#[test]
fn crop_shows_the_maze_only() {
    // 16 cells of 0.18 m and walls 0.012 m thick: 2.892 m at 80 px/m, and below the maze
    // the scale bar's strip, 0.4 m (four tenths of its 1 m bar)
    let whole = render("dfs-micromouse-seed42.json", "m.png", &[]);
    let cropped = render("dfs-micromouse-seed42.json", "m.png", &["--crop"]);
    assert_eq!(png_size(&whole), (800, 800));
    assert_eq!(png_size(&cropped), (232, 264));
    let wide = render(
        "dfs-micromouse-seed42.json",
        "m.png",
        &["--crop", "--width", "800"],
    );
    assert_eq!(png_size(&wide), (800, 911));
    // the 9x9 course maze with 0.1 m lines: 9.1 m, centred on the floor, and the bar's
    // 0.4 m strip below
    let svg = render(
        "dfs-9x9-seed42.json",
        "m.svg",
        &["--crop", "--px-per-m", "100"],
    );
    let frame = svg_frame(&svg);
    let expected = [910.0, 950.0, -4.55, -4.55, 9.1, 9.5];
    for (got, want) in frame.iter().zip(expected) {
        assert!((got - want).abs() < 1e-3, "{frame:?}");
    }
}

#[test]
fn sizes_out_of_range_and_ascii_are_refused() {
    let layout = root().join("mazes/dfs-9x9-seed42.json");
    let dir = tempfile::tempdir().unwrap();
    bin()
        .arg("render")
        .arg(&layout)
        .args(["--px-per-m", "5000", "-o"])
        .arg(dir.path().join("m.png"))
        .assert()
        .code(1)
        .stderr(contains("at most 16384 px"));
    bin()
        .arg("render")
        .arg(&layout)
        .arg("--crop")
        .assert()
        .code(2)
        .stderr(contains("not ASCII"));
    bin()
        .arg("render")
        .arg(&layout)
        .args(["--width", "0", "--format", "svg"])
        .assert()
        .code(2);
    bin()
        .arg("render")
        .arg(&layout)
        .args(["--width", "10", "--px-per-m", "3", "--format", "svg"])
        .assert()
        .code(2)
        .stderr(contains("cannot be used with"));
    assert!(!dir.path().join("m.png").exists());
}

/// Issue 41, row 11: `--crop` keeps the markers whole, in the corners of a 100 x 100 (lines
/// and walls, unturned and turned): at 10 px a metre each is all of its 10 x 10 px cell,
/// in its own colour, however the window is rounded.
#[test]
fn a_cropped_picture_keeps_the_markers_whole() {
    let dir = tempfile::tempdir().unwrap();
    for extra in [&[][..], &["--style", "walls"], &["--rotation", "30"]] {
        let layout = dir.path().join("m.json");
        bin()
            .args(["generate", "--seed", "1", "--size", "100x100"])
            .args(["--start", "sw", "--end", "ne", "-o"])
            .arg(&layout)
            .args(extra)
            .assert()
            .success();
        let png = dir.path().join("m.png");
        bin()
            .arg("render")
            .arg(&layout)
            .args(["--crop", "--px-per-m", "10", "-o"])
            .arg(&png)
            .assert()
            .success();
        let mut reader = png::Decoder::new(std::io::BufReader::new(fs::File::open(&png).unwrap()))
            .read_info()
            .unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(3).collect();
        for (marker, colour) in [("Start", [0, 0, 255]), ("End", [255, 0, 0])] {
            let n = pixels.iter().filter(|p| **p == colour).count();
            // a turned cell covers about its area in whole pixels
            assert!(
                (90..=110).contains(&n),
                "{extra:?}: {marker}: {n} px of 100"
            );
        }
    }
}
