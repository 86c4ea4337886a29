#!/usr/bin/env bash
# Runs one fuzz target for a while on its seed corpus (the `fuzz` CTest label):
#   run_fuzzer.sh <fuzzer> <seed-dir> <seconds> <timeout-per-input> [dict]
# New inputs go to a scratch corpus beside the seeds (<seed-dir>.run, emptied first), a crashing
# input to <seed-dir>.run/crash-* (reproduce with `<fuzzer> <file>`). Exit status: libFuzzer's
# (non-zero on a crash, hang, leak, OOM or sanitizer report).
set -euo pipefail
fuzzer=$1 seeds=$2 seconds=$3 per_input=$4 dict=${5:-}
work=$seeds.run
rm -rf "$work" && mkdir -p "$work"
args=(-max_total_time="$seconds" -timeout="$per_input" -rss_limit_mb=4096 -print_final_stats=1
      -artifact_prefix="$work/")
[ -n "$dict" ] && args+=(-dict="$dict")
exec "$fuzzer" "${args[@]}" "$work" "$seeds"
