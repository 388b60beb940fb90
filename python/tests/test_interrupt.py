"""Ctrl-C: during a long generation and during a drawing, as the command line handles it."""

import signal
import subprocess
import sys
import textwrap
import time

import pytest

import vrep_maze
from conftest import Serve, big_course_scene

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="sends SIGINT")


def start(script: str) -> subprocess.Popen:
    """Runs `script` in a new Python; returns once it printed its first line."""
    process = subprocess.Popen([sys.executable, "-c", textwrap.dedent(script)],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert process.stdout.readline().strip() == "started"
    return process


def test_ctrl_c_during_a_long_generation_raises_keyboard_interrupt_at_once():
    process = start("""
        import vrep_maze
        print("started", flush=True)
        vrep_maze.generate(seed=1, algo="aldous-broder", size=(4096, 4096))
        print("finished", flush=True)
    """)
    time.sleep(0.5)
    sent = time.monotonic()
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    assert time.monotonic() - sent < 2, "KeyboardInterrupt waited for the generation"
    assert "finished" not in out
    assert "KeyboardInterrupt" in err


# sizes that take several seconds on the emulated real CoppeliaSim's timing
@pytest.mark.parametrize("api, size", [("legacy", 40), ("zmq", 30)])
def test_ctrl_c_during_apply_stops_cleanly_and_the_same_call_finishes_the_maze(api, size, tmp_path):
    server = Serve("--timing", "realistic", "--scene", big_course_scene(tmp_path))
    try:
        process = start(f"""
            import sys, vrep_maze
            layout = vrep_maze.generate(seed=5, size=({size}, {size}))
            print("started", flush=True)
            try:
                vrep_maze.apply(layout, api="{api}", port={server.port(api)})
            except vrep_maze.Interrupted as e:
                print("interrupted", e.placed, e.total, e, flush=True)
                sys.exit(130)
            print("finished", flush=True)
        """)
        time.sleep(1.5)
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=120)
        assert process.returncode == 130, (out, err)
        words = next(l for l in out.splitlines() if l.startswith("interrupted ")).split()
        placed, total = int(words[1]), int(words[2])
        layout = vrep_maze.generate(seed=5, size=(size, size))
        assert placed < total == len(layout.segments)
        assert "the idle rate is restored and the connection closed cleanly" in out
        assert "finishing what is in flight" in err
        report = vrep_maze.apply(layout, api=api, port=server.port(api))
        assert report.verified and report.pasted + report.reused == total - 1
        assert report.reused > 0
    finally:
        server.process.kill()
        server.process.wait()
