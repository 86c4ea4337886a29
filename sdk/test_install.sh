#!/usr/bin/env bash
# The SDK as a plugin author meets it (CTest sdk_install_minimal_plugin):
#   1. `cmake --install` the build into a temporary prefix;
#   2. the installed headers are exactly include/lobe/*.h, each compiles alone against the
#      prefix, and none includes a header that is not installed;
#   3. the prefix is moved (everything must be found relative to the library, never through the
#      build tree: liblobe.so has no build-tree paths); the installed bin/lobe runs from there;
#   4. examples/minimal_plugin configures with find_package(Lobe), builds and runs;
#   5. its printed values equal closed forms computed here, not by Lobe:
#        t.Cout   = c (0.5 + 0.5 u), c = (0.2, 0.4, 0.6)          (the tint shader)
#        albedo   = Kd Cout, Kd = 0.5                              (matte: Kd Cs diffuse(N))
#        eval     = albedo cos(theta_i) / pi, cos = 0.6             (Lambert, cosine included)
#        eval pdf = cos(theta_i) / pi = 0.190986                    (cosine-weighted sampling)
#        sample   : |wi| = 1, wi.z > 0, weight = albedo, pdf = wi.z / pi
#      and the texture error comes from OpenImageIO, i.e. liblobe_oiio.so loaded from the prefix;
#      and the renderer-registered closure of step 9 evaluates as its closed form (below).
# Usage: test_install.sh <build dir> <examples/minimal_plugin> <C++ compiler> [example flags]
set -euo pipefail
build=$1
example=$2
cxx=$3
flags=${4:-} # the sanitizers, when the library was built with them

tmp=$(mktemp -d "${TMPDIR:-/tmp}/lobe_sdk_test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# 1. Install.
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" || {
  cat "$tmp/install.log"
  fail "cmake --install"
}
prefix=$tmp/prefix
libdir=$(dirname "$(find "$prefix" -name 'liblobe.so' | head -1)")
[ -n "$libdir" ] || fail "no liblobe.so installed"
for f in "$libdir/lobe/liblobe_oiio.so" "$libdir/lobe/lobe_closures.bc" "$libdir/lobe/lobe_shadeops.bc" \
  "$libdir/cmake/Lobe/LobeConfig.cmake" "$libdir/cmake/Lobe/LobeConfigVersion.cmake" \
  "$prefix/share/lobe/shaders/matte.osl" "$prefix/share/lobe/shaders/stdosl.h"; do
  [ -f "$f" ] || fail "not installed: ${f#"$prefix"/}"
done
if ldd "$libdir/liblobe.so" | grep -q -e OpenImageIO -e libOpenColorIO; then
  fail "liblobe.so links OpenImageIO (it must load it on first use)"
fi

# 2. The public headers.
extra=$(find "$prefix/include" -type f | grep -v -E "^$prefix/include/lobe/[^/]+\.h$" || true)
[ -z "$extra" ] || fail "installed beyond include/lobe/*.h: $extra"
for h in "$prefix"/include/lobe/*.h; do
  name=$(basename "$h")
  # Quoted includes must name an installed lobe/ header; angle includes the standard library.
  { grep -E '^\s*#\s*include\s*"' "$h" || true; } | while read -r line; do
    inc=$(echo "$line" | sed -E 's/.*"(.*)".*/\1/')
    case $inc in
    lobe/*) [ -f "$prefix/include/$inc" ] || fail "$name includes $inc, which is not installed" ;;
    *) fail "$name includes \"$inc\", not a public header" ;;
    esac
  done
  if grep -E '^\s*#\s*include\s*<' "$h" | grep -v -E '<(lobe/[a-z_]+\.h|[a-z_]+)>' >/dev/null; then
    fail "$name includes a non-standard header: $(grep -E '^\s*#\s*include\s*<' "$h" | grep -v -E '<(lobe/[a-z_]+\.h|[a-z_]+)>')"
  fi
  echo "#include <lobe/$name>" | "$cxx" -std=c++20 -fsyntax-only -Wall -Wextra -Werror \
    -I"$prefix/include" -x c++ - || fail "lobe/$name does not compile on its own"
done

# 3. Move the prefix.
mv "$prefix" "$tmp/moved"
prefix=$tmp/moved

# The installed executable runs from the moved prefix and finds the stdlib there.
[ -x "$prefix/bin/lobe" ] || fail "not installed: bin/lobe"
"$prefix/bin/lobe" --version | grep -q -E '^lobe [0-9]+\.[0-9]+\.[0-9]+' || fail "bin/lobe --version"
info=$("$prefix/bin/lobe" info matte) || fail "bin/lobe info matte (stdlib not found from the prefix?)"
echo "$info" | grep -q -x 'surface "matte"' || fail "bin/lobe info matte printed: $info"

# 4. Build and run the example against the installed SDK only.
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$example" -B "$tmp/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
  -DCMAKE_PREFIX_PATH="$prefix" >"$tmp/configure.log" 2>&1 || {
  cat "$tmp/configure.log"
  fail "configuring examples/minimal_plugin against the installed SDK"
}
cmake --build "$tmp/build" >"$tmp/build.log" 2>&1 || {
  cat "$tmp/build.log"
  fail "building examples/minimal_plugin"
}
out=$("$tmp/build/minimal_plugin") || {
  echo "$out"
  fail "minimal_plugin exited with an error"
}
echo "$out"

# 5. The values.
echo "$out" | grep -q -E '^lobe [0-9]+\.[0-9]+\.[0-9]+$' || fail "no version line"
echo "$out" | grep -q -x "stdlib shaders: $prefix/share/lobe/shaders" ||
  fail "stdlib shaders not found in the (moved) prefix"
echo "$out" | grep -q -x "closure kernels: jit" || fail "closure kernels not compiled (bitcode not found?)"
echo "$out" | grep -q "^shader error: " || fail "no texture error reported"
if echo "$out" | grep -q "cannot load Lobe's OpenImageIO module"; then
  fail "liblobe_oiio.so not found relative to the library"
fi
echo "$out" | grep -q -x "errors reported: 1" || fail "expected one shader error"

echo "$out" | awk '
  function near(a, b, what) {
    d = a - b; if (d < 0) d = -d
    if (d > 2e-5) { printf "FAIL: %s = %.6f, expected %.6f\n", what, a, b; bad = 1 }
  }
  BEGIN { pi = 3.14159265358979; c[1] = 0.2; c[2] = 0.4; c[3] = 0.6; kd = 0.5; cosi = 0.6 }
  /^point u=/ { split($2, kv, "="); u = kv[2] + 0; points++
                for (i = 1; i <= 3; i++) { cout[i] = c[i] * (0.5 + 0.5 * u); alb[i] = kd * cout[i] } }
  /^  t.Cout / { for (i = 1; i <= 3; i++) near($(i + 1), cout[i], "t.Cout[" i "] at u=" u); seen["cout"]++ }
  /^  Ci = / { if ($0 !~ /diffuse/) { print "FAIL: Ci is not a diffuse closure: " $0; bad = 1 } }
  /^  albedo / { for (i = 1; i <= 3; i++) near($(i + 1), alb[i], "albedo[" i "] at u=" u); seen["albedo"]++ }
  /^  eval / && !/pdf/ { for (i = 1; i <= 3; i++) near($(i + 1), alb[i] * cosi / pi, "eval[" i "] at u=" u); seen["eval"]++ }
  /^  eval pdf / { near($3, cosi / pi, "eval pdf at u=" u); seen["pdf"]++ }
  /^  sample wi / { wx = $3; wy = $4; wz = $5
                    near(sqrt(wx * wx + wy * wy + wz * wz), 1, "|wi| at u=" u)
                    if (wz <= 0) { print "FAIL: sampled wi below the surface"; bad = 1 } }
  /^  sample weight / { for (i = 1; i <= 3; i++) near($(i + 2), alb[i], "sample weight[" i "] at u=" u); seen["weight"]++ }
  /^  sample pdf / { near($3, wz / pi, "sample pdf at u=" u); seen["spdf"]++ }
  END {
    if (points != 3) { print "FAIL: " points " points shaded, expected 3"; bad = 1 }
    n = split("cout albedo eval pdf weight spdf", keys, " ")
    for (k = 1; k <= n; k++) if (seen[keys[k]] != 3) { print "FAIL: " keys[k] " printed " seen[keys[k]] + 0 " times"; bad = 1 }
    if (bad) exit 1
    print "minimal_plugin: all values as the closed forms"
  }' || fail "values differ from the closed forms"

# Step 9: the renderer's own closure (registered by the example, declared by its shader with
# [[ int builtin = 1 ]]), Ci = 0.8 * renderer_lambert(N, t), t = (0.25, 0.5, 0.75):
#   eval = 0.8 t cos(theta_i) / pi, cos = 0.6;  pdf = 0.6 / pi;  albedo = 0.8 t.
echo "$out" | grep -q "^renderer closure Ci = .*renderer_lambert" ||
  fail "the renderer's closure is not in Ci"
echo "$out" | awk '
  function near(a, b, what) {
    d = a - b; if (d < 0) d = -d
    if (d > 2e-5) { printf "FAIL: %s = %.6f, expected %.6f\n", what, a, b; bad = 1 }
  }
  BEGIN { pi = 3.14159265358979; t[1] = 0.25; t[2] = 0.5; t[3] = 0.75 }
  /^renderer closure eval pdf / { near($5, 0.6 / pi, "renderer closure pdf"); seen++ }
  /^renderer closure eval / && !/pdf/ { for (i = 1; i <= 3; i++) near($(i + 3), 0.8 * t[i] * 0.6 / pi, "renderer closure eval[" i "]"); seen++ }
  /^renderer closure albedo / { for (i = 1; i <= 3; i++) near($(i + 3), 0.8 * t[i], "renderer closure albedo[" i "]"); seen++ }
  END {
    if (seen != 3) { print "FAIL: renderer closure lines printed " seen + 0 ", expected 3"; bad = 1 }
    if (bad) exit 1
    print "minimal_plugin: the renderer closure as the closed forms"
  }' || fail "the renderer closure differs from the closed forms"
