"""Reset and step times of `vrep_maze/RobotMaze-v0` on running CoppeliaSims, beside
Gymnasium-Robotics' PointMaze (MuJoCo) and `sim.step` alone (the baseline) timed in the same run.

    python bench/robot_env.py --port 23100                    # one simulator
    python bench/robot_env.py --port 23100 --port 23102       # and AsyncVectorEnv over both

Each simulator: `../shared/coppeliasim/sim.sh start 4.10.0 --zmq-port P --robot --display`
(`--display` for the camera rows). Prints one markdown table: median and p99 in ms, and
steps a second. Not run by CI: timings are only reported, never asserted.
"""

from __future__ import annotations

import argparse
import statistics
import time

import gymnasium as gym
import numpy as np

import vrep_maze
import vrep_maze.robot_env  # noqa: F401  (registers vrep_maze/RobotMaze-v0)
from vrep_maze.robot_env import ENV_ID, vector_env


def percentiles(seconds: list[float]) -> tuple[float, float]:
    ordered = sorted(seconds)
    p99 = ordered[min(len(ordered) - 1, int(round(0.99 * (len(ordered) - 1))))]
    return statistics.median(ordered) * 1e3, p99 * 1e3


def time_env(env, resets: int, steps: int) -> tuple[list[float], list[float]]:
    """Times `resets` resets (a new maze each) and `steps` steps (resetting when one ends)."""
    reset_times, step_times = [], []
    env.reset(seed=0)  # warm: connections made, templates created
    for k in range(resets):
        began = time.perf_counter()
        env.reset(seed=k + 1)
        reset_times.append(time.perf_counter() - began)
    env.reset(seed=resets + 1)
    for _ in range(steps):
        action = env.action_space.sample()
        began = time.perf_counter()
        _, _, terminated, truncated, _ = env.step(action)
        step_times.append(time.perf_counter() - began)
        if terminated or truncated:
            env.reset()
    return reset_times, step_times


def bare_steps(port: int, steps: int, dynamics: bool = True) -> list[float]:
    """`sim.step` alone over the official client (stepping on, the camera spared): the
    simulator's own step, the floor under the environment's; without `dynamics`, the
    step without the physics engine (`sim.boolparam_dynamics_handling_enabled` off)."""
    from coppeliasim_zmqremoteapi_client import RemoteAPIClient

    sim = RemoteAPIClient("127.0.0.1", port).require("sim")
    idle = sim.getInt32Param(sim.intparam_idle_fps)
    camera = sim.getObject("/camera")
    flag = sim.getExplicitHandling(camera)
    sim.setInt32Param(sim.intparam_idle_fps, 0)
    sim.setExplicitHandling(camera, 1)
    sim.setBoolParam(sim.boolparam_dynamics_handling_enabled, dynamics)
    sim.setStepping(True)
    sim.startSimulation()
    times = []
    try:
        for _ in range(steps):
            began = time.perf_counter()
            sim.step()
            times.append(time.perf_counter() - began)
    finally:
        sim.setBoolParam(sim.boolparam_dynamics_handling_enabled, True)
        sim.setStepping(False)
        sim.stopSimulation()
        while sim.getSimulationState() != sim.simulation_stopped:
            time.sleep(0.005)
        sim.setExplicitHandling(camera, flag)
        sim.setInt32Param(sim.intparam_idle_fps, idle)
    return times


def row(name: str, resets: list[float], steps: list[float]) -> str:
    reset = "| {:.1f} | {:.1f}".format(*percentiles(resets)) if resets else "| |"
    s50, s99 = percentiles(steps)
    return f"| {name} {reset} | {s50:.2f} | {s99:.2f} | {1e3 / s50:.0f} |"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--port", type=int, action="append", required=True)
    parser.add_argument("--resets", type=int, default=50)
    parser.add_argument("--steps", type=int, default=500)
    parser.add_argument("--size", default="5x5")
    parser.add_argument(
        "--stop-start",
        action="store_true",
        help="the AsyncVectorEnv rows with fast_reset=False (a stop and a start every episode)",
    )
    args = parser.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    print("| environment | reset median ms | reset p99 ms | step median ms | step p99 ms | steps/s |")
    print("|---|---|---|---|---|---|")
    bare = bare_steps(args.port[0], args.steps)
    print(row("sim.step alone (official client, the baseline)", [], bare))
    print(row("sim.step alone, physics off", [], bare_steps(args.port[0], args.steps, dynamics=False)))
    for obs in ("pose", "camera"):
        for fast in (False, True):
            env = gym.make(
                ENV_ID, port=args.port[0], size=size, obs=obs, max_episode_steps=400, fast_reset=fast
            )
            try:
                resets, steps = time_env(env, args.resets, args.steps)
            finally:
                env.close()
            kind = "" if fast else ", fast_reset=False"
            ratio = statistics.median(steps) / statistics.median(bare)
            print(row(f"RobotMaze-v0 {args.size} obs={obs}{kind} (step {ratio:.2f}x the baseline)", resets, steps))
    try:
        import gymnasium_robotics

        gym.register_envs(gymnasium_robotics)
        layout = vrep_maze.generate(seed=1, size=size)
        env = gym.make("PointMaze_UMaze-v3", maze_map=layout.maze_map(), max_episode_steps=400)
        resets, steps = time_env(env, args.resets, args.steps)
        env.close()
        print(row(f"PointMaze {args.size} (MuJoCo, Gymnasium-Robotics)", resets, steps))
    except ImportError as missing:
        print(f"| PointMaze | not installed ({missing}) | | | | |")
    for n in range(2, len(args.port) + 1):
        envs = vector_env(args.port[:n], size=size, max_episode_steps=400, fast_reset=not args.stop_start)
        try:
            envs.reset(seed=0)
            step_times = []
            for _ in range(args.steps // 2):
                began = time.perf_counter()
                envs.step(envs.action_space.sample())
                step_times.append(time.perf_counter() - began)
        finally:
            envs.close()
        s50, s99 = percentiles(step_times)
        kind = ", fast_reset=False" if args.stop_start else ""
        print(f"| AsyncVectorEnv x{n} obs=pose{kind} | | | {s50:.2f} | {s99:.2f} | {n * 1e3 / s50:.0f} (all envs) |")


if __name__ == "__main__":
    main()
