#!/usr/bin/env bash
# Command-line scale benchmark: generate -> validate -> render svg -> render png.
#
#   bench/scale.sh                # 1000x1000, 2000x2000 and 4096x4096
#   bench/scale.sh 1000 2000      # only these sides (square grids)
#   KEEP=1 bench/scale.sh 1000    # keep the work files (printed at the end)
#   ALGO=dfs SEED=7 bench/scale.sh 1000
#   BIN=target/debug/vrep-maze bench/scale.sh 50   # this binary, no release build
#   BASELINE_BIN=/tmp/old/vrep-maze bench/scale.sh 4096   # and an older one, side by side
#
# Builds the release binary, runs each step under GNU time (`/usr/bin/time -v`) and prints
# one markdown table: wall seconds, peak RSS, output size and the issue's target. The
# targets are set for 4096x4096; at other sizes the time targets are scaled by cell count
# (marked ~) and the memory targets are left out. A failing step is reported as FAILED
# with its exit code and the next steps still run (those needing its output are SKIPPED).
# With BASELINE_BIN, every step also runs with that binary (on its own files, right
# before ours, so both see the same machine), the table gains its wall time, peak RSS and
# the ratio ours / baseline, and whether both wrote the same layout is said at the end.
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
baseline=""
if [[ -n "${BASELINE_BIN:-}" ]]; then
    if [[ ! -x "$BASELINE_BIN" ]]; then
        echo "scale.sh: BASELINE_BIN=$BASELINE_BIN is not an executable" >&2
        exit 2
    fi
    baseline="$(realpath "$BASELINE_BIN")"
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

# quiet BIN SUBCOMMAND: `--quiet` (no progress bars) where the subcommand has it, so this
# runs with binaries from before and after the flag exists.
quiet() {
    local help
    help="$("$1" "$2" --help)"
    if grep -q -- '--quiet' <<<"$help"; then
        echo --quiet
    fi
}

# command_line BIN FILES STEP SIDE: sets `cmd` to STEP's command line for BIN, whose work
# files are FILES-SIDE.json (the layout), .svg and .png, and `output` to the file it writes.
command_line() {
    local bin="$1" files="$2" name="$3" side="$4"
    local layout="$files-$side.json" q
    case "$name" in
    generate)
        mapfile -t q < <(quiet "$bin" generate)
        output="$layout"
        cmd=("$bin" generate "${q[@]}" --size "${side}x$side" --seed "$seed" --algo "$algo" -o "$layout")
        ;;
    validate)
        mapfile -t q < <(quiet "$bin" validate)
        output=-
        cmd=("$bin" validate "${q[@]}" "$layout")
        ;;
    svg | png)
        mapfile -t q < <(quiet "$bin" render)
        output="$files-$side.$name"
        cmd=("$bin" render "${q[@]}" "$layout" -o "$output")
        ;;
    esac
}

# Targets at 4096x4096: seconds and peak RSS in MB (0: none).
declare -A target_s=([generate]=8 [validate]=15 [svg]=20 [png]=10)
declare -A target_mb=([generate]=512 [validate]=1024 [svg]=0 [png]=1024)
full_cells=$((4096 * 4096))

rows=()
notes=()

# timed LOG COMMAND...: runs COMMAND under GNU time (its output beside LOG) and sets
# `status`, `wall` (seconds) and `rss_mb` (peak RSS).
timed() {
    local log="$1"
    shift
    status=0
    /usr/bin/time -v -o "$log" "$@" >"$log.stdout" 2>"$log.stderr" || status=$?
    # "Elapsed (wall clock) time (h:mm:ss or m:ss): 1:02.34" -> seconds.
    wall="$(awk -F': ' '/Elapsed \(wall clock\)/ {
        n = split($2, p, ":"); s = 0
        for (i = 1; i <= n; i++) s = s * 60 + p[i]
        printf "%.2f", s }' "$log")"
    rss_mb="$(awk -F': ' '/Maximum resident set size/ { printf "%.0f", $2 / 1024 }' "$log")"
}

# step SIZE STEP: runs STEP (baseline first, if any) and adds a table row.
step() {
    local side="$1" name="$2"
    local base_cells=""
    if [[ -n "$baseline" ]]; then
        if [[ "$name" != generate && ! -f "$work/base-$side.json" ]]; then
            base_cells=" - | - | - |"
        else
            command_line "$baseline" "$work/base" "$name" "$side"
            timed "$work/base-$name-$side.time" "${cmd[@]}"
            local base_wall="$wall" base_rss="$rss_mb"
            if ((status != 0)); then
                base_cells=" FAILED (exit $status) | - | - |"
            fi
        fi
    fi

    command_line "$bin" "$work/maze" "$name" "$side"
    timed "$work/$name-$side.time" "${cmd[@]}"
    local size_mb="-"
    if [[ "$output" != - && -f "$output" ]]; then
        size_mb="$(awk -v b="$(stat -c %s "$output")" 'BEGIN { printf "%.1f MB", b / 1e6 }')"
    fi
    if [[ -n "$baseline" && -z "$base_cells" ]]; then
        local ratio="-"
        if ((status == 0)); then
            ratio="$(awk -v w="$wall" -v b="$base_wall" 'BEGIN {
                if (b > 0) printf "%.2fx", w / b; else print "-" }')"
        fi
        base_cells=" $base_wall | $base_rss | $ratio |"
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
    rows+=("| $name | ${side}x$side | $wall | $rss_mb | $size_mb |$base_cells $target | $result |")
    echo "$name ${side}x$side: $result ($wall s, $rss_mb MB)" >&2
    if ((status != 0)); then
        echo "  its last error line: $(tail -n 1 "$work/$name-$side.time.stderr")" >&2
    fi
    return 0
}

skip() {
    local dashes=" - | - | - |"
    rows+=("| $2 | ${1}x$1 | - | - | - |${baseline:+$dashes} - | SKIPPED (no layout) |")
}

for side in "${sizes[@]}"; do
    step "$side" generate
    if [[ -n "$baseline" && -f "$work/base-$side.json" && -f "$work/maze-$side.json" ]]; then
        if cmp -s "$work/base-$side.json" "$work/maze-$side.json"; then
            notes+=("${side}x$side: the layout is byte for byte the baseline's.")
        else
            notes+=("${side}x$side: the layout DIFFERS from the baseline's.")
        fi
    fi
    if [[ ! -f "$work/maze-$side.json" ]]; then
        skip "$side" validate
        skip "$side" svg
        skip "$side" png
        continue
    fi
    step "$side" validate
    step "$side" svg
    step "$side" png
done

echo
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) (cores: $(nproc)); $algo, seed $seed, $(git rev-parse --short HEAD)"
echo
if [[ -n "$baseline" ]]; then
    echo "| step | size | wall s | peak RSS MB | output | baseline wall s | baseline peak RSS MB | wall ratio | target | result |"
    echo "|---|---|---:|---:|---:|---:|---:|---:|---|---|"
else
    echo "| step | size | wall s | peak RSS MB | output | target | result |"
    echo "|---|---|---:|---:|---:|---|---|"
fi
printf '%s\n' "${rows[@]}"
echo
echo "Targets are the issue's, for 4096x4096; ~: the 4096 time target scaled by cell count (no memory target)."
if [[ -n "$baseline" ]]; then
    echo "Baseline: $baseline; wall ratio = ours / baseline (below 1: faster)."
    printf '%s\n' "${notes[@]}"
fi
