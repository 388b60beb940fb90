#!/usr/bin/env bash
# Conformance of `vrep-maze serve` with the official legacy remote API C client (from the
# PyPI wheel dqrobotics-interface-coppeliasim-vrep, loaded with ctypes).
# Prints `legacy-conformance: N passed, M failed` last; exits non-zero on failure.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
venv="$root/.venv"
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
lib=$(ls "$venv"/lib/python3*/site-packages/dqrobotics/interfaces/vrep/_core*.so 2>/dev/null | head -n1 || true)
if [ -z "$lib" ]; then
    "$venv/bin/pip" install --quiet --no-deps dqrobotics-interface-coppeliasim-vrep
    lib=$(ls "$venv"/lib/python3*/site-packages/dqrobotics/interfaces/vrep/_core*.so | head -n1)
fi
cargo build --quiet --bin vrep-maze
bin="${CARGO_TARGET_DIR:-$root/target}/debug/vrep-maze"
exec timeout 300 "$venv/bin/python" "$root/tests/conformance/legacy_c_client.py" "$bin" "$lib"
