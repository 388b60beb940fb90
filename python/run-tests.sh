#!/usr/bin/env bash
# The Python package's tests, as CI runs them: `pip install .[rl]` (the README's command: maturin
# builds the release wheel) in a fresh virtual environment, then pytest on python/tests
# against what it installed.
# Prints pytest's summary last; exits non-zero on failure.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
target="${CARGO_TARGET_DIR:-$root/target}"
venv="$target/python-venv"
rm -rf "$venv"
if ! python3 -m venv "$venv" 2>/dev/null; then
    # Debian's python3 keeps venv in a package of its own
    apt-get update -qq && apt-get install -y -qq python3-venv
    rm -rf "$venv"
    python3 -m venv "$venv"
fi
# PyYAML reads the ROS maps test_export.py writes (hostile file names)
"$venv/bin/pip" install --quiet pytest coppeliasim-zmqremoteapi-client pyyaml
# with the `rl` extra (gymnasium-robotics, which brings MuJoCo, and minigrid: about a minute
# to install) for tests/test_rl.py
"$venv/bin/pip" install --quiet "$root[rl]"
# from the repository root, so `import vrep_maze` is the installed wheel, not python/vrep_maze
exec timeout 900 "$venv/bin/python" -m pytest -q python/tests
