#!/usr/bin/env bash
# Assembles the seed corpora of the fuzz targets from the project's own files:
#   make_corpus.sh <out-dir> [lobe]
# <out-dir>/<target>/ gets the shaders, IR, scenes and meshes of tests/, scenes/ and
# stdlib_shaders/, plus the hand-written seeds in fuzz/seeds/. With a `lobe` binary (a normal
# build's), the IR corpus also gets `lobe compile --emit=ir` of every shader that compiles.
set -euo pipefail
out=$1 lobe=${2:-}
src=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$out"
mkdir -p "$out"/{osl,ir,group,scene_json,scene_xml,obj,ply,merl}
copy() { # copy <target> <find args...>: one file per seed, named after its path
  local t=$1; shift
  find "$src/tests" "$src/scenes" "$src/stdlib_shaders" "$src/compiler/stdlib" -type f "$@" \
    -print0 | while IFS= read -r -d '' f; do
    cp "$f" "$out/$t/$(realpath --relative-to="$src" "$f" | tr / _)"
  done
}
copy osl \( -name '*.osl' -o -name '*.h' \)
copy ir -name '*.lir'
copy scene_json -name '*.json'
copy scene_xml -name '*.xml'
copy obj -name '*.obj'
copy ply -name '*.ply'
for t in ir group obj ply merl; do
  [ -d "$src/fuzz/seeds/$t" ] && cp "$src/fuzz/seeds/$t"/* "$out/$t/"
done
if [ -n "$lobe" ]; then
  for f in "$out"/osl/*.osl; do
    "$lobe" compile --emit=ir -o "$out/ir/$(basename "$f" .osl).lir" "$f" >/dev/null 2>&1 || true
  done
fi
for t in "$out"/*; do echo "$(basename "$t"): $(ls "$t" | wc -l) seeds"; done
