"""Layout files: JSON round trips, the validation gate, rendering."""

import json

import pytest

import vrep_maze
from conftest import MAZES, run_cli

GOLDEN = MAZES / "prim-20x15-seed7.json"


def test_json_round_trips_byte_for_byte(tmp_path):
    text = GOLDEN.read_text()
    layout = vrep_maze.Layout.from_json(text)
    assert layout.to_json() == text
    assert vrep_maze.load(GOLDEN) == layout
    assert vrep_maze.load(str(GOLDEN)) == layout
    saved = tmp_path / "m.json"
    layout.save(saved)
    assert saved.read_bytes() == GOLDEN.read_bytes()
    assert [p.name for p in tmp_path.iterdir()] == ["m.json"]


def test_validate_returns_the_metrics():
    layout = vrep_maze.load(GOLDEN)
    assert layout.validate() == json.loads(GOLDEN.read_text())["metrics"]


def broken(tmp_path):
    data = json.loads(GOLDEN.read_text())
    data["segments"][3]["z"] = 0.5
    data["metrics"]["dead_ends"] += 1
    path = tmp_path / "broken.json"
    path.write_text(json.dumps(data))
    return path


def test_an_invalid_layout_raises_validation_error_listing_its_problems(tmp_path):
    path = broken(tmp_path)
    with pytest.raises(vrep_maze.ValidationError) as raised:
        vrep_maze.load(path)
    problems = raised.value.problems
    assert any(p.startswith("segments[3].z") for p in problems), problems
    assert any("dead_ends" in p for p in problems), problems
    cli = run_cli("validate", path)
    assert cli.returncode == 1
    for problem in problems:
        assert f"error: {path}: {problem}" in cli.stderr.decode()
    assert isinstance(raised.value, ValueError)
    assert str(len(problems)) in str(raised.value)
    with pytest.raises(vrep_maze.ValidationError):
        vrep_maze.Layout.from_json(path.read_text())


def test_unreadable_input_is_refused_with_the_commands_message(tmp_path):
    with pytest.raises(FileNotFoundError, match="nowhere.json"):
        vrep_maze.load(tmp_path / "nowhere.json")
    with pytest.raises(ValueError, match=r"<json>:1:\d+: "):
        vrep_maze.Layout.from_json("{not json")
    with pytest.raises(ValueError, match="not a vrep-maze layout"):
        vrep_maze.Layout.from_json('{"format": "other", "version": 1}')
    with pytest.raises(OSError, match="cannot|directory"):
        vrep_maze.load(GOLDEN).save(tmp_path / "missing-dir" / "m.json")


@pytest.mark.parametrize("name, solution", [("m.svg", True), ("m.png", True),
                                            ("m.txt", False), ("m.svg", False)])
def test_render_writes_what_the_command_writes(tmp_path, name, solution):
    ours, theirs = tmp_path / f"ours-{name}", tmp_path / f"cli-{name}"
    assert vrep_maze.load(GOLDEN).render(ours, solution=solution) is None
    flags = ["--solution"] if solution else []
    done = run_cli("render", GOLDEN, "-o", theirs, *flags)
    assert done.returncode == 0, done.stderr
    assert ours.read_bytes() == theirs.read_bytes()


def test_render_without_a_path_returns_the_picture():
    layout = vrep_maze.load(GOLDEN)
    ascii_art = layout.render(solution=True)
    assert ascii_art.encode() == run_cli("render", GOLDEN, "--solution").stdout
    svg = layout.render(format="svg")
    assert svg.startswith("<svg") or svg.startswith("<?xml")
    assert layout._repr_svg_() == svg
    png = layout.render(format="png")
    assert isinstance(png, bytes) and png.startswith(b"\x89PNG")


def test_render_refuses_unknown_and_conflicting_formats(tmp_path):
    layout = vrep_maze.load(GOLDEN)
    with pytest.raises(ValueError, match="not .jpg"):
        layout.render(tmp_path / "m.jpg")
    with pytest.raises(ValueError, match="does not match"):
        layout.render(tmp_path / "m.png", format="svg")
    with pytest.raises(ValueError, match="unknown format"):
        layout.render(format="pdf")
