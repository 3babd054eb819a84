# cmake -DROOT=<a cosim folder> -P tools/check_cosim_rooms.cmake
#
# cosim/'s rooms and the one way their dependencies point (README, "Layout"):
#
#   reports  <-  engines  <-  hardware  <-  explore  <-  cluster
#                         <-  verify   <------------------'
#   commands uses every room; main.cpp dispatches to commands (and catches the
#   precision guard's error from engines).
#
# Every source of ROOT must sit in a room (main.cpp alone at the top), and each
# `#include "cosim/ROOM/..."` must name a room its own may use. Prints one line
# per violation, naming the file and the include, and fails if there is any.
cmake_minimum_required(VERSION 3.25)
if(NOT DEFINED ROOT)
  message(FATAL_ERROR "check_cosim_rooms: give -DROOT=<cosim folder>")
endif()

set(allowed_reports  reports)
set(allowed_engines  reports engines)
set(allowed_hardware reports engines hardware)
set(allowed_verify   reports engines verify)
set(allowed_explore  reports engines hardware explore)
set(allowed_cluster  reports engines hardware verify explore cluster)
set(allowed_commands reports engines hardware verify explore cluster commands)
set(allowed_main     commands engines)
set(rooms reports engines hardware verify explore cluster commands)

file(GLOB_RECURSE sources RELATIVE "${ROOT}" "${ROOT}/*.cpp" "${ROOT}/*.hpp")
list(SORT sources)
set(violations 0)
foreach(rel IN LISTS sources)
  if(rel STREQUAL "main.cpp")
    set(room main)
  else()
    string(REGEX MATCH "^([a-z_]+)/[^/]+$" _ "${rel}")
    set(room "${CMAKE_MATCH_1}")
    if(NOT room OR NOT room IN_LIST rooms)
      string(REPLACE ";" ", " names "${rooms}")
      message("cosim/${rel}: not in a room (${names}); only main.cpp sits at the top")
      math(EXPR violations "${violations} + 1")
      continue()
    endif()
  endif()
  file(STRINGS "${ROOT}/${rel}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"cosim/")
  foreach(line IN LISTS includes)
    string(REGEX MATCH "\"cosim/([^\"]*)\"" _ "${line}")
    set(target "${CMAKE_MATCH_1}")
    string(REGEX MATCH "^([a-z_]+)/" _ "${target}")
    set(target_room "${CMAKE_MATCH_1}")
    if(NOT target_room OR NOT target_room IN_LIST allowed_${room})
      string(REPLACE ";" ", " names "${allowed_${room}}")
      message("cosim/${rel} includes cosim/${target}: the ${room} room may use only ${names}")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()
if(violations GREATER 0)
  message(FATAL_ERROR "check_cosim_rooms: ${violations} include(s) against the rooms' order")
endif()
list(LENGTH sources n)
message(STATUS "check_cosim_rooms: ${n} sources, every include one way")
