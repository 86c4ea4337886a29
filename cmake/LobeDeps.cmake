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

# lobe_llvm: the shared libLLVM plus its include paths and definitions.
add_library(lobe_llvm INTERFACE)
target_include_directories(lobe_llvm SYSTEM INTERFACE ${LLVM_INCLUDE_DIRS})
separate_arguments(_llvm_defs NATIVE_COMMAND "${LLVM_DEFINITIONS}")
target_compile_definitions(lobe_llvm INTERFACE ${_llvm_defs})
target_link_libraries(lobe_llvm INTERFACE LLVM)

# OpenImageIO 2.4.7: its exported target lists /usr/include/opencv4 as an include directory,
# which the Debian package does not install; CMake refuses a missing INTERFACE path. Strip it.
find_package(OpenImageIO CONFIG REQUIRED)
foreach(_prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
  foreach(_tgt OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
    if(TARGET ${_tgt})
      get_target_property(_dirs ${_tgt} ${_prop})
      if(_dirs)
        list(FILTER _dirs EXCLUDE REGEX "opencv4")
        set_target_properties(${_tgt} PROPERTIES ${_prop} "${_dirs}")
      endif()
    endif()
  endforeach()
endforeach()

find_package(embree 3 CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(fmt CONFIG REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_package(Threads REQUIRED)
if(LOBE_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(LOBE_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
