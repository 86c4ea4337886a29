#!/usr/bin/env bash
# The README's main-job command: install, build, and run Lobe's main job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh
./build/lobe render -o lobe.png "$@"
