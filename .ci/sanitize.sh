#!/usr/bin/env bash
# The default suite built with AddressSanitizer + UndefinedBehaviorSanitizer, in its own build
# folder (./build-asan; docs/verification.md, "Sanitizers"):
#   bash .ci/sanitize.sh            # GCC (the default compiler)
#   CXX=clang++-19 CC=clang-19 bash .ci/sanitize.sh
# Any ASan error, leak or UB report fails the test that triggered it (UB is not recoverable:
# -fno-sanitize-recover). Benchmarks are not built. Times each phase.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install-deps.sh
dir=${LOBE_SANITIZE_DIR:-build-asan}
t0=$(date +%s)
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DLOBE_SANITIZE=ON \
      -DLOBE_BUILD_BENCH=OFF >/dev/null
cmake --build "$dir" -j "${LOBE_JOBS:-2}"
t1=$(date +%s)
# detect_leaks: leaks fail the test at exit. abort_on_error: a core-dump-like exit CTest sees.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
status=0
ctest --test-dir "$dir" -LE heavy -j 2 --output-on-failure --timeout 3600 || status=$?
t2=$(date +%s)
echo "sanitize: build $((t1 - t0)) s, tests $((t2 - t1)) s, status $status"
exit $status
