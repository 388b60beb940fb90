"""Curricula from Python: `vrep_maze.batch(..., where=...)` keeps what `batch --where` keeps."""

import json

import pytest

import vrep_maze
from conftest import run_cli


def test_where_keeps_what_the_command_keeps(tmp_path):
    condition = "solution_cells >= 30 and dead_ends <= 9"
    kept = list(vrep_maze.batch(range(12), size=(8, 8), where=condition))
    assert kept and len(kept) < 12
    # `where_`, the spelling of Python's keywords, is the same option
    assert [l.seed for l in vrep_maze.batch(range(12), size=(8, 8), where_=condition)] == [
        l.seed for l in kept]
    for layout in kept:
        assert layout.metrics["solution_cells"] >= 30 and layout.metrics["dead_ends"] <= 9
    done = run_cli("batch", "-q", "--size", "8x8", "--seeds", "0..12", "--where", condition,
                   "--out-dir", tmp_path)
    assert done.returncode == 0, done.stderr
    manifest = [json.loads(line) for line in (tmp_path / "manifest.jsonl").read_text().splitlines()]
    assert [entry["seed"] for entry in manifest] == [layout.seed for layout in kept]


def test_a_percentile_keeps_what_the_command_keeps(tmp_path):
    condition = "solution_cells >= p75"
    kept = list(vrep_maze.batch(range(12), size=(8, 8), where=condition))
    every = list(vrep_maze.batch(range(12), size=(8, 8)))
    lengths = sorted(layout.metrics["solution_cells"] for layout in every)
    # nearest rank: the 9th of 12
    assert [l.seed for l in kept] == [
        l.seed for l in every if l.metrics["solution_cells"] >= lengths[8]]
    assert 3 <= len(kept) < 12
    done = run_cli("batch", "-q", "--size", "8x8", "--seeds", "0..12", "--where", condition,
                   "--out-dir", tmp_path)
    assert done.returncode == 0, done.stderr
    manifest = [json.loads(line) for line in (tmp_path / "manifest.jsonl").read_text().splitlines()]
    assert [entry["seed"] for entry in manifest] == [layout.seed for layout in kept]


def test_a_bad_condition_is_a_value_error_naming_the_position():
    with pytest.raises(ValueError, match="at position 0: unknown metric 'solution_length'"):
        vrep_maze.batch(range(3), where="solution_length >= 40")
