"""`vrep_maze.connect`: one connection, many mazes; a lost connection and a restarted
simulator raise `SimulatorError` and leave the scene repairable; the call after one that
lost the connection connects again; `inspect` reports what `vrep-maze inspect --json` does."""

import json
import signal
import subprocess
import sys
import textwrap
import time

import pytest

import vrep_maze
from conftest import Serve, big_course_scene, command, run_cli


@pytest.mark.parametrize("api", ["legacy", "zmq"])
def test_one_session_replaces_mazes_then_clears(serve, api):
    with vrep_maze.connect(api=api, port=serve.port(api)) as sim:
        assert api in sim.description.lower() or "zeromq" in sim.description.lower()
        reports = [sim.apply(vrep_maze.generate(seed=seed), draw="mesh") for seed in (1, 2, 3)]
        assert all(r.verified and r.meshes == 1 for r in reports), reports
        assert [r.pasted for r in reports] == [1, 1, 1], "each maze replaces the last"
        cleared = sim.clear()
        assert cleared.removed_meshes, cleared
    with pytest.raises(ValueError, match="the session is closed"):
        sim.apply(vrep_maze.generate(seed=4))


def test_a_legacy_sessions_repr_names_its_host_and_port(serve):
    port = serve.legacy_port
    with vrep_maze.connect(api="legacy", port=port) as sim:
        assert sim.description == f"legacy remote API at 127.0.0.1:{port}"
        assert repr(sim) == f"<Session legacy remote API at 127.0.0.1:{port}>"


@pytest.mark.parametrize("api", ["legacy", "zmq"])
def test_inspect_in_a_session_reports_what_the_command_reports(serve, api, tmp_path):
    maze = vrep_maze.generate(seed=5, size=(6, 5))
    other = vrep_maze.generate(seed=6, size=(6, 5))
    path = tmp_path / "maze.json"
    maze.save(path)
    with vrep_maze.connect(api=api, port=serve.port(api)) as sim:
        empty = sim.inspect()
        assert empty["maze"]["lines"] == 0 and empty["maze"]["meshes"] == [], empty["maze"]
        assert "layout" not in empty
        sim.apply(maze, draw="mesh")
        report = sim.inspect(maze)
        assert report["layout"]["matches"], report["layout"]
        assert len(report["maze"]["meshes"]) == 1, report["maze"]
        differs = sim.inspect(other)
        assert not differs["layout"]["matches"] and differs["layout"]["differences"]
        # the idle rate as the user left it, not as raised while reading
        assert report["idle_fps"] == empty["idle_fps"]
    done = run_cli("inspect", "--api", api, "--port", serve.port(api), "--layout", path, "--json")
    assert done.returncode == 0, done.stderr
    cli = json.loads(done.stdout)
    # the same document but where the two name the connection and the layout's file
    for r in (report, cli):
        r.pop("connection")
        r["layout"].pop("file")
    assert report == cli


def test_a_stopped_simulator_raises_and_the_session_closes(serve):
    port = serve.zmq_port
    sim = vrep_maze.connect(api="zmq", port=port, timeout=1)
    sim.apply(vrep_maze.generate(seed=1), draw="mesh")
    serve.stop()
    with pytest.raises(vrep_maze.SimulatorError, match="nothing listens there any more"):
        sim.apply(vrep_maze.generate(seed=2), draw="mesh")
    sim.close()
    with pytest.raises(ValueError, match="the session is closed"):
        sim.clear()


def test_a_restarted_simulator_on_the_same_port(serve):
    port = serve.zmq_port
    sim = vrep_maze.connect(api="zmq", port=port, timeout=1)
    sim.apply(vrep_maze.generate(seed=1), draw="mesh")
    serve.stop()
    again = subprocess.Popen(
        [command(), "serve", "--api", "zmq", "--listen", f"127.0.0.1:{port}", "--timing", "instant"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert str(port) in again.stdout.readline()
        # no call while it was down: the session's next call reaches the new simulator,
        # whose fresh scene it surveys, draws and verifies
        report = sim.apply(vrep_maze.generate(seed=2), draw="mesh")
        assert report.verified and report.pasted == 1 and report.reused == 0, report
        with vrep_maze.connect(api="zmq", port=port) as fresh:
            assert fresh.apply(vrep_maze.generate(seed=3), draw="mesh").verified
    finally:
        sim.close()
        again.kill()
        again.wait()


@pytest.mark.parametrize("api", ["legacy", "zmq"])
def test_a_call_that_failed_on_a_dead_simulator_leaves_the_session_to_reconnect(serve, api):
    port = serve.port(api)
    sim = vrep_maze.connect(api=api, port=port, timeout=1, connect_timeout=2)
    sim.apply(vrep_maze.generate(seed=1), draw="mesh")
    serve.stop()
    with pytest.raises(vrep_maze.SimulatorError):
        sim.apply(vrep_maze.generate(seed=2), draw="mesh")
    again = subprocess.Popen(
        [command(), "serve", "--api", api, "--listen", f"127.0.0.1:{port}", "--timing", "instant"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert str(port) in again.stdout.readline()
        # the failed call lost the connection: the next one connects again and draws on
        # the new simulator's fresh scene
        report = sim.apply(vrep_maze.generate(seed=2), draw="mesh")
        assert report.verified and report.pasted == 1 and report.reused == 0, report
        assert sim.clear().removed_meshes
    finally:
        sim.close()
        again.kill()
        again.wait()


@pytest.mark.skipif(sys.platform == "win32", reason="sends SIGINT")
def test_ctrl_c_in_a_session_stops_cleanly_and_the_session_finishes_the_maze(tmp_path):
    server = Serve("--timing", "realistic", "--scene", big_course_scene(tmp_path))
    try:
        process = subprocess.Popen([sys.executable, "-c", textwrap.dedent(f"""
            import vrep_maze
            layout = vrep_maze.generate(seed=5, size=(60, 60))
            with vrep_maze.connect(api="zmq", port={server.zmq_port}) as sim:
                print("started", flush=True)
                try:
                    sim.apply(layout)
                except vrep_maze.Interrupted as e:
                    print("interrupted", e.placed, e.total, e, flush=True)
                report = sim.apply(layout)
                print("finished", report.verified, report.reused, flush=True)
        """)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        # a 60x60 drawn as copies at realistic timing takes several seconds, so the Ctrl-C
        # 1.5 s after the start lands in the first apply on a fast machine too (a 30x30 was
        # sometimes drawn before it, and the signal then hit the second apply)
        # connect says on standard output which API answered, then the script starts
        lines = iter(process.stdout.readline, "")
        assert "started" in (line.strip() for line in lines), process.stderr.read()
        time.sleep(1.5)
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=120)
        assert process.returncode == 0, (out, err)
        words = next(l for l in out.splitlines() if l.startswith("interrupted ")).split()
        assert int(words[1]) < int(words[2]), out
        assert "the idle rate is restored" in out
        finished = next(l for l in out.splitlines() if l.startswith("finished ")).split()
        assert finished[1] == "True" and int(finished[2]) > 0, out
    finally:
        server.process.kill()
        server.process.wait()


@pytest.mark.skipif(sys.platform == "win32", reason="sends SIGINT")
def test_ctrl_c_after_the_last_request_of_an_apply_raises_interrupted_with_placed(tmp_path):
    # the maze drawn once, each later apply places nothing: it makes no request a Ctrl-C
    # could stop before, so one that lands in it comes too late to stop the drawing. It
    # raises `Interrupted` with everything placed, as an earlier one raises it with what was
    # placed so far, never a bare `KeyboardInterrupt`.
    server = Serve("--timing", "realistic", "--scene", big_course_scene(tmp_path))
    try:
        process = subprocess.Popen([sys.executable, "-c", textwrap.dedent(f"""
            import vrep_maze
            layout = vrep_maze.generate(seed=5, size=(20, 20))
            with vrep_maze.connect(api="zmq", port={server.zmq_port}) as sim:
                sim.apply(layout)
                print("started", flush=True)
                while True:
                    try:
                        sim.apply(layout)
                    except vrep_maze.Interrupted as e:
                        print("interrupted", e.placed, e.total, e, flush=True)
                        break
                    except KeyboardInterrupt:
                        # landed in Python between two applies: not the case tested
                        print("between applies", flush=True)
                print("finished", sim.inspect(layout)["layout"]["matches"], flush=True)
        """)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        lines = iter(process.stdout.readline, "")
        assert "started" in (line.strip() for line in lines), process.stderr.read()
        # each Ctrl-C gives one line; one that lands between two applies is sent again
        seen = []
        for _ in range(20):
            time.sleep(0.3)
            process.send_signal(signal.SIGINT)
            seen.append(process.stdout.readline())
            if seen[-1].startswith("interrupted "):
                break
        out, err = process.communicate(timeout=120)
        out = "".join(seen) + out
        assert process.returncode == 0, (out, err)
        words = next(l for l in out.splitlines() if l.startswith("interrupted ")).split()
        total = len(vrep_maze.generate(seed=5, size=(20, 20)).segments)
        assert int(words[1]) == int(words[2]) == total, out
        assert "after the maze was drawn and verified" in out
        assert "finished True" in out
    finally:
        server.process.kill()
        server.process.wait()
