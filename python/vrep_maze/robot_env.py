"""Learn inside CoppeliaSim: ``vrep_maze/RobotMaze-v0``, the course robot in a new seeded maze
every episode.

``import vrep_maze.robot_env`` registers the environment with Gymnasium. It needs a running
CoppeliaSim with the course robot (``sim.sh start 4.10.0 --robot``, or any scene with a
differential-drive robot whose parts are named as ``vrep-maze drive --wheels`` takes them)
and Gymnasium (``pip install vrep-maze[rl]``)::

    import gymnasium as gym
    import vrep_maze.robot_env

    env = gym.make("vrep_maze/RobotMaze-v0", port=23000, size=(5, 5), obs="pose")
    obs, info = env.reset(seed=1)          # a new maze drawn, the robot at Start
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
    env.close()                             # simulation stopped, what was changed put back

An episode: ``reset`` draws the episode's maze (``draw="mesh"`` by default) over one open
:class:`vrep_maze.Session` and puts the robot at Start facing the first passage, at rest, in a
physics world made afresh. The first reset starts the simulation in stepping mode; the later
ones leave it running (``fast_reset``, the default): the maze is drawn into the running
simulation and the robot put back in one request, the physics engine's world ended and made
again from the scene (dynamics handling turned off and on), which saves a stop and a start
(about half a reset). Either way an episode runs as every other with the same seed and
actions, to the last bit. ``fast_reset=False`` stops and starts the simulation every episode
instead, which also puts back any other object a run moved (a fast reset puts back the robot
only). Each ``step`` sets the two wheel
velocities (rad/s) and advances the simulation one step (50 ms in the course scene). The episode ends (``terminated``) when the robot's centre
enters ``End``'s footprint, as ``vrep-maze score`` decides it, and is ``truncated`` after
``max_episode_steps``. Reward: ``goal_reward`` on reaching End, minus ``step_penalty`` every
step.

Seeding: the maze of an episode is drawn from the environment's generator, so
``reset(seed=s)`` gives the same maze, the same start and (the simulation being stepped) the
same episode for the same actions.

Many simulators at once: :func:`vector_env` makes a ``gymnasium.vector.AsyncVectorEnv`` over
a list of ports, one simulator each.
"""

from __future__ import annotations

import math
from typing import Any, Optional, Sequence

try:
    import gymnasium as gym
    from gymnasium import spaces
except ImportError as missing:  # pragma: no cover - the message is the point
    raise ImportError(
        f"vrep_maze.robot_env needs Gymnasium ({missing}): pip install vrep-maze[rl]"
    ) from missing

import numpy as np

from . import _vrep_maze as _vm

__all__ = ["ENV_ID", "RobotMazeEnv", "vector_env"]

ENV_ID = "vrep_maze/RobotMaze-v0"

# maze keywords passed to vrep_maze.generate / vrep_maze.batch as they are
_MAZE_KEYWORDS = (
    "cell_size",
    "line_length",
    "line_width",
    "wall_length",
    "wall_thickness",
    "wall_height",
    "growing",
    "bias",
)

# the scene's names, as vrep-maze drive takes them
_NAME_KEYWORDS = ("robot", "left_motor", "right_motor", "camera", "floor", "line")

# how many seeds a `where` condition is tried on before the episode fails
_WHERE_TRIES = 4096

# bounds of the pose observation's positions, metres (a robot thrown off a 1 km floor is
# clipped to it)
_FAR = 1000.0


class RobotMazeEnv(gym.Env):
    """The course robot in a new maze every episode, in a running CoppeliaSim.

    Keywords:

    - connection: ``api`` (``"zmq"``: the simulation is stepped over ZeroMQ), ``host``,
      ``port``, ``connect_timeout``, ``timeout``;
    - the maze, as :func:`vrep_maze.generate` takes it: ``size`` (``(5, 5)``), ``algo``
      (``"dfs"``), ``braid``, ``style`` (``"lines"`` or ``"walls"``), ``cell_size``,
      ``line_length``, ``line_width``, ``wall_length``, ``wall_thickness``,
      ``wall_height``; ``where``: a condition on its metrics as ``vrep-maze batch --where``
      takes it (a curriculum: ``"solution_cells >= 12"``); ``draw``: ``"mesh"`` (default) or
      ``"copies"``; ``create_missing`` (default ``True``): the templates a maze needs and the
      scene lacks (``Wall`` and ``Post`` of a wall maze in the course scene) are made by the
      first reset as ``vrep-maze apply --create-missing`` makes them, static and respondable;
    - the robot: ``obs`` (``"pose"``: ``[x, y, yaw, goal_x, goal_y]``; ``"camera"``: the
      camera's image, ``uint8``, ``camera_size`` ``(width, height)``, default ``(64, 64)``),
      ``wheel_max`` (rad/s, the action's bound), the scene's names (``robot``,
      ``left_motor``, ``right_motor``, ``camera``, ``floor``, ``line``);
    - the task: ``max_episode_steps`` (1000), ``goal_reward`` (1.0), ``step_penalty`` (0.0);
    - ``fast_reset`` (``True``): resets after the first leave the simulation running (see
      the module's text); ``False`` stops and starts it every episode;
    - ``render_mode``: ``"rgb_array"`` returns the camera's latest image.

    ``info`` holds ``"pose"`` (``x, y, yaw`` in the floor's frame), ``"waypoints"`` (the
    solution's cell centres from start to end, floor frame, a tuple of ``(x, y)``), ``"seed"`` and
    ``"metrics"`` of the episode's maze, ``"time"`` (simulated seconds since the episode
    began) and, once the
    episode ends, ``"score"``: the run graded as ``vrep-maze score`` grades one (SPL, cells
    visited, ...).
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(
        self,
        *,
        api: str = "zmq",
        host: Optional[str] = None,
        port: Optional[int] = None,
        size: Sequence[int] = (5, 5),
        algo: str = "dfs",
        braid: Optional[float] = None,
        style: str = "lines",
        where: Optional[str] = None,
        draw: str = "mesh",
        create_missing: bool = True,
        obs: str = "pose",
        camera_size: Sequence[int] = (64, 64),
        max_episode_steps: int = 1000,
        wheel_max: float = 10.0,
        goal_reward: float = 1.0,
        step_penalty: float = 0.0,
        fast_reset: bool = True,
        connect_timeout: Optional[float] = None,
        timeout: Optional[float] = None,
        render_mode: Optional[str] = None,
        **keywords: Any,
    ) -> None:
        unknown = sorted(set(keywords) - set(_MAZE_KEYWORDS) - set(_NAME_KEYWORDS))
        if unknown:
            raise TypeError(f"RobotMazeEnv: unknown keyword(s) {', '.join(unknown)}")
        if obs not in ("pose", "camera"):
            raise ValueError(f'obs must be "pose" or "camera", got {obs!r}')
        if draw not in ("mesh", "copies"):
            raise ValueError(f'draw must be "mesh" or "copies", got {draw!r}')
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f'render_mode must be None or "rgb_array", got {render_mode!r}')
        if not (isinstance(max_episode_steps, int) and max_episode_steps > 0):
            raise ValueError(f"max_episode_steps must be a positive int, got {max_episode_steps!r}")
        if not (math.isfinite(wheel_max) and wheel_max > 0):
            raise ValueError(f"wheel_max must be a positive number of rad/s, got {wheel_max!r}")
        width, height = (int(v) for v in camera_size)
        self.obs_kind = obs
        self.draw = draw
        self.create_missing = bool(create_missing)
        self.render_mode = render_mode
        self.max_episode_steps = max_episode_steps
        self.goal_reward = float(goal_reward)
        self.step_penalty = float(step_penalty)
        self.where = where
        self.fast_reset = bool(fast_reset)
        self.maze_options = {"algo": algo, "size": tuple(size), "style": style}
        if braid is not None:
            self.maze_options["braid"] = braid
        self.maze_options.update({k: keywords[k] for k in _MAZE_KEYWORDS if k in keywords})
        # a maze made now checks the maze keywords before anything connects
        _vm.generate(seed=0, **self.maze_options)
        connection = {"api": api, "host": host, "port": port}
        connection.update(
            {k: v for k, v in (("connect_timeout", connect_timeout), ("timeout", timeout)) if v is not None}
        )
        names = {k: keywords[k] for k in _NAME_KEYWORDS if k in keywords}
        self._draw_names = {k: names[k] for k in ("floor", "line") if k in names}
        self._camera = obs == "camera" or render_mode == "rgb_array"
        self.session = _vm.connect(**connection)
        try:
            self.link = _vm.RobotLink(**connection, **names)
            if self._camera:
                self.link.set_camera_size(width, height)
        except BaseException:
            self.session.close()
            raise
        self.action_space = spaces.Box(-wheel_max, wheel_max, shape=(2,), dtype=np.float32)
        if obs == "pose":
            low = np.array([-_FAR, -_FAR, -math.pi, -_FAR, -_FAR], dtype=np.float32)
            self.observation_space = spaces.Box(low, -low, dtype=np.float32)
        else:
            self.observation_space = spaces.Box(0, 255, shape=(height, width, 3), dtype=np.uint8)
        self.layout: Optional[_vm.Layout] = None
        self._episodes = 0
        self._drawn_running = False
        self._ended = False
        self._start_time = 0.0
        self._reading = None
        self._steps = 0
        self._trajectory: list[tuple[float, float, float, float]] = []
        self._goal = np.zeros(2)
        self._waypoints = np.zeros((0, 2))

    # -- the episode's maze

    def _next_maze(self) -> _vm.Layout:
        seed = int(self.np_random.integers(0, 2**32))
        if self.where is None:
            return _vm.generate(seed=seed, **self.maze_options)
        options = {k: v for k, v in self.maze_options.items() if k != "style"}
        for layout in _vm.batch(range(seed, seed + _WHERE_TRIES), where=self.where, **options):
            if self.maze_options["style"] == "lines":
                return layout
            # batch makes line mazes: the wall maze of the same seed has the same passages
            return _vm.generate(seed=layout.seed, **self.maze_options)
        raise RuntimeError(
            f"no maze of seeds {seed}..{seed + _WHERE_TRIES - 1} meets where={self.where!r}"
        )

    # -- Gymnasium's API

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        layout = self._next_maze()
        # the first episode starts the simulation; with fast_reset the later ones draw into it
        # as it runs (what is drawn then lasts until it stops: close draws the last maze again)
        running = self.fast_reset and self._episodes > 0
        if not running:
            self.link.end()
        self.session.apply(
            layout,
            draw=self.draw,
            stop_simulation=not running,
            while_running=running,
            # the first reset makes what is missing; a later one would only look again
            create_missing=self.create_missing and self._episodes == 0,
            **self._draw_names,
        )
        self.layout = layout
        self._episodes += 1
        self._drawn_running |= running
        self._ended = False
        points = layout.waypoints()
        # a turn's cell has two rows (arrival, departure): the cell centres once each
        centres = [points[0, :2]]
        for row in points[1:, :2]:
            if np.hypot(*(row - centres[-1])) > 1e-9:
                centres.append(row)
        self._waypoints = np.array(centres)
        self._goal = self._waypoints[-1]
        x, y, yaw = points[0, :3]
        self._reading = self.link.begin(
            float(x), float(y), float(yaw), camera=self._camera, keep_running=running
        )
        # times are the episode's own: the simulation's clock runs on across episodes
        self._start_time = float(self._reading[0])
        self._steps = 0
        self._trajectory = [self._sample()]
        return self._observation(), self._info()

    def step(self, action):
        if self.layout is None:
            raise RuntimeError("call reset() before step()")
        if self._ended:
            raise RuntimeError("the episode has ended: call reset()")
        left, right = np.clip(
            np.asarray(action, dtype=np.float64).reshape(2), self.action_space.low, self.action_space.high
        )
        self._reading = self.link.step(float(left), float(right), camera=self._camera)
        self._steps += 1
        self._trajectory.append(self._sample())
        _, pose, _, _ = self._reading
        terminated = bool(self.layout.reached_end(float(pose[0]), float(pose[1])))
        truncated = not terminated and self._steps >= self.max_episode_steps
        reward = (self.goal_reward if terminated else 0.0) - self.step_penalty
        info = self._info()
        if terminated or truncated:
            info["score"] = self.layout.grade(self._trajectory)
            self._ended = True
            if not self.fast_reset:
                self.link.end()
        return self._observation(), reward, terminated, truncated, info

    def render(self):
        if self.render_mode == "rgb_array" and self._reading is not None:
            return self._reading[3]
        return None

    def close(self):
        link, session = getattr(self, "link", None), getattr(self, "session", None)
        self.link = self.session = None
        # the stop removes the mazes drawn while the simulation ran (fast_reset): the last
        # one is drawn again on the stopped simulation, so the scene shows what the last
        # episode saw. Then the session closes, putting back the idle rate it found (the 0
        # the link set), and the link, putting back the user's.
        try:
            if link is not None:
                link.end()
            if session is not None and link is not None and getattr(self, "_drawn_running", False):
                session.apply(
                    self.layout,
                    draw=self.draw,
                    create_missing=self.create_missing,
                    **self._draw_names,
                )
        finally:
            try:
                if session is not None:
                    session.close()
            finally:
                if link is not None:
                    link.close()

    # -- what an observation and the info hold

    def _episode_time(self, time: float) -> float:
        """Simulated seconds since the episode began, to the microsecond: the simulation's
        clock runs on across episodes, and a difference of its times carries rounding that
        would make the same episode's times differ in the last bits."""
        return round(float(time) - self._start_time, 6)

    def _sample(self) -> tuple[float, float, float, float]:
        time, pose, _, _ = self._reading
        return (self._episode_time(time), float(pose[0]), float(pose[1]), float(pose[2]))

    def _observation(self):
        _, pose, _, image = self._reading
        if self.obs_kind == "camera":
            return image
        goal = self._goal
        obs = np.array([pose[0], pose[1], pose[2], goal[0], goal[1]], dtype=np.float32)
        return np.clip(obs, self.observation_space.low, self.observation_space.high)

    def _info(self) -> dict:
        time, pose, joints, _ = self._reading
        return {
            "pose": np.array(pose, dtype=np.float64),
            "joints": np.array(joints, dtype=np.float64),
            "time": self._episode_time(time),
            # a tuple, not an array: a vector env stacks arrays, and mazes differ in length
            "waypoints": tuple(map(tuple, self._waypoints.tolist())),
            "seed": self.layout.seed,
            "metrics": dict(self.layout.metrics),
        }


def vector_env(ports: Sequence[int], **keywords: Any) -> "gym.vector.AsyncVectorEnv":
    """A ``gymnasium.vector.AsyncVectorEnv`` of :class:`RobotMazeEnv` over ``ports``: one
    simulator each (a process each), the other keywords given to every one. The workers are
    spawned, not forked: a forked child would inherit the parent's connections without
    the threads that serve them."""
    if not ports:
        raise ValueError("vector_env needs at least one port")

    def maker(port: int):
        return lambda: RobotMazeEnv(port=port, **keywords)

    return gym.vector.AsyncVectorEnv([maker(p) for p in ports], context="spawn")


if ENV_ID not in gym.registry:
    gym.register(id=ENV_ID, entry_point="vrep_maze.robot_env:RobotMazeEnv")
