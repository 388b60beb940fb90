"""generate, Layout and batch against the golden mazes and the command line."""

import json
import re
from pathlib import Path

import numpy as np
import pytest

import vrep_maze
from conftest import MAZES, cli_error, golden_cases, imported_goldens, in_python_names, run_cli


@pytest.mark.parametrize("path, options", golden_cases())
def test_every_golden_maze_is_generated_byte_for_byte(path, options):
    layout = vrep_maze.generate(**options)
    assert layout.to_json().encode() == path.read_bytes()


@pytest.mark.parametrize("path", imported_goldens())
def test_imported_golden_mazes_load_and_are_written_back_byte_for_byte(path):
    layout = vrep_maze.load(path)
    assert layout.to_json().encode() == path.read_bytes()
    assert layout.render().count("+") > 0  # walls drawn as text


def test_the_issue_example_equals_the_command_byte_for_byte():
    cli = run_cli("generate", "--seed", 42, "--algo", "prim")
    assert cli.returncode == 0, cli.stderr
    assert vrep_maze.generate(seed=42, algo="prim").to_json().encode() == cli.stdout


def test_geometry_keywords_mean_what_the_options_mean():
    keywords = dict(seed=3, algo="kruskal", size=(7, 5), start=(0, 4), end="se",
                    cell_size=0.5, line_length=0.3, line_width=0.05, rotation=-30.5,
                    origin=(1.25, -2), floor_size=(20, 20), marker_z=0.003)
    cli = run_cli("generate", "--seed", 3, "--algo", "kruskal", "--size", "7x5",
                  "--start", "0,4", "--end", "se", "--cell-size", 0.5, "--line-length", 0.3,
                  "--line-width", 0.05, "--rotation", -30.5, "--origin", "1.25,-2",
                  "--floor-size", "20x20", "--marker-z", 0.003)
    assert cli.returncode == 0, cli.stderr
    assert vrep_maze.generate(**keywords).to_json().encode() == cli.stdout
    # text is passed as written, so the command line's spelling works too
    assert vrep_maze.generate(seed=3, algo="kruskal", size="7x5", start="0,4", end="se",
                              cell_size="0.5", line_length=0.3, line_width=0.05,
                              rotation=-30.5, origin="1.25,-2", floor_size="20x20",
                              marker_z=0.003).to_json().encode() == cli.stdout


@pytest.mark.parametrize("keywords, args", [
    (dict(size=(0, 9)), ["--size", "0x9"]),
    (dict(size=(5000, 5000)), ["--size", "5000x5000"]),
    (dict(algo="foo"), ["--algo", "foo"]),
    (dict(cell_size=-1), ["--cell-size", "-1"]),
    (dict(braid=2), ["--braid", "2"]),
    (dict(growing="oldest"), ["--growing", "oldest"]),
    (dict(start=(9, 9)), ["--start", "9,9"]),
    (dict(start="farthest-pair", end="ne"), ["--start", "farthest-pair", "--end", "ne"]),
    (dict(line_width=1.5), ["--line-width", "1.5"]),
    (dict(seed=-1), ["--seed", "-1"]),
    (dict(seed=2**64), ["--seed", str(2**64)]),
    (dict(rotation=float("nan")), ["--rotation", "NaN"]),
    (dict(algo="dfs\x1b[31m"), ["--algo", "dfs\x1b[31m"]),
    (dict(algo="a\nerror: forged"), ["--algo", "a\nerror: forged"]),
])
def test_a_refused_value_raises_value_error_with_the_commands_message(keywords, args):
    with pytest.raises(ValueError) as raised:
        vrep_maze.generate(**keywords)
    # the same words as the command line's, options as keyword arguments (`braid=2`, quoted
    # values): compared word by word, keyword punctuation aside
    words = lambda text: re.sub(r'[=",]', " ", text).split()
    assert words(str(raised.value)) == words(in_python_names(cli_error("generate", *args)))
    assert "--" not in str(raised.value)


@pytest.mark.parametrize("algo, shown", [("dfs\x00x", r"'dfs\0x'"),
                                         ("\x1b[31m", r"'\u{1b}[31m'"),
                                         ("a\nerror: forged", r"'a\nerror: forged'")])
def test_a_refused_value_shows_its_control_characters_escaped_as_the_command_does(algo, shown):
    # the manual: control characters from an option are shown escaped, never raw nor dropped
    with pytest.raises(ValueError) as raised:
        vrep_maze.generate(algo=algo)
    message = str(raised.value)
    assert f"unknown algorithm {shown}" in message, message
    assert not any(c < " " for c in message), repr(message)


def test_python_type_errors_are_type_errors():
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        vrep_maze.generate(colour="red")
    with pytest.raises(TypeError, match="not a bool"):
        vrep_maze.generate(braid=True)
    with pytest.raises(TypeError, match="a pair"):
        vrep_maze.generate(size=(1, 2, 3))
    with pytest.raises(TypeError, match="unexpected keyword argument 'output'"):
        vrep_maze.generate(output="m.json")


def test_a_drawn_seed_is_recorded():
    layout = vrep_maze.generate(size=(4, 4))
    again = vrep_maze.generate(seed=layout.seed, size=(4, 4))
    assert again == layout


def test_layout_inspection():
    layout = vrep_maze.generate(seed=42, algo="prim")
    data = json.loads(layout.to_json())
    assert layout.metrics == data["metrics"]
    assert layout.start == tuple(data["start"]["cell"])
    assert layout.end == tuple(data["end"]["cell"])
    assert layout.size == (9, 9) and layout.seed == 42 and layout.algorithm == "prim"
    segments = layout.segments
    assert segments.shape == (len(data["segments"]), 4) and segments.dtype == np.float64
    assert segments.flags["C_CONTIGUOUS"]
    expected = [[s["x"], s["y"], s["z"], s["yaw"]] for s in data["segments"]]
    assert np.array_equal(segments, np.array(expected))
    passages = layout.passages
    assert passages.shape == (9, 9) and passages.dtype == np.uint8
    for y, row in enumerate(data["passages"]):
        assert [int(c, 16) for c in row] == passages[y].tolist()
        for x, digit in enumerate(row):
            for bit, name in [(1, "east"), (2, "north"), (4, "w"), (8, "S")]:
                assert layout.open(x, y, name) == bool(int(digit, 16) & bit)
    with pytest.raises(ValueError, match="off the 9x9 grid"):
        layout.open(9, 0, "east")
    with pytest.raises(ValueError, match="not a direction"):
        layout.open(0, 0, "up")


def test_the_solution_is_the_shortest_path():
    layout = vrep_maze.generate(seed=42, algo="prim")
    path = layout.solution()
    assert path[0] == layout.start and path[-1] == layout.end
    assert len(path) == layout.metrics["solution_cells"]
    steps = {(1, 0): "east", (0, 1): "north", (-1, 0): "west", (0, -1): "south"}
    for (x, y), (nx, ny) in zip(path, path[1:]):
        assert layout.open(x, y, steps[(nx - x, ny - y)])


def test_batch_yields_the_layouts_generate_makes():
    made = list(vrep_maze.batch(range(5), algo="prim", size=(6, 6)))
    assert [m.seed for m in made] == list(range(5))
    for layout in made:
        assert layout == vrep_maze.generate(seed=layout.seed, algo="prim", size=(6, 6))
    assert [m.seed for m in vrep_maze.batch("3..=4")] == [3, 4]
    assert [m.seed for m in vrep_maze.batch([7, 2])] == [7, 2]
    assert len(vrep_maze.batch(range(100))) == 100


def test_batch_filters_like_the_command():
    keep = [m.seed for m in vrep_maze.batch(range(40), size=(5, 5), min_solution=12)]
    assert keep and len(keep) < 40
    assert all(vrep_maze.generate(seed=s, size=(5, 5)).metrics["solution_cells"] >= 12
               for s in keep)
    with pytest.raises(ValueError) as raised:
        vrep_maze.batch(range(3), max_dead_ends=150)
    assert str(raised.value) == in_python_names(cli_error(
        "batch", "--seeds", "0..3", "--out-dir", ".", "--max-dead-ends", "150"))
    with pytest.raises(ValueError) as raised:
        vrep_maze.batch("5..2")
    assert str(raised.value) == in_python_names(
        cli_error("batch", "--seeds", "5..2", "--out-dir", "."))


def test_help_says_what_the_options_are():
    for function in (vrep_maze.generate, vrep_maze.apply, vrep_maze.clear, vrep_maze.batch,
                     vrep_maze.load, vrep_maze.Layout.render):
        assert len(function.__doc__) > 200, function
    assert "cell_size" in vrep_maze.generate.__doc__
    installed = Path(vrep_maze.__file__).parent
    assert (installed / "py.typed").exists() and (installed / "_vrep_maze.pyi").exists()


def test_a_wall_maze_has_walls_and_no_segments():
    layout = vrep_maze.generate(seed=42, style="walls", openings="start,end", end="ne")
    cli = run_cli("generate", "--seed", 42, "--style", "walls", "--openings", "start,end",
                  "--end", "ne")
    assert cli.returncode == 0, cli.stderr
    assert layout.to_json().encode() == cli.stdout
    assert layout.style == "walls"
    assert layout.segments.shape == (0, 4)
    walls = layout.walls
    assert walls.shape == (len(json.loads(cli.stdout)["walls"]), 4)
    assert np.allclose(walls[:, 2], 0.1)  # centres at half the 0.2 m height
    assert "walls>" in repr(layout)
    assert vrep_maze.generate(seed=42).style == "lines"
    assert vrep_maze.generate(seed=42).walls.shape == (0, 4)


def test_wall_options_without_walls_are_refused_as_the_command_refuses_them():
    with pytest.raises(ValueError) as raised:
        vrep_maze.generate(seed=1, wall_height=0.3)
    assert str(raised.value) == in_python_names(
        cli_error("generate", "--seed", 1, "--wall-height", 0.3))


def test_waypoints_are_what_solve_writes(tmp_path):
    layout = vrep_maze.generate(seed=42, algo="prim", braid=0.5)
    waypoints = layout.waypoints()
    assert waypoints.dtype == np.float64 and waypoints.shape[1] == 4
    path = layout.solution()
    turns = layout.metrics["solution_turns"]
    assert waypoints.shape[0] == len(path) + turns
    assert waypoints[-1, 3] == len(path) - 1  # 1 m cells: metres along the path
    file = tmp_path / "m.json"
    layout.save(file)
    report = json.loads(run_cli("solve", file).stdout)
    expected = [[w["x"], w["y"], w["yaw"], w["distance"]] for w in report["waypoints"]]
    assert waypoints.tolist() == expected
    other = layout.waypoints(start=(8, 8))
    assert other[0].tolist()[:2] == [4.0, 4.0] and other[0, 3] == 0.0  # cell (8,8) of 1 m cells
    assert other[-1].tolist()[:2] == waypoints[-1].tolist()[:2]
    with pytest.raises(ValueError, match="off the 9x9 grid"):
        layout.waypoints(start=(9, 9))


def test_batch_makes_every_style():
    made = list(vrep_maze.batch(range(2), style="walls", posts=True, size=(5, 4)))
    assert [m.style for m in made] == ["walls", "walls"]
    assert made[1] == vrep_maze.generate(seed=1, style="walls", posts=True, size=(5, 4))
    assert len(made[0].posts) > 0
    mice = list(vrep_maze.batch([3], preset="micromouse"))
    assert mice[0].size == (16, 16)
