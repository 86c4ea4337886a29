#!/usr/bin/env bash
# The README's test command: install, build, run every test except the `heavy` label
# (the long statistical sweeps: `ctest --test-dir build -L heavy`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh
ctest --test-dir build -LE heavy -j 2 --output-on-failure --timeout 900
