# The C simulation testbench `voxcast synth-script` sets up (docs/synthesis.md,
# "C simulation"): synth-script writes the default scene's elaborated_config.hpp
# and csim_frame.bin; hls/tb/vizard2_frame_tb.cpp and the top are compiled as a
# Vitis csim would, C++14 with g++ against Xilinx's ap_fixed headers
# (VOXCAST_VENDOR_DIR), and run: 0 differing pixels, and a corrupted expected
# pixel must fail it. Without the vendor headers both tests say SKIPPED.
set(csim_dir ${CMAKE_CURRENT_BINARY_DIR}/csim/default)
set(csim_xilinx ${VOXCAST_VENDOR_DIR}/xilinx-ap-types/include)
if(NOT EXISTS ${csim_xilinx}/ap_fixed.h)
  foreach(name csim.vizard2_frame_tb csim.corrupted_pixel_fails)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -E echo
             "SKIPPED: the vendor headers are absent (${csim_xilinx}/ap_fixed.h)")
    set_tests_properties(${name} PROPERTIES SKIP_REGULAR_EXPRESSION "SKIPPED:" LABELS csim)
  endforeach()
  return()
endif()

add_custom_command(OUTPUT ${csim_dir}/elaborated_config.hpp ${csim_dir}/csim_frame.bin
  COMMAND voxcast synth-script ${PROJECT_SOURCE_DIR}/scenes/default.toml
          --out ${csim_dir} --source-dir ${PROJECT_SOURCE_DIR}
  DEPENDS voxcast ${PROJECT_SOURCE_DIR}/scenes/default.toml
  COMMENT "voxcast synth-script: csim data of scenes/default.toml" VERBATIM)
add_custom_target(voxcast_csim_data DEPENDS ${csim_dir}/elaborated_config.hpp
                                            ${csim_dir}/csim_frame.bin)

add_executable(voxcast_csim_tb ${PROJECT_SOURCE_DIR}/hls/tb/vizard2_frame_tb.cpp
                               ${PROJECT_SOURCE_DIR}/hls/vizard2_synth_top.cpp)
add_dependencies(voxcast_csim_tb voxcast_csim_data)
# Compiled as the vendor's csim compiles it, not with the project's policy: an
# instrumented (asan preset) build would report UBSan findings inside Xilinx's
# simulation headers (ap_private.h shifts negative values left, undefined in
# C++14), which are the vendor's code, not the design's.
target_compile_options(voxcast_csim_tb PRIVATE -Wall -Wextra -pedantic -ffp-contract=off
                       $<$<BOOL:${VOXCAST_WERROR}>:-Werror>)
target_include_directories(voxcast_csim_tb PRIVATE ${PROJECT_SOURCE_DIR})
target_include_directories(voxcast_csim_tb SYSTEM PRIVATE ${csim_xilinx})
target_compile_definitions(voxcast_csim_tb PRIVATE VOXCAST_VENDOR_TYPES VOXCAST_HLS_KERNELS_ONLY)
# ap_fixed's default constructor leaves the value unset (as documented), and at
# -O2 GCC's flow analysis reports reads of such temporaries inside the inlined
# vendor headers, which -isystem does not silence; the design's own code keeps
# both warnings (the dialect tests compile it with them).
target_compile_options(voxcast_csim_tb PRIVATE "SHELL:-include ${csim_dir}/elaborated_config.hpp"
                       -Wno-maybe-uninitialized -Wno-uninitialized)
set_target_properties(voxcast_csim_tb PROPERTIES CXX_STANDARD 14 CXX_EXTENSIONS OFF
                      UNITY_BUILD OFF DISABLE_PRECOMPILE_HEADERS ON)

add_test(NAME csim.vizard2_frame_tb COMMAND voxcast_csim_tb ${csim_dir})
set_tests_properties(csim.vizard2_frame_tb PROPERTIES LABELS csim
                     PASS_REGULAR_EXPRESSION "pixels, 0 differ;")
add_test(NAME csim.corrupted_pixel_fails
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/csim/corrupt_one_pixel.sh
                 $<TARGET_FILE:voxcast_csim_tb> ${csim_dir} ${CMAKE_CURRENT_BINARY_DIR}/csim/corrupt)
set_tests_properties(csim.corrupted_pixel_fails PROPERTIES LABELS csim)
