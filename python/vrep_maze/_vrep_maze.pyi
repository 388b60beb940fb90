"""Type stubs of the extension module; see the docstrings for what each item does."""

from os import PathLike
from typing import Any, Iterable, Iterator, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

Pair = Union[str, Tuple[float, float], Sequence[float]]
Cell = Tuple[int, int]
StrPath = Union[str, PathLike[str]]
Api = Literal["legacy", "zmq", "auto"]

class ValidationError(ValueError):
    problems: list[str]

class SimulatorError(RuntimeError):
    hints: list[str]

class Interrupted(KeyboardInterrupt):
    placed: Optional[int]
    total: Optional[int]

class Layout:
    @staticmethod
    def from_json(text: str) -> Layout: ...
    def to_json(self) -> str: ...
    def save(self, path: StrPath) -> None: ...
    def validate(self) -> dict[str, int]: ...
    @property
    def metrics(self) -> dict[str, int]: ...
    @property
    def start(self) -> Cell: ...
    @property
    def end(self) -> Cell: ...
    @property
    def size(self) -> Tuple[int, int]: ...
    @property
    def seed(self) -> int: ...
    @property
    def algorithm(self) -> str: ...
    @property
    def passages(self) -> npt.NDArray[np.uint8]: ...
    def open(self, x: int, y: int, direction: str) -> bool: ...
    def solution(self) -> list[Cell]: ...
    def maze_map(self) -> list[list[Union[int, str]]]: ...
    @property
    def maze_size_scaling(self) -> float: ...
    def waypoints(
        self, *, start: Optional[Cell] = None
    ) -> npt.NDArray[np.float64]: ...
    @property
    def segments(self) -> npt.NDArray[np.float64]: ...
    @property
    def walls(self) -> npt.NDArray[np.float64]: ...
    @property
    def posts(self) -> npt.NDArray[np.float64]: ...
    @property
    def style(self) -> str: ...
    @overload
    def render(
        self, path: StrPath, *, format: Optional[str] = None, solution: bool = False
    ) -> None: ...
    @overload
    def render(
        self, path: None = None, *, format: Optional[str] = None, solution: bool = False
    ) -> Union[str, bytes]: ...
    def export(self, path: StrPath) -> None: ...
    def reached_end(self, x: float, y: float) -> bool: ...
    def grade(
        self, trajectory: Union[npt.ArrayLike, Sequence[Sequence[float]]], *, robot_radius: float = 0.1
    ) -> dict[str, Any]: ...
    def _repr_svg_(self) -> str: ...
    def __eq__(self, other: object) -> bool: ...

class ApplyReport:
    lines: int
    posts: int
    meshes: int
    reused: int
    pasted: int
    removed: int
    removed_meshes: int
    unchanged: int
    placed: int
    placed_unread: int
    markers_unchanged: int
    markers_placed: int
    nothing_to_do: bool
    warnings: list[str]
    left_alone: list[str]
    edits: int
    round_trips: int
    elapsed: float
    stopped_simulation: bool
    dry_run: bool
    verified: bool
    created: list[str]
    saved_scene: Optional[str]
    summary: str

class ClearReport:
    removed: list[str]
    removed_meshes: list[str]
    round_trips: int
    restored_idle_fps: Optional[int]
    stopped_simulation: bool
    dry_run: bool
    left_alone: list[str]
    template: Optional[str]
    markers: Optional[str]
    warnings: list[str]
    summary: str

class Batch(Iterator[Layout]):
    def __iter__(self) -> Batch: ...
    def __next__(self) -> Layout: ...
    def __len__(self) -> int: ...

def generate(
    seed: Optional[int] = None,
    algo: Optional[str] = None,
    size: Optional[Pair] = None,
    *,
    growing: Optional[str] = None,
    bias: Optional[str] = None,
    braid: Optional[float] = None,
    start: Optional[Pair] = None,
    end: Optional[Pair] = None,
    cell_size: Optional[float] = None,
    line_length: Optional[float] = None,
    line_width: Optional[float] = None,
    line_z: Optional[float] = None,
    marker_z: Optional[float] = None,
    origin: Optional[Pair] = None,
    rotation: Optional[float] = None,
    floor_size: Optional[Pair] = None,
    style: Optional[str] = None,
    wall_length: Optional[float] = None,
    wall_thickness: Optional[float] = None,
    wall_height: Optional[float] = None,
    openings: Optional[str] = None,
    posts: Optional[bool] = None,
    post_size: Optional[float] = None,
    preset: Optional[str] = None,
) -> Layout: ...
def load(path: StrPath) -> Layout: ...
def batch(
    seeds: Union[int, str, Iterable[int]],
    algo: Optional[str] = None,
    size: Optional[Pair] = None,
    *,
    min_solution: Optional[int] = None,
    max_dead_ends: Optional[float] = None,
    where: Optional[str] = None,
    where_: Optional[str] = None,
    growing: Optional[str] = None,
    bias: Optional[str] = None,
    braid: Optional[float] = None,
    start: Optional[Pair] = None,
    end: Optional[Pair] = None,
    cell_size: Optional[float] = None,
    line_length: Optional[float] = None,
    line_width: Optional[float] = None,
    line_z: Optional[float] = None,
    marker_z: Optional[float] = None,
    origin: Optional[Pair] = None,
    rotation: Optional[float] = None,
    floor_size: Optional[Pair] = None,
) -> Batch: ...
def apply(
    layout: Layout,
    api: Optional[Api] = None,
    host: Optional[str] = None,
    port: Optional[int] = None,
    *,
    floor: Optional[str] = None,
    parent: Optional[str] = None,
    line: Optional[str] = None,
    start: Optional[str] = None,
    end: Optional[str] = None,
    connect_timeout: Optional[float] = None,
    timeout: Optional[float] = None,
    stop_simulation: bool = False,
    while_running: bool = False,
    dry_run: bool = False,
    create_missing: bool = False,
    save_scene: Optional[str] = None,
    draw: Optional[Literal["copies", "mesh"]] = None,
    robot: Optional[str] = None,
    robot_width: Optional[float] = None,
) -> ApplyReport: ...
def clear(
    api: Optional[Api] = None,
    host: Optional[str] = None,
    port: Optional[int] = None,
    *,
    floor: Optional[str] = None,
    parent: Optional[str] = None,
    line: Optional[str] = None,
    start: Optional[str] = None,
    end: Optional[str] = None,
    connect_timeout: Optional[float] = None,
    timeout: Optional[float] = None,
    stop_simulation: bool = False,
    dry_run: bool = False,
) -> ClearReport: ...
class Session:
    description: str
    def apply(
        self,
        layout: Layout,
        *,
        floor: Optional[str] = None,
        parent: Optional[str] = None,
        line: Optional[str] = None,
        start: Optional[str] = None,
        end: Optional[str] = None,
        stop_simulation: bool = False,
        while_running: bool = False,
        dry_run: bool = False,
        create_missing: bool = False,
        save_scene: Optional[str] = None,
        draw: Optional[Literal["copies", "mesh"]] = None,
        robot: Optional[str] = None,
        robot_width: Optional[float] = None,
    ) -> ApplyReport: ...
    def clear(
        self,
        *,
        floor: Optional[str] = None,
        parent: Optional[str] = None,
        line: Optional[str] = None,
        start: Optional[str] = None,
        end: Optional[str] = None,
        stop_simulation: bool = False,
        dry_run: bool = False,
    ) -> ClearReport: ...
    def inspect(
        self,
        layout: Optional[Layout] = None,
        *,
        floor: Optional[str] = None,
        parent: Optional[str] = None,
        line: Optional[str] = None,
        start: Optional[str] = None,
        end: Optional[str] = None,
    ) -> dict[str, Any]: ...
    def score(
        self,
        layout: Layout,
        robot: Optional[str] = None,
        *,
        floor: Optional[str] = None,
        start_simulation: bool = False,
        timeout: Optional[float] = None,
        until: Optional[Literal["end", "stop"]] = None,
        robot_radius: Optional[float] = None,
        end_size: Optional[float] = None,
    ) -> Tuple[dict, npt.NDArray[np.float64]]: ...
    def drive(
        self,
        layout: Layout,
        wheels: bool = True,
        *,
        steer: Optional[Literal["pose", "camera"]] = None,
        robot: Optional[str] = None,
        left_motor: Optional[str] = None,
        right_motor: Optional[str] = None,
        camera: Optional[str] = None,
        speed: Optional[float] = None,
        wheel_radius: Optional[float] = None,
        track: Optional[float] = None,
        wheel_max: Optional[float] = None,
        sim_timeout: Optional[float] = None,
        run_timeout: Optional[float] = None,
        floor: Optional[str] = None,
        line: Optional[str] = None,
        start_simulation: bool = True,
    ) -> dict[str, Any]: ...
    def close(self) -> None: ...
    def __enter__(self) -> "Session": ...
    def __exit__(self, *exc: object) -> bool: ...

Reading = Tuple[
    float, npt.NDArray[np.float64], npt.NDArray[np.float64], Optional[npt.NDArray[np.uint8]]
]

class RobotLink:
    description: str
    def __init__(
        self,
        api: Optional[Api] = None,
        host: Optional[str] = None,
        port: Optional[int] = None,
        *,
        connect_timeout: Optional[float] = None,
        timeout: Optional[float] = None,
        robot: Optional[str] = None,
        left_motor: Optional[str] = None,
        right_motor: Optional[str] = None,
        camera: Optional[str] = None,
        floor: Optional[str] = None,
        line: Optional[str] = None,
    ) -> None: ...
    @property
    def geometry(self) -> Tuple[float, float]: ...
    def set_camera_size(self, width: int, height: int) -> None: ...
    def begin(
        self, x: float, y: float, yaw: float, camera: bool = False, keep_running: bool = False
    ) -> Reading: ...
    def step(self, left: float, right: float, camera: bool = False) -> Reading: ...
    def end(self) -> None: ...
    def close(self) -> None: ...
    def __enter__(self) -> "RobotLink": ...
    def __exit__(self, *exc: object) -> bool: ...

def connect(
    api: Optional[Api] = None,
    host: Optional[str] = None,
    port: Optional[int] = None,
    *,
    connect_timeout: Optional[float] = None,
    timeout: Optional[float] = None,
) -> Session: ...
def score(
    layout: Layout,
    robot: Optional[str] = None,
    api: Optional[Api] = None,
    host: Optional[str] = None,
    port: Optional[int] = None,
    *,
    floor: Optional[str] = None,
    connect_timeout: Optional[float] = None,
    reply_timeout: Optional[float] = None,
    start_simulation: bool = False,
    timeout: Optional[float] = None,
    until: Optional[Literal["end", "stop"]] = None,
    robot_radius: Optional[float] = None,
    end_size: Optional[float] = None,
) -> Tuple[dict, npt.NDArray[np.float64]]: ...
def main(argv: list[str]) -> int: ...
