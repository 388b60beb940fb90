"""The manual's Python example and examples/course_maze.py, run against `vrep-maze serve`."""

import re
import subprocess
import sys

from conftest import ROOT


def readme_example() -> str:
    """The Python code block of the manual's Python section (docs/manual.md)."""
    section = ROOT.joinpath("docs", "manual.md").read_text().split("\n## Python\n", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_readme_example_works(serve, tmp_path):
    code = readme_example()
    # the manual draws into the default port; here the emulator listens on a free one
    drawn = "vrep_maze.apply(maze)"
    assert drawn in code
    code = code.replace(drawn, f"vrep_maze.apply(maze, port={serve.legacy_port})")
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "drew 160 lines: 1 kept (the template" in done.stdout and "159 pasted" in done.stdout
    assert (tmp_path / "maze.json").read_bytes() == (ROOT / "mazes/prim-9x9-seed42.json").read_bytes()
    assert (tmp_path / "maze.svg").exists()


def test_the_course_script_draws_and_redraws(serve, tmp_path):
    script = ROOT / "examples" / "course_maze.py"
    run = lambda *args: subprocess.run(
        [sys.executable, script, "--port", str(serve.legacy_port), *args],
        cwd=tmp_path, capture_output=True, text=True, timeout=120)
    first = run("--seed", "42", "--save", "m.json")
    assert first.returncode == 0, first.stderr
    assert "dfs seed 42" in first.stdout and "verified" in first.stdout
    assert (tmp_path / "m.json").read_bytes() == (ROOT / "mazes/dfs-9x9-seed42.json").read_bytes()
    second = run("--seed", "7", "--algo", "prim")
    # the second maze keeps the first one's copies where it can
    assert second.returncode == 0 and " kept (the template and " in second.stdout
    refused = run("--size", "0x9")
    # the library names the keyword argument (size=), the script passes --size to it
    assert refused.returncode == 2 and "error: size: grid size 0x9" in refused.stderr
