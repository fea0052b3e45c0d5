# Helpers shared by every ltm target.
include(GoogleTest)

# Warnings as errors on the project's own targets (not on generated IDL code).
function(ltm_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
endfunction()

set(LTM_INCLUDE_ROOTS ${CMAKE_SOURCE_DIR} ${CMAKE_SOURCE_DIR}/components)

# ltm_library(NAME SOURCES ... [DEPS ...]): a static library of ltm code.
function(ltm_library name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${A_SOURCES})
  target_include_directories(${name} PUBLIC ${LTM_INCLUDE_ROOTS})
  target_link_libraries(${name} PUBLIC ${A_DEPS})
  ltm_warnings(${name})
endfunction()

# ltm_component(NAME SOURCES ... [DEPS ...]): a DDS adapter library whose components register
# themselves at link time; the host and the tests link every one of them whole.
function(ltm_component name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  ltm_library(${name} SOURCES ${A_SOURCES} DEPS ltm_runtime ${A_DEPS})
  set_property(GLOBAL APPEND PROPERTY LTM_COMPONENT_LIBS ${name})
endfunction()

# ltm_link_components(TARGET): link every component library, keeping their registrations.
function(ltm_link_components target)
  get_property(libs GLOBAL PROPERTY LTM_COMPONENT_LIBS)
  foreach(lib ${libs})
    target_link_libraries(${target} PRIVATE "$<LINK_LIBRARY:WHOLE_ARCHIVE,${lib}>")
  endforeach()
endfunction()

# ltm_test(NAME SOURCES ... [DEPS ...] [LABELS ...]): a GoogleTest executable, discovered at
# test time (keeps the build fast).
function(ltm_test name)
  cmake_parse_arguments(A "" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_include_directories(${name} PRIVATE ${LTM_INCLUDE_ROOTS})
  target_link_libraries(${name} PRIVATE ${A_DEPS} GTest::gtest GTest::gtest_main Threads::Threads)
  target_compile_definitions(${name} PRIVATE
    LTM_SOURCE_DIR="${CMAKE_SOURCE_DIR}" LTM_BINARY_DIR="${CMAKE_BINARY_DIR}")
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  ltm_warnings(${name})
  if(NOT A_TIMEOUT)
    set(A_TIMEOUT 300)
  endif()
  # Listing a binary's tests (before ctest runs them) may wait for a core on a loaded machine:
  # CMake's 5 s default failed the whole run there.
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 120
    PROPERTIES TIMEOUT ${A_TIMEOUT} LABELS "${A_LABELS}")
endfunction()
