# The operation-level differential test of the fixed-point types (issue 16,
# docs/fixed-point.md, "Differential test"): tests/differential/engine.cpp is
# compiled once per hls/types.hpp mapping -- the clone, Xilinx's ap_fixed
# (VOXCAST_VENDOR_TYPES) and Catapult's ac_fixed (VOXCAST_AC_TYPES), from
# VOXCAST_VENDOR_DIR -- and per chunk of the type-pair list (the vendor objects
# are the slow ones to compile: ap's simulation headers; the chunks compile in
# parallel), and linked with the driver into voxcast_differential. The ctest
# case runs a bounded fixed-seed sample (label `differential`); a longer run is
# the same program with --records / --seed. Without the vendor headers the test
# says SKIPPED.
set(diff_xilinx ${VOXCAST_VENDOR_DIR}/xilinx-ap-types/include)
set(diff_catapult ${VOXCAST_VENDOR_DIR}/ac-types/include)
if(NOT EXISTS ${diff_xilinx}/ap_fixed.h OR NOT EXISTS ${diff_catapult}/ac_fixed.h)
  add_test(NAME differential.fixed_point COMMAND ${CMAKE_COMMAND} -E echo
           "SKIPPED: the vendor headers are absent (${diff_xilinx}/ap_fixed.h, ${diff_catapult}/ac_fixed.h)")
  set_tests_properties(differential.fixed_point PROPERTIES
                       SKIP_REGULAR_EXPRESSION "SKIPPED:" LABELS "differential;hls")
  return()
endif()

# Records of the CI run (each compared against ap and against ac) and its seed.
set(VOXCAST_DIFF_RECORDS 2000000 CACHE STRING "Operation records of the differential ctest case")
set(VOXCAST_DIFF_SEED 16 CACHE STRING "Seed of the differential ctest case")
# Chunks per engine (objects compiled in parallel).
set(diff_chunks_clone 2)
set(diff_chunks_ap 6)
set(diff_chunks_ac 2)
set(diff_defs_clone "")
set(diff_defs_ap VOXCAST_VENDOR_TYPES)
set(diff_defs_ac VOXCAST_AC_TYPES)

add_executable(voxcast_differential differential/main.cpp)
foreach(engine ap ac clone)  # the slowest first
  math(EXPR last "${diff_chunks_${engine}} - 1")
  foreach(chunk RANGE ${last})
    set(t voxcast_differential_${engine}_${chunk})
    add_library(${t} OBJECT differential/engine.cpp)
    target_compile_definitions(${t} PRIVATE ${diff_defs_${engine}} VOXCAST_DIFF_CHUNK=${chunk}
                               VOXCAST_DIFF_CHUNKS=${diff_chunks_${engine}})
    target_sources(voxcast_differential PRIVATE $<TARGET_OBJECTS:${t}>)
    list(APPEND diff_targets ${t})
  endforeach()
endforeach()
foreach(t voxcast_differential ${diff_targets})
  target_include_directories(${t} PRIVATE ${PROJECT_SOURCE_DIR})
  target_include_directories(${t} SYSTEM PRIVATE ${diff_xilinx} ${diff_catapult})
  # Not the project's policy (voxcast_policy): the program is compiled as a vendor C
  # simulation compiles it, uninstrumented in the asan build too -- UBSan reports Xilinx's
  # own code there (ap_private.h shifts negative values left), as for the csim testbench
  # (tests/csim.cmake). -O0: the cost is compiling (ap's headers), not running.
  target_compile_options(${t} PRIVATE -Wall -Wextra -O0 -g0 $<$<BOOL:${VOXCAST_WERROR}>:-Werror>)
  set_target_properties(${t} PROPERTIES CXX_STANDARD 17 CXX_EXTENSIONS OFF UNITY_BUILD OFF
                        DISABLE_PRECOMPILE_HEADERS ON)
endforeach()

add_test(NAME differential.fixed_point
         COMMAND voxcast_differential --records ${VOXCAST_DIFF_RECORDS} --seed ${VOXCAST_DIFF_SEED})
set_tests_properties(differential.fixed_point PROPERTIES LABELS "differential;hls" TIMEOUT 300)
