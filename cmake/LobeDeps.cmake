# Third-party dependencies, all from Debian bookworm packages (see .ci/install-deps).

# LLVM 19. find_package(LLVM 19) rejects 19.1.7 ("version not compatible"), so find it by
# path and check the major version ourselves. Debian's LLVM is built with RTTI and without
# exceptions: code that includes LLVM headers must never throw through LLVM frames.
find_package(LLVM CONFIG REQUIRED HINTS /usr/lib/llvm-19/lib/cmake/llvm NO_DEFAULT_PATH)
if(NOT LLVM_VERSION_MAJOR EQUAL 19)
  message(FATAL_ERROR "Lobe needs LLVM 19, found ${LLVM_PACKAGE_VERSION} at ${LLVM_DIR}")
endif()
message(STATUS "LLVM ${LLVM_PACKAGE_VERSION} at ${LLVM_DIR}")
find_program(LOBE_CLANG19 NAMES clang-19 clang HINTS ${LLVM_TOOLS_BINARY_DIR} REQUIRED)
find_program(LOBE_LLVM_LINK llvm-link HINTS ${LLVM_TOOLS_BINARY_DIR} REQUIRED)

# lobe_llvm: libLLVM plus its include paths and definitions. An executable with the property
# LOBE_STATIC_LLVM set links the static component libraries it uses instead of the shared
# libLLVM: loading libLLVM.so (its 360k relocations and static constructors) costs about 60 ms
# of every process's start-up, the static components about 20 (measured on a hello-world that
# creates an LLJIT; docs/runtime.md). Only the `lobe` executable does: linking them takes tens
# of seconds, which every test binary would pay.
add_library(lobe_llvm INTERFACE)
target_include_directories(lobe_llvm SYSTEM INTERFACE ${LLVM_INCLUDE_DIRS})
separate_arguments(_llvm_defs NATIVE_COMMAND "${LLVM_DEFINITIONS}")
target_compile_definitions(lobe_llvm INTERFACE ${_llvm_defs})
# LLVMSupport's link interface names zstd's CMake target; the libzstd1 package (a dependency of
# libLLVM) has the library without the CMake files of libzstd-dev.
if(NOT TARGET zstd::libzstd_shared)
  find_library(LOBE_ZSTD_LIBRARY NAMES zstd libzstd.so.1 REQUIRED)
  add_library(zstd::libzstd_shared SHARED IMPORTED)
  set_target_properties(zstd::libzstd_shared PROPERTIES IMPORTED_LOCATION ${LOBE_ZSTD_LIBRARY})
endif()
llvm_map_components_to_libnames(LOBE_LLVM_STATIC_LIBS orcjit native passes linker bitreader
                                bitwriter irreader asmparser)
set(_static_llvm "$<BOOL:$<TARGET_PROPERTY:LOBE_STATIC_LLVM>>")
target_link_libraries(lobe_llvm INTERFACE "$<${_static_llvm}:${LOBE_LLVM_STATIC_LIBS}>"
                                          "$<$<NOT:${_static_llvm}>:LLVM>")

# OpenImageIO 2.4.7: its CMake config is unusable on a fresh bookworm machine (it lists
# /usr/include/opencv4, which the package does not install, and imported targets for the
# command-line tools, which live in another package). Its pkg-config file is correct; use that.
# OpenImageIO costs ~0.25 s of process start-up (it pulls in ~260 shared libraries): only the
# module runtime/oiio loads on first use links it (lobe_oiio); lobe_oiio_headers is for code
# that uses its header-only parts (Strutil::strhash).
find_package(PkgConfig REQUIRED)
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
add_library(lobe_oiio INTERFACE)
target_link_libraries(lobe_oiio INTERFACE PkgConfig::OIIO)
add_library(lobe_oiio_headers INTERFACE)
target_include_directories(lobe_oiio_headers INTERFACE ${OIIO_INCLUDE_DIRS})

find_package(embree 3 CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(fmt 9.1 CONFIG REQUIRED)
# printf formats as OSL's does through fmt 9's parsing of the spec it makes ("%-05d" of 5 is
# "50000": fmt 9 keeps the 0 fill after an alignment; later fmt versions changed such rules).
if(fmt_VERSION VERSION_GREATER_EQUAL 10)
  message(FATAL_ERROR "Lobe's printf needs fmt 9 (OSL 1.13's formatting library), found ${fmt_VERSION}")
endif()
find_package(tinyobjloader CONFIG REQUIRED)
find_package(Threads REQUIRED)
if(LOBE_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(LOBE_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
