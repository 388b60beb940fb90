"""Seeded, reproducible grid mazes for CoppeliaSim (V-REP), from Python.

The Rust library behind the ``vrep-maze`` command, as a module: every function takes the
command's options as keywords, checks them with the command's own parser (a refused value
raises ``ValueError`` with the message ``vrep-maze`` prints), and gives the same mazes byte
for byte.

Example::

    import vrep_maze
    maze = vrep_maze.generate(seed=42, algo="prim")      # a Layout
    maze.metrics["solution_cells"], maze.segments.shape  # what it is like, what to draw
    maze.render("maze.svg", solution=True)               # or just show `maze` in Jupyter
    vrep_maze.apply(maze, api="zmq")                     # into a running CoppeliaSim

- :func:`generate`, :func:`load`, :meth:`Layout.from_json` make a :class:`Layout`;
  :func:`batch` yields many.
- :func:`apply` draws a layout into CoppeliaSim (or ``vrep-maze serve``) and verifies it;
  :func:`clear` removes it. Both return a report. :func:`connect` keeps one connection
  open for many (a :class:`Session`: a new maze every episode without reconnecting).
- :func:`score` follows a robot while the simulation runs and grades its run: the report as
  a dict and the trajectory as an array; :meth:`Layout.grade` grades a trajectory of one's own.
- :class:`RobotLink` steps the scene's wheeled robot one simulation step a call;
  ``import vrep_maze.robot_env`` registers the Gymnasium environment
  ``vrep_maze/RobotMaze-v0`` built on it (a new seeded maze every episode).
- Errors: ``ValueError`` (a refused option), :class:`ValidationError` (an invalid layout),
  :class:`SimulatorError` (a simulator that does not answer or refuses, with ``hints``),
  :class:`Interrupted` (Ctrl-C stopped a drawing cleanly).
"""

from ._vrep_maze import (
    ApplyReport,
    Batch,
    ClearReport,
    Interrupted,
    Layout,
    RobotLink,
    Session,
    SimulatorError,
    ValidationError,
    __version__,
    apply,
    batch,
    clear,
    connect,
    generate,
    load,
    score,
)

__all__ = [
    "ApplyReport",
    "Batch",
    "ClearReport",
    "Interrupted",
    "Layout",
    "RobotLink",
    "Session",
    "SimulatorError",
    "ValidationError",
    "__version__",
    "apply",
    "batch",
    "clear",
    "connect",
    "generate",
    "load",
    "score",
]
