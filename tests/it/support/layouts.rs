//! Mazes to draw.

use vrep_maze::draw::Drawing;
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, Layout, build_layout};
use vrep_maze::maze::Grid;
use vrep_maze::sim::Scene;

/// A floor that takes every maze the tests draw over the emulator (the course's is 10 m:
/// `apply` refuses a larger maze's layout on it).
pub const BIG_FLOOR: [f64; 2] = [500.0, 500.0];

/// The course scene with a [`BIG_FLOOR`].
pub fn big_course() -> Scene {
    Scene::course().with_floor(BIG_FLOOR)
}

/// [`big_course`] as a scene file in `dir`, for `vrep-maze serve --scene`.
pub fn big_course_file(dir: &std::path::Path) -> String {
    let path = dir.join("big-course.json");
    std::fs::write(&path, big_course().to_json().to_string()).unwrap();
    path.display().to_string()
}

/// The course layout for `algorithm` and `seed` on a `w` x `h` grid.
pub fn course_layout(algorithm: Algorithm, w: u64, h: u64, seed: u64) -> Layout {
    build_layout(&GenerateSpec::course(
        Grid::new(w, h).unwrap(),
        algorithm,
        seed,
    ))
    .unwrap()
}

/// The lines of the `n` x `n` Prim course for `seed` (9 x 9 seed 42 has 160 lines).
pub fn drawing(n: u64, seed: u64) -> Drawing {
    drawing_with(Algorithm::Prim, n, seed)
}

/// The lines of the `n` x `n` course of `algorithm` for `seed`.
pub fn drawing_with(algorithm: Algorithm, n: u64, seed: u64) -> Drawing {
    Drawing::try_from(&course_layout(algorithm, n, n, seed)).unwrap()
}

/// Checks that `r`, an apply of `d` in copies mode, counts each line and post once: kept
/// (already in place or placed) or pasted; the kept being the reused copies and, in a line
/// maze with lines, the template; and each marker once. Its summary line says those numbers.
pub fn assert_counts_add_up(r: &vrep_maze::draw::ApplyReport, d: &Drawing) {
    let template = usize::from(d.template_drawn() && !d.pieces.is_empty());
    let hidden = usize::from(d.template_drawn() && d.pieces.is_empty());
    assert_eq!(
        (r.pieces, r.posts),
        (d.pieces.len(), d.posts.len()),
        "{r:?}"
    );
    assert_eq!(
        r.pieces + r.posts,
        r.unchanged + r.placed + r.pasted,
        "{r:?}"
    );
    assert_eq!(r.unchanged + r.placed, r.reused + template, "{r:?}");
    assert_eq!(r.markers_unchanged + r.markers_placed, 2 + hidden, "{r:?}");
    if r.dry_run && r.nothing_to_do() {
        return;
    }
    // the summary line's own numbers add up: "N lines[ and P posts]: K kept (…: I already in
    // place, M placed[, U set unread…]), X pasted; markers: A already in place, B placed; …"
    let text = vrep_maze::cli::summary::apply_line(r);
    let number_before = |word: &str| -> usize {
        let at = text
            .find(word)
            .unwrap_or_else(|| panic!("no {word:?} in {text}"));
        let head = text[..at].trim_end();
        let digits = &head[head
            .rfind(|c: char| !c.is_ascii_digit())
            .map_or(0, |i| i + 1)..];
        digits
            .parse()
            .unwrap_or_else(|_| panic!("no number before {word:?} in {text}"))
    };
    let whole = number_before(r.style.name())
        + if d.posts.is_empty() {
            0
        } else {
            number_before(" posts")
        };
    let kept = number_before(" kept");
    assert_eq!(whole, kept + number_before(" pasted;"), "{text}");
    if kept > 0 {
        let unread = if text.contains(" set unread") {
            number_before(" set unread")
        } else {
            0
        };
        let (in_place, placed) = (
            number_before(" already in place, "),
            number_before(" placed"),
        );
        assert_eq!(kept, in_place + placed + unread, "{text}");
        assert_eq!(r.unread, unread, "{text}");
    }
    // the template is named with the markers when it is counted with them (one cell)
    let label = ["markers: ", "Start, End and the line template: "]
        .into_iter()
        .find(|l| text.contains(l))
        .expect("markers");
    let markers = &text[text.find(label).unwrap()..];
    let in_place: usize = markers[label.len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let placed: usize = markers[label.len()..]
        .split(", ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(in_place + placed, 2 + hidden, "{text}");
}
