"""score: following an emulated robot (`vrep-maze serve --robot`) and grading its run."""

import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import vrep_maze
from conftest import Serve

# The 3 x 3 course maze (DFS, seed 1): Start at floor (-1, -1), End at (1, -1); the solution
# goes up column 0, along the top row and down column 2: 6 m.
# At 2 m/s, 0.1 m a 50 ms step: a scorer slowed by a busy machine may miss four steps in a
# row and still see every half cell, as score needs to grade the run.
SOLUTION = "t,x,y,yaw\n0,-1,-1,0\n0.5,-1,-1,0\n1.5,-1,1,0\n2.5,1,1,0\n3.5,1,-1,0\n"


def maze():
    return vrep_maze.generate(seed=1, algo="dfs", size=(3, 3))


@pytest.fixture
def robot_serve(tmp_path):
    """An emulator (both APIs) whose Robot drives the solution at 2 m/s."""
    path = tmp_path / "path.csv"
    path.write_text(SOLUTION)
    server = Serve("--timing", "instant", "--idle-fps", "0", "--robot", str(path))
    yield server
    if server.process.poll() is None:
        server.process.kill()
        server.process.wait()


@pytest.mark.parametrize("api", ["legacy", "zmq"])
def test_a_perfect_run_gives_the_report_and_the_trajectory(robot_serve, api):
    report, trajectory = vrep_maze.score(maze(), api=api, port=robot_serve.port(api),
                                         start_simulation=True, timeout=60)
    assert report["complete"] and report["reached_end"]
    assert report["shortest_length_m"] == 6.0
    assert report["spl"] == pytest.approx(1.0)
    assert isinstance(trajectory, np.ndarray) and trajectory.shape == (report["samples"], 4)
    assert np.all(np.diff(trajectory[:, 0]) > 0), "by increasing simulation time"
    assert trajectory[-1, 1] == pytest.approx(1.0, abs=1e-6), "ends in End's column"


@pytest.mark.parametrize("api", ["legacy", "zmq"])
def test_a_session_draws_then_scores_on_one_connection(robot_serve, api):
    # what a training loop does each episode: draw the maze, run, grade, on one connection
    with vrep_maze.connect(api=api, port=robot_serve.port(api)) as sim:
        sim.apply(maze(), draw="mesh")
        report, trajectory = sim.score(maze(), start_simulation=True, timeout=60)
        assert report["complete"] and report["reached_end"], report
        assert report["spl"] == pytest.approx(1.0)
        assert trajectory.shape == (report["samples"], 4)
        # the connection stays open for the next episode's maze
        assert sim.inspect(maze())["layout"]["matches"]
        with pytest.raises(vrep_maze.SimulatorError, match="no object named `Rover`"):
            sim.score(maze(), robot="Rover", start_simulation=True)
    alone, _ = vrep_maze.score(maze(), api=api, port=robot_serve.port(api),
                               start_simulation=True, timeout=60)
    # the same report as the function's, run for run (the samples depend on timing)
    assert report.keys() == alone.keys()
    assert alone["complete"] and alone["shortest_length_m"] == report["shortest_length_m"]


def test_a_missing_robot_and_a_bad_option_raise(serve):
    with pytest.raises(vrep_maze.SimulatorError, match="no object named `Rover`"):
        vrep_maze.score(maze(), robot="Rover", port=serve.port("legacy"), start_simulation=True)
    with pytest.raises(ValueError, match="until"):
        vrep_maze.score(maze(), until="never")


def test_ctrl_c_ends_the_run_with_the_partial_report(tmp_path):
    path = tmp_path / "slow.csv"
    # a slow robot: 60 s to End
    path.write_text("t,x,y,yaw\n0,-1,-1,0\n20,-1,1,0\n40,1,1,0\n60,1,-1,0\n")
    server = Serve("--timing", "instant", "--idle-fps", "0", "--robot", str(path))
    try:
        process = subprocess.Popen([sys.executable, "-c", textwrap.dedent(f"""
            import vrep_maze
            maze = vrep_maze.generate(seed=1, algo="dfs", size=(3, 3))
            print("started", flush=True)
            try:
                vrep_maze.score(maze, port={server.legacy_port}, start_simulation=True, timeout=60)
            except vrep_maze.Interrupted as e:
                print("interrupted", e.report["complete"], e.report["incomplete_reason"],
                      e.trajectory.shape[0] == e.report["samples"], flush=True)
        """)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        assert process.stdout.readline().strip() == "started"
        # let it connect and follow a few steps
        time.sleep(1.5)
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=30)
        assert out.strip() == "interrupted False interrupted True", (out, err)
    finally:
        server.process.kill()
        server.process.wait()
