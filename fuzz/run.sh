#!/usr/bin/env bash
# Runs UP's fuzz targets one after the other, each for a given time.
#
#   fuzz/run.sh [SECONDS] [TARGET...]     default: 300 s each, every target
#   FUZZ_MERGE=1 fuzz/run.sh ...          then merge new finds into fuzz/corpus/
#
# Needs a nightly toolchain (UP_NIGHTLY, default: the Makefile's pinned
# nightly-2026-05-19) and cargo-fuzz (`cargo install cargo-fuzz --locked`).
# The committed corpus in fuzz/corpus/<target> seeds each run; what a run
# finds goes to fuzz/target/work/<target> (not committed) unless merged.
# A crash stops the script with a non-zero status; the input is saved under
# fuzz/artifacts/<target>/ and the log under fuzz/logs/<target>.log.
# Each target runs on one core (libFuzzer's default: one job). The scene
# target mutates with a dictionary of the scene format's keys (scene.dict).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here"
seconds="${1:-300}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(scene obj contacts toi)
fi
nightly="${UP_NIGHTLY:-nightly-2026-05-19}"
if ! cargo "+$nightly" fuzz --version >/dev/null 2>&1; then
    echo "fuzz/run.sh: cargo-fuzz or $nightly is missing: cargo install cargo-fuzz --locked" >&2
    exit 2
fi

# Longest input per target, bytes: scenes and OBJ text need room, numbers do not.
max_len() {
    case "$1" in
        scene) echo 8192 ;;
        obj) echo 16384 ;;
        *) echo 512 ;;
    esac
}

# Mutation hints per target: the scene format's keys for the scene target.
dictionary() {
    case "$1" in
        scene) echo "-dict=scene.dict" ;;
    esac
}

mkdir -p logs
cargo "+$nightly" fuzz build -O -s none >/dev/null
status=0
for target in "${targets[@]}"; do
    work="target/work/$target"
    mkdir -p "$work" "corpus/$target" "artifacts/$target"
    log="logs/$target.log"
    echo "fuzz $target: ${seconds}s (log: fuzz/$log)"
    # shellcheck disable=SC2046 # an empty dictionary is no argument
    if cargo "+$nightly" fuzz run -O -s none "$target" "$work" "corpus/$target" -- \
        $(dictionary "$target") -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
        -max_len="$(max_len "$target")" -print_final_stats=1 >"$log" 2>&1; then
        runs="$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')"
        coverage="$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1)"
        echo "fuzz $target: clean, ${runs:-?} runs, ${coverage:-cov: ?}"
    else
        echo "fuzz $target: FAILED; see fuzz/$log and fuzz/artifacts/$target/" >&2
        grep -E 'panicked|SUMMARY|ERROR' "$log" | head -5 >&2 || true
        status=1
        continue
    fi
    if [ "${FUZZ_MERGE:-0}" = 1 ]; then
        cargo "+$nightly" fuzz run -O -s none "$target" "corpus/$target" "$work" -- \
            -merge=1 -max_len="$(max_len "$target")" >>"$log" 2>&1
        echo "fuzz $target: corpus merged ($(ls "corpus/$target" | wc -l) files)"
    fi
done
exit "$status"
