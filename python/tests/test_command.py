"""The `vrep-maze` command that pip installs: the binary's code and behaviour."""

import subprocess
import sys

from conftest import MAZES, Serve, command, run_cli


def test_generate_writes_the_golden_bytes():
    done = run_cli("generate", "--seed", 42, "--algo", "prim")
    assert done.returncode == 0
    assert done.stdout == (MAZES / "prim-9x9-seed42.json").read_bytes()


def test_version_help_and_exit_codes():
    version = run_cli("--version")
    assert version.returncode == 0 and version.stdout.decode().startswith("vrep-maze ")
    assert b"generate" in run_cli("--help").stdout
    refused = run_cli("generate", "--size", "0x9")
    assert refused.returncode == 2
    assert refused.stderr.decode().startswith("error: --size: ")
    invalid = run_cli("validate", MAZES / "nowhere.json")
    assert invalid.returncode == 1


def test_python_dash_m_runs_the_command():
    done = subprocess.run([sys.executable, "-m", "vrep_maze", "--version"], capture_output=True)
    assert done.returncode == 0 and done.stdout.startswith(b"vrep-maze ")


def test_a_reader_that_closes_the_pipe_early_ends_the_run_quietly():
    reader = subprocess.Popen([command(), "render", MAZES / "prim-20x15-seed7.json",
                               "--format", "svg"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    reader.stdout.read(10)
    reader.stdout.close()
    _, err = reader.communicate(timeout=30)
    assert reader.returncode == 0, err
    assert b"panicked" not in err


def test_serve_stops_on_ctrl_c_as_the_binary_does():
    server = Serve("--timing", "instant")
    err = server.stop()
    assert server.process.returncode == 0, err
    assert "vrep-maze serve: stopped with" in err
