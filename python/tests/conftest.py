"""Shared fixtures: the repository's golden mazes, the pip-installed `vrep-maze` command, and
`vrep-maze serve` emulators to draw into."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MAZES = ROOT / "mazes"


def command() -> str:
    """The `vrep-maze` command the package installed beside this Python."""
    path = Path(sys.executable).parent / "vrep-maze"
    assert path.exists(), f"{path}: the package's vrep-maze command is not installed"
    return str(path)


def run_cli(*args, **kwargs) -> subprocess.CompletedProcess:
    """Runs the package's `vrep-maze` command; output captured as bytes."""
    return subprocess.run([command(), *map(str, args)], capture_output=True, timeout=120, **kwargs)


def in_python_names(message: str) -> str:
    """A command-line message as the Python API words it: `'--algo <ALGO>'` is `algo`,
    `invalid value 'x' for '--algo <ALGO>'` is `invalid value algo='x'`, `--size` is `size`."""
    keyword = lambda option: option.replace("-", "_")
    message = re.sub(r"invalid value ('[^']*') for '--([a-z-]+)(?: <[A-Z_]+>)?'",
                     lambda m: f"invalid value {keyword(m[2])}={m[1]}", message)
    message = re.sub(r"'--([a-z-]+)(?: <[A-Z_]+>)?'", lambda m: keyword(m[1]), message)
    return re.sub(r"(?<![\w-])--([a-z][a-z-]*)", lambda m: keyword(m[1]), message)


def cli_error(*args) -> str:
    """The error line `vrep-maze` prints for a refused command line, without `error: `."""
    done = run_cli(*args)
    assert done.returncode == 2, done
    first = done.stderr.decode().splitlines()[0]
    assert first.startswith("error: "), first
    return first[len("error: "):]


def golden_cases():
    """Every generated golden layout and the `generate` keywords that make it (imported ones
    are in `imported_goldens`)."""
    cases = []
    for path in sorted(MAZES.glob("*.json")):
        layout = json.loads(path.read_text())
        generator = layout["generator"]
        if generator["algorithm"] == "import":
            continue
        options = dict(seed=generator["seed"], algo=generator["algorithm"], **generator["options"])
        if "preset" not in options:  # a preset sets the size and the walls itself
            options["size"] = (layout["grid"]["columns"], layout["grid"]["rows"])
            if layout.get("style") == "walls":
                options.update(style="walls", **wall_keywords(layout))
        cases.append(pytest.param(path, options, id=path.stem))
    return cases


def wall_keywords(layout) -> dict:
    """The wall options that make `layout`'s walls: its template and its openings, named by
    the endpoint they open beside."""
    wall = layout["wall"]
    beside = {tuple(layout[end]["cell"]): end for end in ("start", "end")}
    opened = [beside[tuple(o["cell"])] for o in wall.get("openings", [])]
    return dict(wall_length=wall["length"], wall_thickness=wall["thickness"],
                wall_height=wall["height"], openings=",".join(opened) or "none")


def imported_goldens():
    """The golden layouts `vrep-maze import` made, with the drawing each came from."""
    return [pytest.param(path, id=path.stem) for path in sorted(MAZES.glob("*.json"))
            if json.loads(path.read_text())["generator"]["algorithm"] == "import"]


def big_course_scene(folder: Path) -> str:
    """The course scene with a 500 m `Floor` as a `serve --scene` file in `folder`, for mazes
    larger than the course's 10 m floor (which `apply` refuses to draw beyond)."""
    objects = {
        "10": ("Floor", "shape", [0.0, 0.0, 0.0], [500.0, 500.0, 0.0], [128, 128, 128]),
        "11": ("Maze", "dummy", [0.0, 0.0, 0.0], [0.01, 0.01, 0.01], [255, 255, 0]),
        "12": ("Line", "shape", [0.0, 0.0, 0.001], [0.6, 0.1, 0.0], [0, 255, 0]),
        "13": ("Start", "shape", [-4.0, -4.0, 0.002], [1.0, 1.0, 0.0], [0, 0, 255]),
        "14": ("End", "shape", [4.0, 4.0, 0.002], [1.0, 1.0, 0.0], [255, 0, 0]),
    }
    scene = {"naming": "plain", "next_handle": 15, "objects": {
        key: {"alias": name, "name": name, "handle": int(key), "type": kind, "parent": None,
              "position": position, "orientation": [0.0, 0.0, 0.0], "size": size,
              "colour": colour}
        for key, (name, kind, position, size, colour) in objects.items()}}
    path = folder / "big-course.json"
    path.write_text(json.dumps({"scene": scene}))
    return str(path)


class Serve:
    """A `vrep-maze serve --api both` process (one scene behind both APIs), instant timing."""

    def __init__(self, *extra: str):
        self.process = subprocess.Popen(
            [command(), "serve", "--api", "both", "--listen", "127.0.0.1:0",
             "--zmq-listen", "127.0.0.1:0", *extra],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        lines = [self.process.stdout.readline() for _ in range(2)]
        ports = [int(line.split("127.0.0.1:")[1].split()[0]) for line in lines]
        self.legacy_port, self.zmq_port = ports

    def port(self, api: str) -> int:
        return self.legacy_port if api == "legacy" else self.zmq_port

    def stop(self) -> str:
        """Stops it as Ctrl-C does; returns what it said on standard error."""
        self.process.send_signal(2)
        _, err = self.process.communicate(timeout=30)
        return err


@pytest.fixture
def serve():
    """A fresh emulator with the course scene and instant timing."""
    server = Serve("--timing", "instant")
    yield server
    if server.process.poll() is None:
        server.process.kill()
        server.process.wait()


@pytest.fixture
def in_tmp(tmp_path):
    """Runs the test in a temporary directory."""
    old = os.getcwd()
    os.chdir(tmp_path)
    yield tmp_path
    os.chdir(old)
