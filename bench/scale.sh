#!/usr/bin/env bash
# Command-line scale benchmark: generate -> validate -> render svg -> render png.
#
#   bench/scale.sh                # 1000x1000, 2000x2000 and 4096x4096
#   bench/scale.sh 1000 2000      # only these sides (square grids)
#   KEEP=1 bench/scale.sh 1000    # keep the work files (printed at the end)
#   ALGO=dfs SEED=7 bench/scale.sh 1000
#   BIN=target/debug/vrep-maze bench/scale.sh 50   # this binary, no release build
#
# Builds the release binary, runs each step under GNU time (`/usr/bin/time -v`) and prints
# one markdown table: wall seconds, peak RSS, output size and the issue's target. The
# targets are set for 4096x4096; at other sizes the time targets are scaled by cell count
# (marked ~) and the memory targets are left out. A failing step is reported as FAILED
# with its exit code and the next steps still run (those needing its output are SKIPPED).
# Work files go to a temporary directory under target/scale, deleted unless KEEP=1.
# Not run by CI: timings are only reported, never asserted.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

sizes=("$@")
if ((${#sizes[@]} == 0)); then
    sizes=(1000 2000 4096)
fi
for side in "${sizes[@]}"; do
    if ! [[ "$side" =~ ^[1-9][0-9]*$ ]]; then
        echo "scale.sh: '$side' is not a side length (e.g. bench/scale.sh 1000 2000)" >&2
        exit 2
    fi
done
if [[ ! -x /usr/bin/time ]]; then
    echo "scale.sh: needs GNU time at /usr/bin/time: apt-get install -y time" >&2
    exit 2
fi
algo="${ALGO:-prim}"
seed="${SEED:-1}"

if [[ -n "${BIN:-}" ]]; then
    bin="$(realpath "$BIN")"
else
    cargo build --release --quiet
    bin="$root/target/release/vrep-maze"
fi

mkdir -p "$root/target/scale"
work="$(mktemp -d "$root/target/scale/run.XXXXXX")"
cleanup() {
    if [[ "${KEEP:-0}" == 1 ]]; then
        echo "work files kept in $work"
    else
        rm -rf "$work"
    fi
}
trap cleanup EXIT

# `--quiet` (no progress bars) where the subcommand has it, so this runs before and after
# the flag exists.
quiet() {
    local help
    help="$("$bin" "$1" --help)"
    if grep -q -- '--quiet' <<<"$help"; then
        echo --quiet
    fi
}
mapfile -t q_generate < <(quiet generate)
mapfile -t q_validate < <(quiet validate)
mapfile -t q_render < <(quiet render)

# Targets at 4096x4096: seconds and peak RSS in MB (0: none).
declare -A target_s=([generate]=8 [validate]=15 [svg]=20 [png]=10)
declare -A target_mb=([generate]=512 [validate]=1024 [svg]=0 [png]=1024)
full_cells=$((4096 * 4096))

rows=()

# step SIZE STEP OUTPUT COMMAND...: runs COMMAND under GNU time and adds a table row.
# OUTPUT is the file the step writes ("-" for none).
step() {
    local side="$1" name="$2" output="$3"
    shift 3
    local log="$work/$name-$side.time" status=0
    /usr/bin/time -v -o "$log" "$@" >"$work/$name-$side.stdout" 2>"$work/$name-$side.stderr" || status=$?
    local wall rss_kb
    # "Elapsed (wall clock) time (h:mm:ss or m:ss): 1:02.34" -> seconds.
    wall="$(awk -F': ' '/Elapsed \(wall clock\)/ {
        n = split($2, p, ":"); s = 0
        for (i = 1; i <= n; i++) s = s * 60 + p[i]
        printf "%.2f", s }' "$log")"
    rss_kb="$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$log")"
    local rss_mb size_mb="-"
    rss_mb="$(awk -v k="${rss_kb:-0}" 'BEGIN { printf "%.0f", k / 1024 }')"
    if [[ "$output" != - && -f "$output" ]]; then
        size_mb="$(awk -v b="$(stat -c %s "$output")" 'BEGIN { printf "%.1f MB", b / 1e6 }')"
    fi

    local cells=$((side * side)) secs="${target_s[$name]}" mb="${target_mb[$name]}" target result
    if ((cells == full_cells)); then
        target="≤ ${secs} s"
        if ((mb > 0)); then
            target+=", ≤ ${mb} MB"
        fi
    else
        secs="$(awk -v t="$secs" -v c="$cells" -v f="$full_cells" 'BEGIN { printf "%.3g", t * c / f }')"
        target="~≤ ${secs} s"
        mb=0
    fi
    if ((status != 0)); then
        result="FAILED (exit $status)"
    else
        result="$(awk -v w="$wall" -v t="$secs" -v r="$rss_mb" -v m="$mb" 'BEGIN {
            over = ""
            if (w > t) over = "time"
            if (m > 0 && r > m) over = over (over == "" ? "" : ", ") "memory"
            print (over == "" ? "ok" : "over: " over) }')"
    fi
    rows+=("| $name | ${side}x$side | $wall | $rss_mb | $size_mb | $target | $result |")
    echo "$name ${side}x$side: $result ($wall s, $rss_mb MB)" >&2
    if ((status != 0)); then
        echo "  its last error line: $(tail -n 1 "$work/$name-$side.stderr")" >&2
    fi
    return 0
}

skip() {
    rows+=("| $2 | ${1}x$1 | - | - | - | - | SKIPPED (no layout) |")
}

for side in "${sizes[@]}"; do
    layout="$work/maze-$side.json"
    step "$side" generate "$layout" "$bin" generate "${q_generate[@]}" \
        --size "${side}x$side" --seed "$seed" --algo "$algo" -o "$layout"
    if [[ ! -f "$layout" ]]; then
        skip "$side" validate
        skip "$side" svg
        skip "$side" png
        continue
    fi
    step "$side" validate - "$bin" validate "${q_validate[@]}" "$layout"
    step "$side" svg "$work/maze-$side.svg" "$bin" render "${q_render[@]}" "$layout" -o "$work/maze-$side.svg"
    step "$side" png "$work/maze-$side.png" "$bin" render "${q_render[@]}" "$layout" -o "$work/maze-$side.png"
done

echo
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) (cores: $(nproc)); $algo, seed $seed, $(git rev-parse --short HEAD)"
echo
echo "| step | size | wall s | peak RSS MB | output | target | result |"
echo "|---|---|---:|---:|---:|---|---|"
printf '%s\n' "${rows[@]}"
echo
echo "Targets are the issue's, for 4096x4096; ~: the 4096 time target scaled by cell count (no memory target)."
