#!/usr/bin/env bash
# Generation benchmark with the knossos baseline, side by side, in one run.
#
#   bench/run.sh                # everything (about 10-15 minutes on 2 cores)
#   bench/run.sh wilson eller   # only these algorithms (our names)
#
# 1. builds bench/knossos (a separate cargo project timing knossos 1.2's library
#    generators; knossos's own CLI (`cargo install knossos`) always renders and writes
#    its output, so it cannot time generation alone) and runs it;
# 2. runs `cargo bench --bench generate` with that baseline, printing one markdown table.
# Not run by CI: timings are only reported, never asserted.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
out="$root/target/bench"
mkdir -p "$out"

cargo build --release --quiet --manifest-path bench/knossos/Cargo.toml
"$root/bench/knossos/target/release/knossos-timer" "$@" | tee "$out/knossos.tsv"

VREP_MAZE_BASELINE="$out/knossos.tsv" cargo bench --quiet --bench generate -- "$@" | tee "$out/table.md"
echo "table written to $out/table.md"
