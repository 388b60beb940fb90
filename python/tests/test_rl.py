"""The learning formats end to end (the `rl` extra): our maze in Gymnasium-Robotics'
PointMaze, driven along our solution to the goal, and in MiniGrid, walked to the goal."""

import json

import gymnasium
import gymnasium_robotics
import numpy as np
import pytest

import vrep_maze
from conftest import MAZES, run_cli

gymnasium.register_envs(gymnasium_robotics)


def test_maze_map_is_the_block_grid_export_writes(tmp_path):
    layout = vrep_maze.load(MAZES / "dfs-9x9-seed42-walls.json")
    out = tmp_path / "m.pointmaze.json"
    assert run_cli("export", MAZES / "dfs-9x9-seed42-walls.json", "-o", out).returncode == 0
    written = json.loads(out.read_text())
    assert written == {"maze_map": layout.maze_map(),
                       "maze_size_scaling": layout.maze_size_scaling}
    assert len(written["maze_map"]) == 19 and len(written["maze_map"][0]) == 19


@pytest.mark.parametrize("style", ["lines", "walls"])
def test_pointmaze_reaches_our_goal_along_our_solution(style):
    layout = vrep_maze.generate(seed=3, size=(4, 3), style=style)
    # PointMaze fixes its block size at 1 m (maze_size_scaling is not an argument of it)
    env = gymnasium.make("PointMaze_UMaze-v3", maze_map=layout.maze_map(),
                         continuing_task=False, max_episode_steps=3000)
    maze = env.unwrapped.maze
    obs, _ = env.reset(seed=0)
    rows = 2 * layout.size[1] + 1
    waypoints = [maze.cell_rowcol_to_xy(np.array([2 * (layout.size[1] - 1 - y) + 1, 2 * x + 1]))
                 for x, y in layout.solution()]
    assert rows == len(layout.maze_map())
    np.testing.assert_allclose(obs["desired_goal"], waypoints[-1], atol=0.25 * maze.maze_size_scaling)
    target, terminated, steps = 0, False, 0
    while not terminated and steps < 3000:
        position, velocity = obs["observation"][:2], obs["observation"][2:]
        if target < len(waypoints) - 1 and np.linalg.norm(waypoints[target] - position) < 0.1:
            target += 1
        aim = waypoints[target] if target < len(waypoints) - 1 else obs["desired_goal"]
        action = np.clip(10.0 * (aim - position) - 1.0 * velocity, -1.0, 1.0)
        obs, reward, terminated, truncated, _ = env.step(action)
        assert not truncated
        steps += 1
    assert terminated and reward == 1.0
    env.close()


def test_minigrid_walks_our_solution_to_the_goal():
    from vrep_maze.minigrid import MazeEnv, solution_actions

    layout = vrep_maze.generate(seed=11, size=(6, 5))
    env = MazeEnv(layout)
    env.reset(seed=0)
    actions = solution_actions(layout)
    assert actions.count(2) == 2 * (len(layout.solution()) - 1)
    for i, action in enumerate(actions):
        _, reward, terminated, truncated, _ = env.step(action)
        assert terminated == (i == len(actions) - 1) and not truncated
    assert reward > 0


def test_minigrid_walls_are_the_maze_map():
    from minigrid.core.world_object import Wall
    from vrep_maze.minigrid import MazeEnv

    layout = vrep_maze.generate(seed=2, size=(3, 4), style="walls")
    env = MazeEnv(layout)
    env.reset(seed=0)
    for row, blocks in enumerate(layout.maze_map()):
        for column, block in enumerate(blocks):
            assert isinstance(env.unwrapped.grid.get(column, row), Wall) == (block == 1)


def test_without_minigrid_the_import_error_names_the_extra():
    import subprocess
    import sys

    code = ("import sys; sys.modules['minigrid'] = None\n"
            "import vrep_maze\n"
            "import vrep_maze.minigrid\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode != 0
    assert "pip install vrep-maze[rl]" in done.stderr.splitlines()[-1]
