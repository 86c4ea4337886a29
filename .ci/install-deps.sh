#!/usr/bin/env bash
# Installs the Debian bookworm packages Lobe builds and runs with. Idempotent: packages that
# are already installed are skipped, so a warm machine spends no time here.
set -euo pipefail
PKGS=(
  cmake ninja-build g++ pkg-config
  llvm-19-dev clang-19                 # JIT backend; clang-19 compiles closures to bitcode
  libclang-rt-19-dev                   # libFuzzer and clang sanitizer runtimes (fuzz/)
  libembree-dev libtbb-dev             # ray queries; parallel tiles
  libopenimageio-dev                   # images and textures
  nlohmann-json3-dev libcli11-dev libfmt-dev libtinyobjloader-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox                          # plots for `lobe brdf` and bench/
  libpugixml-dev                       # OSL testrender XML scenes (renderer/scene)
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "install-deps: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
