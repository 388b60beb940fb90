#!/usr/bin/env bash
# Conformance of `vrep-maze serve --api zmq` with the official ZeroMQ remote API client
# (PyPI coppeliasim-zmqremoteapi-client, pyzmq, cbor2) in the project's .venv.
# Prints `zmq-conformance: N passed, M failed` last; exits non-zero on failure.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
venv="$root/.venv"
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import coppeliasim_zmqremoteapi_client, zmq, cbor2" 2>/dev/null; then
    "$venv/bin/pip" install --quiet coppeliasim-zmqremoteapi-client pyzmq cbor2
fi
cargo build --quiet --bin vrep-maze
bin="${CARGO_TARGET_DIR:-$root/target}/debug/vrep-maze"
exec timeout 120 "$venv/bin/python" "$root/tests/conformance/zmq_official_client.py" "$bin"
