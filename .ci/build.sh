#!/usr/bin/env bash
# Configures and builds Lobe into ./build (Release, Ninja, two jobs: the machines have two cores).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "${LOBE_JOBS:-2}"
