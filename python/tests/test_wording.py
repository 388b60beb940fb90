"""The options the library's messages name, as each adapter words them: the command line's
flags (`--line-length 0.3`), Python's keyword arguments (`line_length=0.3`)."""

import json
import re

import pytest

import vrep_maze
from conftest import MAZES, cli_error, run_cli


def words(text: str) -> list:
    """`text`'s words, option punctuation aside: `--end ne` and `end="ne"` read alike."""
    plain = re.sub(r"(?<![\w-])--", "", text).replace('"', "").replace("-", "_")
    return re.sub(r"[=,]", " ", plain).split()


@pytest.mark.parametrize("keywords, args, python_says", [
    (dict(start="farthest-pair", end="ne"), ["--start", "farthest-pair", "--end", "ne"],
     'end="ne" conflicts with start="farthest-pair", which picks both ends: drop end'),
    (dict(cell_size=0.4), ["--cell-size", "0.4"],
     "cell_size=0.4 m is too small for the line template: one 0.6 m line would reach over the"
     " walls; a cell needs at least line_length - line_width = 0.5 m"),
    (dict(style="walls", openings="start,end", end=(4, 4)),
     ["--style", "walls", "--openings", "start,end", "--end", "4,4"],
     'openings="start,end": the end cell (4,4) is not on the edge of the 9x9 grid, so no gap'
     " can lead to it; choose end on the edge or leave end out of openings"),
    (dict(size=(20, 15), floor_size=(10, 10)), ["--size", "20x15", "--floor-size", "10x10"],
     "the maze needs a floor of 21.000 m x 15.000 m (centred on the floor origin) but"
     " floor_size is 10 m x 10 m"),
])
def test_generate_refusals_name_flags_on_the_command_line_and_keywords_in_python(
        keywords, args, python_says):
    cli = cli_error("generate", "--seed", 1, *args)
    with pytest.raises(ValueError) as raised:
        vrep_maze.generate(seed=1, **keywords)
    assert str(raised.value) == python_says
    assert "--" in cli and words(cli) == words(python_says), cli


def test_a_validation_problem_names_the_call_that_makes_the_maze_anew(tmp_path):
    layout = json.loads((MAZES / "dfs-9x9-seed42.json").read_text())
    layout["grid"]["cell_size"] = 2.0
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(layout))
    done = run_cli("validate", path)
    assert "`vrep-maze generate --cell-size 2`" in done.stderr.decode()
    with pytest.raises(vrep_maze.ValidationError) as raised:
        vrep_maze.load(path)
    assert "`vrep_maze.generate(cell_size=2)` and the rest of its options" in str(raised.value)
    assert "--" not in str(raised.value)


def test_a_template_refusal_offers_generate_keywords(serve, tmp_path):
    # the course scene's `Line` is 0.6 x 0.1 m
    layout = vrep_maze.generate(seed=1, size=(5, 5), line_length=0.3, line_width=0.05)
    path = tmp_path / "m.json"
    layout.save(path)
    done = run_cli("apply", path, "--api", "zmq", "--port", serve.port("zmq"))
    assert done.returncode == 1
    assert ("generated with --line-length 0.3 --line-width 0.05: generate with --line-length 0.6"
            " --line-width 0.1 (and the layout's other options)") in done.stderr.decode()
    with pytest.raises(vrep_maze.SimulatorError) as raised:
        vrep_maze.apply(layout, api="zmq", port=serve.port("zmq"))
    said = str(raised.value).splitlines()[0]
    assert ("generated with line_length=0.3, line_width=0.05: generate with line_length=0.6,"
            " line_width=0.1 (and the layout's other options)") in said, said
    assert "--" not in said
