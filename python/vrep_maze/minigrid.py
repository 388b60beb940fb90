"""Our mazes as MiniGrid environments: ``MazeEnv(layout)``.

The grid is the layout's block grid (:meth:`Layout.maze_map`: ``2*height+1`` rows of
``2*width+1`` blocks, row 0 the north edge), a ``Wall`` on every wall block, the agent on the
start facing east and a ``Goal`` on the end. One step forward crosses half a cell, so a
cell-to-cell move is two ``forward`` actions. Needs the ``rl`` extra
(``pip install vrep-maze[rl]``)::

    import vrep_maze
    from vrep_maze.minigrid import MazeEnv, solution_actions
    layout = vrep_maze.generate(seed=7, size=(6, 6))
    env = MazeEnv(layout)
    env.reset(seed=0)
    for action in solution_actions(layout):
        _, reward, terminated, truncated, _ = env.step(action)
    assert terminated and reward > 0
"""

from __future__ import annotations

try:
    from minigrid.core.grid import Grid
    from minigrid.core.mission import MissionSpace
    from minigrid.core.world_object import Goal, Wall
    from minigrid.minigrid_env import MiniGridEnv
except ImportError as missing:  # pragma: no cover - the message is the point
    raise ImportError(
        f"vrep_maze.minigrid needs MiniGrid ({missing}): pip install vrep-maze[rl]"
    ) from missing

from ._vrep_maze import Layout

__all__ = ["MazeEnv", "solution_actions"]

MISSION = "reach the goal"

# MiniGrid's headings: 0 east, 1 south, 2 west, 3 north (x grows east, y grows south).
_HEADING = {(1, 0): 0, (0, 1): 1, (-1, 0): 2, (0, -1): 3}


def _block(layout: Layout, cell: tuple[int, int]) -> tuple[int, int]:
    """The MiniGrid position (x, y) of a cell: column 2x+1, row 2(height-1-y)+1."""
    x, y = cell
    return 2 * x + 1, 2 * (layout.size[1] - 1 - y) + 1


class MazeEnv(MiniGridEnv):
    """A MiniGrid environment of one layout: walls where the maze has them, the agent at the
    start facing east, the goal at the end. Keywords go to ``MiniGridEnv`` (``render_mode``,
    ``agent_view_size``, ...); ``max_steps`` defaults to four steps per block."""

    def __init__(self, layout: Layout, max_steps: int | None = None, **kwargs):
        self.layout = layout
        self.maze_map = layout.maze_map()
        height, width = len(self.maze_map), len(self.maze_map[0])
        super().__init__(
            mission_space=MissionSpace(mission_func=lambda: MISSION),
            width=width,
            height=height,
            max_steps=max_steps if max_steps is not None else 4 * width * height,
            see_through_walls=True,
            **kwargs,
        )

    def _gen_grid(self, width: int, height: int) -> None:
        self.grid = Grid(width, height)
        for row, blocks in enumerate(self.maze_map):
            for column, block in enumerate(blocks):
                if block == 1:
                    self.grid.set(column, row, Wall())
        self.put_obj(Goal(), *_block(self.layout, self.layout.end))
        self.agent_pos = _block(self.layout, self.layout.start)
        self.agent_dir = 0
        self.mission = MISSION


def solution_actions(layout: Layout) -> list[int]:
    """The MiniGrid actions (``left`` 0, ``right`` 1, ``forward`` 2) that walk the layout's
    solution from the start, facing east as :class:`MazeEnv` puts the agent, to the goal."""
    actions: list[int] = []
    heading = 0
    path = [_block(layout, cell) for cell in layout.solution()]
    for (x0, y0), (x1, y1) in zip(path, path[1:]):
        wanted = _HEADING[((x1 - x0) // 2, (y1 - y0) // 2)]
        turn = (wanted - heading) % 4
        actions += {0: [], 1: [1], 2: [1, 1], 3: [0]}[turn]
        heading = wanted
        actions += [2, 2]
    return actions
