//! Validation catches hand-edited and broken layouts, each problem named with its place.

use crate::support::course_layout;
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{Layout, passages};
use vrep_maze::maze::{Cell, Direction, Maze};
use vrep_maze::validate::validate;

fn messages(layout: &Layout) -> Vec<String> {
    validate(layout)
        .problems
        .iter()
        .map(|p| p.worded(&vrep_maze::cli::wording::Flags))
        .collect()
}

fn assert_problem(layout: &Layout, needle: &str) {
    let all = messages(layout);
    assert!(
        all.iter().any(|m| m.contains(needle)),
        "expected {needle:?} among {all:#?}"
    );
}

fn maze_of(layout: &Layout) -> Maze {
    let grid =
        vrep_maze::maze::Grid::new(layout.grid.columns.into(), layout.grid.rows.into()).unwrap();
    passages::decode(grid, &layout.passages).unwrap()
}

#[test]
fn generated_layouts_are_valid() {
    for algorithm in Algorithm::ALL {
        let layout = course_layout(algorithm, 9, 9, 42);
        let report = validate(&layout);
        assert!(report.is_ok(), "{algorithm}: {:?}", report.problems);
        assert_eq!(report.metrics.as_ref(), Some(&layout.metrics));
    }
}

#[test]
fn a_removed_passage_names_the_unreachable_end() {
    let mut layout = course_layout(Algorithm::Dfs, 5, 5, 3);
    let mut maze = maze_of(&layout);
    // Cut the passage that enters the end cell on its shortest path.
    let grid = maze.grid();
    let end = grid.index(Cell::new(layout.end.cell[0], layout.end.cell[1]));
    let start = grid.index(Cell::new(layout.start.cell[0], layout.start.cell[1]));
    let path = vrep_maze::maze::analysis::shortest_path(&maze, start, end).unwrap();
    let before = path[path.len() - 2];
    let dir = maze.direction_between(before, end).unwrap();
    let mut masks = maze.masks().to_vec();
    masks[before] &= !dir.bit();
    masks[end] &= !dir.opposite().bit();
    maze = Maze::from_masks(grid, masks).unwrap();
    layout.passages = passages::encode(&maze);
    let end_cell = grid.cell(end);
    assert_problem(
        &layout,
        &format!("end: end {end_cell} cannot be reached from start"),
    );
    assert_problem(&layout, "falls apart into 2 pieces");
    // The segments of the removed passage now draw over a wall.
    assert_problem(&layout, "draws over a wall");
}

#[test]
fn an_added_loop_is_reported_unless_declared() {
    let mut layout = course_layout(Algorithm::Prim, 6, 6, 11);
    let mut maze = maze_of(&layout);
    let grid = maze.grid();
    let (index, dir) = (0..grid.cell_count())
        .flat_map(|i| [(i, Direction::East), (i, Direction::North)])
        .find(|&(i, d)| grid.step_index(i, d).is_some() && !maze.is_open(i, d))
        .unwrap();
    maze.carve(index, dir);
    layout.passages = passages::encode(&maze);
    assert_problem(
        &layout,
        "the passages form 1 loop(s) but the layout declares a perfect maze",
    );
    // The new passage has no segments yet.
    assert_problem(&layout, "is not covered gap-free by segments");
    layout.metrics.loops = 1;
    let all = messages(&layout);
    assert!(!all.iter().any(|m| m.contains("loop(s)")), "{all:?}");
}

#[test]
fn segment_faults_are_named_by_index() {
    let base = course_layout(Algorithm::Kruskal, 5, 5, 8);

    let mut shifted = base.clone();
    shifted.segments[3].x += 0.2;
    shifted.segments[3].y += 0.0;
    let all = messages(&shifted);
    assert!(
        all.iter()
            .any(|m| m.starts_with("segments[3]") || m.starts_with("passage ")),
        "{all:?}"
    );

    let mut between = base.clone();
    let horizontal = between.segments.iter().position(|s| s.yaw == 0.0).unwrap();
    between.segments[horizontal].y += 0.5;
    assert_problem(&between, &format!("segments[{horizontal}]: at"));
    assert_problem(&between, "lies between two rows of cell centres");

    let mut duplicated = base.clone();
    let copy = duplicated.segments[5];
    duplicated.segments.push(copy);
    let last = duplicated.segments.len() - 1;
    assert_problem(
        &duplicated,
        &format!("segments[{last}]: duplicates segments[5]"),
    );

    let mut missing = base.clone();
    missing.segments.remove(0);
    assert_problem(&missing, "is not covered gap-free by segments");

    let mut off = base.clone();
    off.segments[2].x += 100.0;
    assert_problem(&off, "segments[2]");

    let mut crooked = base.clone();
    crooked.segments[1].yaw = 0.3;
    assert_problem(&crooked, "segments[1]: at");
    assert_problem(&crooked, "runs along neither maze axis");
}

#[test]
fn markers_metrics_and_floor_are_checked() {
    let base = course_layout(Algorithm::Dfs, 9, 9, 42);

    let mut start_off = base.clone();
    start_off.start.cell = [9, 0];
    assert_problem(&start_off, "start.cell: (9,0) is off the 9x9 grid");

    let mut moved_marker = base.clone();
    moved_marker.end.pose.x += 0.5;
    assert_problem(&moved_marker, "end.pose: marker at");

    let mut lying = base.clone();
    lying.metrics.dead_ends += 1;
    assert_problem(&lying, "metrics.dead_ends: says");

    let mut small_floor = base.clone();
    small_floor.floor.size = [8.0, 10.0];
    assert_problem(
        &small_floor,
        "floor.size: the maze needs 9.000 m x 9.000 m but the floor is 8 m x 10 m",
    );

    let mut nan = base.clone();
    nan.line.length = f64::NAN;
    assert_problem(
        &nan,
        "line.length: must be a positive number of metres, not NaN",
    );

    let mut unknown = base.clone();
    unknown.generator.algorithm = "mazeomatic".into();
    assert_problem(&unknown, "generator: unknown algorithm 'mazeomatic'");

    let mut option = base.clone();
    option.generator.options.insert("bias".into(), "ne".into());
    assert_problem(
        &option,
        "generator: --bias ne applies to --algo binary-tree, not dfs",
    );
    option
        .generator
        .options
        .insert("colour".into(), "red".into());
    assert_problem(
        &option,
        "generator.options.colour: is not an option vrep-maze knows",
    );

    let mut huge = base;
    huge.grid.columns = 100_000;
    huge.grid.rows = 100_000;
    assert_problem(&huge, "the limit is 16777216 cells");
}

#[test]
fn rotated_and_offset_mazes_validate() {
    use vrep_maze::layout::{FloorSize, GenerateSpec, build_layout};
    let grid = vrep_maze::maze::Grid::new(6, 4).unwrap();
    let mut spec = GenerateSpec::course(grid, Algorithm::Prim, 2);
    spec.geometry.rotation = 30f64.to_radians();
    spec.geometry.origin = [-2.5, 1.25];
    spec.floor = FloorSize::Fixed([20.0, 20.0]);
    let layout = build_layout(&spec).unwrap();
    let report = validate(&layout);
    assert!(report.is_ok(), "{:?}", report.problems);
    spec.geometry.line_length = 0.3;
    spec.geometry.cell_size = 0.5;
    spec.geometry.line_width = 0.05;
    let layout = build_layout(&spec).unwrap();
    assert_eq!(layout.segments.len(), 2 * layout.metrics.passages as usize);
    assert!(validate(&layout).is_ok());
}

#[test]
fn a_hand_edited_cell_size_is_named_first_as_the_one_cause_with_the_generate_option() {
    for (size, rotation) in [(2.0, 0.0), (0.5, 0.7)] {
        let mut spec = vrep_maze::layout::GenerateSpec::course(
            vrep_maze::maze::Grid::new(9, 9).unwrap(),
            Algorithm::Dfs,
            4,
        );
        spec.geometry.rotation = rotation;
        let mut layout = vrep_maze::layout::build_layout(&spec).unwrap();
        layout.grid.cell_size = size;
        let all = messages(&layout);
        assert!(
            all[0].starts_with(&format!(
                "grid.cell_size: is {size} m, but the maze was made for cells of 1 m"
            )) && all[0].contains(&format!("vrep-maze generate --cell-size {size}")),
            "{all:#?}"
        );
        assert_eq!(
            all.iter().filter(|m| m.contains("cell_size")).count(),
            1,
            "{all:#?}"
        );
    }
    // an untouched layout says nothing of it
    assert!(messages(&course_layout(Algorithm::Dfs, 9, 9, 4)).is_empty());
}
