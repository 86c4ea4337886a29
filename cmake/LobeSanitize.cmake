# Sanitizer and fuzzing builds (docs/verification.md, "Sanitizers" and "Fuzzing"), each in its
# own build folder:
#   LOBE_SANITIZE=ON  everything with AddressSanitizer + UndefinedBehaviorSanitizer (GCC or
#                     clang); the default suite then runs under them (.ci/sanitize.sh).
#   LOBE_FUZZ=ON      clang only: the same sanitizers plus libFuzzer's coverage
#                     instrumentation everywhere, and the fuzz/ targets (fuzz/README.md).
# UB is fatal (-fno-sanitize-recover) so that a finding fails the test or stops the fuzzer.
# Asserts stay on in both (-UNDEBUG): they are invariants a fuzzer should be able to trip.
# -O1 (after the build type's -O3, so it wins): the usual ASan level; it compiles in about
# two thirds of -O3's time, which the CI budget needs (docs/verification.md, "Sanitizers").
if(LOBE_FUZZ AND NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "LOBE_FUZZ needs clang (libFuzzer): CC=clang-19 CXX=clang++-19 cmake ...")
endif()
if(LOBE_SANITIZE OR LOBE_FUZZ)
  set(_lobe_san -fsanitize=address,undefined -fno-sanitize-recover=undefined)
  add_compile_options(${_lobe_san} -O1 -fno-omit-frame-pointer -g1 -UNDEBUG)
  add_link_options(${_lobe_san})
  if(LOBE_FUZZ)
    add_compile_options(-fsanitize=fuzzer-no-link)
  endif()
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    add_compile_options(-Wno-unknown-warning-option) # GCC's -Wshadow=local
    # Off, with its reason (docs/verification.md, "Sanitizers"): clang's -fsanitize=function
    # (part of `undefined` since clang 17) reads a signature word just before every function
    # called through a pointer. Code the JIT made has none: the check cannot apply to it, and the
    # read faults when a compiled shader starts a page whose predecessor is unmapped (clang 19:
    # GroupOutputs.ReadOutputIsPerContext, GroupThreads.ConcurrentCompiles, SEGV in
    # Material::shade). GCC has no such check, so both sanitized builds now check the same.
    add_compile_options(-fno-sanitize=function)
    add_link_options(-fno-sanitize=function)
  endif()
endif()
