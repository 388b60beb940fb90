#!/usr/bin/env bash
# The exported robot-simulator files read by each simulator's own parser: MuJoCo (PyPI
# `mujoco`, in the project's .venv), libsdformat's `ign sdf` and urdfdom's `check_urdf`
# (Debian packages, installed here when missing). Webots has no installable parser: its
# export is checked for structure by the unit tests only. The ROS map (`-o maze.yaml`) is
# read by PyYAML and Pillow with map_server's rules (tests/conformance/ros_map.py): no ROS
# map loader installs from PyPI or Debian.
# Prints `export-parsers: N passed, M failed`, then `ros-map: N passed, M failed` last;
# exits non-zero on failure.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
if ! command -v check_urdf >/dev/null || ! ign sdf --help >/dev/null 2>&1; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
        liburdfdom-tools libsdformat-dev ignition-tools >/dev/null
fi
venv="$root/.venv"
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import mujoco, yaml, PIL" 2>/dev/null; then
    "$venv/bin/pip" install --quiet mujoco pyyaml pillow
fi
cargo build --quiet --bin vrep-maze
bin="${CARGO_TARGET_DIR:-$root/target}/debug/vrep-maze"
timeout 300 "$venv/bin/python" "$root/tests/conformance/export_parsers.py" "$bin"
exec timeout 300 "$venv/bin/python" "$root/tests/conformance/ros_map.py" "$bin"
