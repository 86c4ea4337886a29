# Helpers shared by every folder's CMakeLists.txt.

# lobe_warnings(target): the project's warning set, applied to every first-party target.
function(lobe_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local
                         -Wno-unused-parameter -Wno-missing-field-initializers)
endfunction()

# lobe_add_subdirectories(): adds every direct subdirectory that has a CMakeLists.txt, so a new
# stage or test folder needs no edit of its parent. (Target references across folders resolve
# at generate time, so the order does not matter.)
macro(lobe_add_subdirectories)
  file(GLOB _lobe_children LIST_DIRECTORIES true CONFIGURE_DEPENDS
       ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT _lobe_children)
  foreach(_child ${_lobe_children})
    if(IS_DIRECTORY ${_child} AND EXISTS ${_child}/CMakeLists.txt)
      add_subdirectory(${_child})
    endif()
  endforeach()
endmacro()

# lobe_gtest(NAME name SOURCES ... LIBS ... [LABELS ...] [TIMEOUT s]): a GoogleTest executable
# registered with CTest, one CTest test per TEST(); label `heavy` keeps it out of the default run.
# Each removes its tests' scratch in the temp folder when they pass (tests/scratch_cleanup.cpp).
function(lobe_gtest)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  # Scratch clean-up (tests/scratch_cleanup.cpp), compiled once for every test executable.
  if(NOT TARGET lobe_test_scratch)
    add_library(lobe_test_scratch OBJECT ${CMAKE_SOURCE_DIR}/tests/scratch_cleanup.cpp)
    target_link_libraries(lobe_test_scratch PRIVATE GTest::gtest)
    lobe_warnings(lobe_test_scratch)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} lobe_test_scratch GTest::gtest
                                          GTest::gtest_main)
  lobe_warnings(${T_NAME})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  if(LOBE_SANITIZE OR LOBE_FUZZ) # ASan + UBSan code runs 2-4x slower
    math(EXPR T_TIMEOUT "${T_TIMEOUT} * 4")
  endif()
  set(_props TIMEOUT ${T_TIMEOUT})
  if(T_LABELS)
    list(APPEND _props LABELS "${T_LABELS}")
  endif()
  gtest_discover_tests(${T_NAME} WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
                       DISCOVERY_TIMEOUT 60 PROPERTIES ${_props})
endfunction()
