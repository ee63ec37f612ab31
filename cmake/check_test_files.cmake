# A test file per source (cmake -P): every src/<stage>/<name>.cpp has its
# tests/<stage>/<name>_test.cpp, but for the sources listed below with the
# reason. Fails listing every source without one.
#
#   cmake -DROOT=<source tree> -P check_test_files.cmake

cmake_minimum_required(VERSION 3.22)

if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<tree> -P check_test_files.cmake")
endif()

# Sources whose tests are elsewhere, and why.
set(exempt
  # The entry point: every test of tests/cli/ runs the binary it makes.
  src/cli/main.cpp
  # MPI's stand-in when the build has no MPI: tests/cli/mpi_test.cpp runs
  # `cairn batch` and `cairn plan` through whichever of the two was built.
  src/cli/mpi_none.cpp)

file(GLOB sources RELATIVE "${ROOT}" "${ROOT}/src/*/*.cpp")
list(SORT sources)
set(missing "")
foreach(source IN LISTS sources)
  if(source IN_LIST exempt)
    continue()
  endif()
  string(REGEX REPLACE "^src/([a-z_]+)/([a-z_0-9]+)\\.cpp$" "tests/\\1/\\2_test.cpp" test "${source}")
  if(NOT EXISTS "${ROOT}/${test}")
    string(APPEND missing "\n  ${source}: no ${test}")
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "sources without a test file of their own:${missing}")
endif()
list(LENGTH sources n)
message(STATUS "every one of ${n} sources has its test file (or is exempt, with the reason)")
