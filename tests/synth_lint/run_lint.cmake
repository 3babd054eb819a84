# Runs voxcast_synth_lint and checks its verdict (tests/synth_lint/CMakeLists.txt).
#
#   cmake -DEXPECT=violations|clean|error -DSOURCE=FILE [-DTOP=NAME]
#         -P run_lint.cmake TOOL ARGS...
#
# violations: SOURCE marks each line the checker must flag with a comment
#   `expect-lint: RULE`. The tool must exit 1, report every marked (line, rule)
#   and nothing else. A SOURCE without marks is an error of the test itself, so
#   a violation test cannot pass vacuously.
# clean: exit 0, no error lines, and the summary "N functions reachable from
#   TOP, 0 violations".
# error: exit 2 (the translation unit does not parse, or a top is missing).

cmake_policy(VERSION 3.25)

# The tool and its arguments: everything after `-P script`.
set(command)
set(after_script FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE 1 ${last})
  if(after_script)
    list(APPEND command "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "-P")
    math(EXPR script "${i} + 1")
    set(skip ${script})
  elseif(DEFINED skip AND i EQUAL skip)
    set(after_script TRUE)
  endif()
endforeach()

execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
get_filename_component(name "${SOURCE}" NAME)
string(REPLACE "." "\\." name_re "${name}")

# The error lines of the output, as "file:line:rule".
string(REGEX MATCHALL "[^\n]*: error: \\[[a-z-]+\\][^\n]*" error_lines "${out}")
set(reported)
foreach(line IN LISTS error_lines)
  if(line MATCHES "^(.*):([0-9]+):[0-9]+: error: \\[([a-z-]+)\\]")
    get_filename_component(file "${CMAKE_MATCH_1}" NAME)
    list(APPEND reported "${file}:${CMAKE_MATCH_2}:${CMAKE_MATCH_3}")
  endif()
endforeach()

if(EXPECT STREQUAL "violations")
  file(STRINGS "${SOURCE}" lines)
  set(expected)
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    if(line MATCHES "expect-lint: ([a-z-]+)")
      list(APPEND expected "${name}:${n}:${CMAKE_MATCH_1}")
    endif()
  endforeach()
  if(NOT expected)
    message(FATAL_ERROR "${SOURCE} marks no line with `expect-lint: RULE`")
  endif()
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "expected exit 1 (violations), got ${rc}")
  endif()
  foreach(e IN LISTS expected)
    if(NOT e IN_LIST reported)
      message(FATAL_ERROR "missing diagnostic ${e}")
    endif()
  endforeach()
  foreach(r IN LISTS reported)
    if(NOT r IN_LIST expected)
      message(FATAL_ERROR "unexpected diagnostic ${r}")
    endif()
  endforeach()
elseif(EXPECT STREQUAL "clean")
  if(NOT rc EQUAL 0 OR reported)
    message(FATAL_ERROR "expected a clean pass (exit 0), got exit ${rc} and ${reported}")
  endif()
  if(NOT out MATCHES "[0-9]+ functions reachable from ${TOP}, 0 violations")
    message(FATAL_ERROR "no summary line for ${TOP}")
  endif()
elseif(EXPECT STREQUAL "error")
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "expected exit 2 (the input is refused), got ${rc}")
  endif()
else()
  message(FATAL_ERROR "EXPECT must be violations, clean or error")
endif()
