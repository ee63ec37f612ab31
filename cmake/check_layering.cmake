# The layering test (cmake -P): every include of a stage's headers
# (include/cairn/<stage>/) and sources (src/<stage>/) names its own stage or a
# stage it depends on, directly or through others. The graph is the one
# CMakeLists.txt wrote from the DEPS of each cairn_stage() call, so the test
# and the build cannot disagree.
#
#   cmake -DGRAPH=<build>/stage_graph.txt -DROOT=<source tree> -P check_layering.cmake
#
# An include counts as a stage's when it is "cairn/<stage>/..." or
# <cairn/<stage>/...> (a public header), or "<stage>/..." (a private header
# under src/, which only its own stage may include). The front ends are
# stages too: cli (src/cli/) and python (python/src/). Fails listing every
# include that is not allowed: file, line, the include and the arrow.

cmake_minimum_required(VERSION 3.22)

if(NOT GRAPH OR NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DGRAPH=stage_graph.txt -DROOT=<tree> -P check_layering.cmake")
endif()

# The graph: "stage: dep dep ..." per line; "*" allows every stage.
file(STRINGS "${GRAPH}" lines)
set(stages "")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^([a-z_]+):(.*)$")
    continue()
  endif()
  set(stage "${CMAKE_MATCH_1}")
  string(STRIP "${CMAKE_MATCH_2}" deps)
  separate_arguments(deps UNIX_COMMAND "${deps}")
  list(APPEND stages ${stage})
  set(direct_${stage} ${deps})
endforeach()

# Transitive closure, by repeated expansion (the graph is small).
foreach(stage IN LISTS stages)
  set(closure ${direct_${stage}})
  set(changed TRUE)
  while(changed)
    set(changed FALSE)
    foreach(dep IN LISTS closure)
      foreach(next IN LISTS direct_${dep})
        if(NOT next IN_LIST closure)
          list(APPEND closure ${next})
          set(changed TRUE)
        endif()
      endforeach()
    endforeach()
  endwhile()
  set(allowed_${stage} ${stage} ${closure})
endforeach()

set(violations "")
set(checked 0)
foreach(stage IN LISTS stages)
  if("*" IN_LIST direct_${stage})
    continue()
  endif()
  file(GLOB_RECURSE files "${ROOT}/include/cairn/${stage}/*.h" "${ROOT}/src/${stage}/*.h"
       "${ROOT}/src/${stage}/*.cpp")
  if(stage STREQUAL "python")
    file(GLOB_RECURSE files "${ROOT}/python/src/*.h" "${ROOT}/python/src/*.cpp")
  endif()
  foreach(file IN LISTS files)
    math(EXPR checked "${checked} + 1")
    # Lines as a list: semicolons (CMake's list separator) made harmless first.
    file(READ "${file}" content)
    string(REPLACE ";" "," content "${content}")
    string(REPLACE "[" "(" content "${content}")
    string(REPLACE "]" ")" content "${content}")
    string(REPLACE "\n" ";" file_lines "${content}")
    set(line_no 0)
    foreach(inc IN LISTS file_lines)
      math(EXPR line_no "${line_no} + 1")
      if(NOT inc MATCHES "^[ \t]*#[ \t]*include[ \t]*[\"<]")
        continue()
      endif()
      set(target "")
      set(private FALSE)
      if(inc MATCHES "[\"<]cairn/([a-z_]+)/")
        set(target "${CMAKE_MATCH_1}")
      elseif(inc MATCHES "\"([a-z_]+)/")
        set(target "${CMAKE_MATCH_1}")
        set(private TRUE)
      endif()
      if(target)
        if(NOT target IN_LIST stages)
          continue()  # not a stage (a third-party folder)
        endif()
        if(private AND NOT target STREQUAL stage)
          file(RELATIVE_PATH rel "${ROOT}" "${file}")
          string(STRIP "${inc}" inc)
          list(APPEND violations
               "${rel}:${line_no}: ${inc}: a private header of stage '${target}' (src/${target}/), which only '${target}' may include")
        elseif(NOT target IN_LIST allowed_${stage})
          file(RELATIVE_PATH rel "${ROOT}" "${file}")
          string(REPLACE ";" ", " may "${allowed_${stage}}")
          string(STRIP "${inc}" inc)
          list(APPEND violations
               "${rel}:${line_no}: ${inc}: stage '${stage}' may not include stage '${target}' (it may include: ${may})")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

if(violations)
  # One line each, unwrapped (message() would wrap them).
  foreach(v IN LISTS violations)
    execute_process(COMMAND ${CMAKE_COMMAND} -E echo "${v}")
  endforeach()
  list(LENGTH violations n)
  message(FATAL_ERROR "layering: ${n} wrong-way include(s), listed above")
endif()
message(STATUS "layering: ${checked} files of ${ROOT} include only their own stage and the stages before it")
