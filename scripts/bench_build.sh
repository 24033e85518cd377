#!/usr/bin/env bash
# The set-up commands' build cost on a fresh clone (issue 36 point 5). Optional, not part of
# CI; `cargo test` never runs it.
#
#   scripts/bench_build.sh [--baseline COMMIT] [--keep] [REV]
#
# For REV (default HEAD) and, with --baseline, for COMMIT too (alternating: baseline first),
# in a fresh clone with an empty target directory:
#   1. README's command 1 without the model run: `cargo install --locked --debug --path .
#      --root DIR`;
#   2. README's command 2's build after it, in the same target: `cargo test --locked --no-run`.
# Each under `nice -n 5`; CPU seconds = user + sys of the whole command (cargo and every
# rustc it starts), wall seconds, and the 1-minute load average before and after (other
# processes on the machine slow the wall clock and, less, the CPU seconds: compare builds
# run in one call of this script, alternating). Ratios against the issue's recorded figures
# for the commands on 2026-12-06: 644 CPU-s (command 1) and 317 CPU-s (command 2); goal:
# halved, 322 and 158.
# The clones live in a temporary directory, removed at the end unless --keep.
set -euo pipefail

BASELINE=""
KEEP=0
REV=HEAD
while [ $# -gt 0 ]; do
    case "$1" in
        --baseline) BASELINE="$2"; shift 2 ;;
        --keep) KEEP=1; shift ;;
        -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
        -*) echo "bench_build.sh: unknown option '$1' (expected --baseline COMMIT, --keep or a revision)" >&2; exit 2 ;;
        *) REV="$1"; shift ;;
    esac
done

ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=$(mktemp -d /tmp/romdyn-bench-build.XXXXXX)
# Removed at the end unless --keep, or a command failed (its log is kept for reading).
trap '[ "$KEEP" = 1 ] || rm -rf "$WORK"' EXIT
ISSUE_INSTALL=644
ISSUE_TEST=317

load() { cut -d' ' -f1 /proc/loadavg; }

# timed FILE CMD...: runs CMD (its output to $LOG), writes "USER SYS WALL" of CMD and every
# process it started (bash's `time` keyword) to FILE.
timed() {
    local out=$1; shift
    local TIMEFORMAT='%U %S %R'
    { time ( "$@" >>"$LOG" 2>&1 ) ; } 2>"$out"
}

measure() { # LABEL REV
    local label=$1 rev=$2 dir="$WORK/$1"
    rm -rf "$dir"
    git clone -q "$ROOT" "$dir"
    git -C "$dir" checkout -q "$rev"
    local sha; sha=$(git -C "$dir" rev-parse --short HEAD)
    LOG="$WORK/$label.log"
    : > "$LOG"
    local l0 l1 l2
    l0=$(load)
    timed "$WORK/$label.t1" bash -c "cd '$dir' && CARGO_TARGET_DIR='$dir/target' nice -n 5 cargo install --locked --debug --path . --root '$dir/inst'" \
        || { echo "$label ($sha): command 1 failed, see $LOG" >&2; KEEP=1; exit 1; }
    l1=$(load)
    timed "$WORK/$label.t2" bash -c "cd '$dir' && CARGO_TARGET_DIR='$dir/target' nice -n 5 cargo test --locked --no-run" \
        || { echo "$label ($sha): command 2 failed, see $LOG" >&2; KEEP=1; exit 1; }
    l2=$(load)
    awk -v label="$label" -v sha="$sha" -v l0="$l0" -v l1="$l1" -v l2="$l2" -v i="$ISSUE_INSTALL" -v t="$ISSUE_TEST" '
        FNR == 1 && NR == 1 { c1 = $1 + $2; w1 = $3 }
        FNR == 1 && NR > 1 { c2 = $1 + $2; w2 = $3 }
        END {
        printf "| %s (%s) | %.1f CPU-s, %.0f s wall, load %s -> %s | %.2f | %.1f CPU-s, %.0f s wall, load %s -> %s | %.2f |\n",
            label, sha, c1, w1, l0, l1, c1 / i, c2, w2, l1, l2, c2 / t }' "$WORK/$label.t1" "$WORK/$label.t2"
    rm -rf "$dir/target"
}

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "| build | command 1: install | ratio to 644 | command 2: test build after it | ratio to 317 |"
echo "| --- | --- | --- | --- | --- |"
if [ -n "$BASELINE" ]; then measure baseline "$BASELINE"; fi
measure this "$REV"
echo "# goal (issue 36 point 5): both ratios at most 0.50"
