# The design in its vendors' dialect (issue 15, docs/synthesis.md): every
# synthesizable top compiles as C++14 with g++ and with clang++, with
# -Wall -Wextra -Werror -pedantic -fno-exceptions -fno-rtti, on voxcast's own
# fixed-point types (hls/fixed_point.hpp) and on the vendors' own headers
# (Xilinx ap_fixed, Catapult ac_fixed; ../shared/vendor). One ctest case per
# (compiler, types, top): a kernel that slips back into C++17/20 fails here
# naming the file and line.
#
# The two warnings turned off are the HLS idioms a host compiler does not know:
# vendor pragmas (-Wno-unknown-pragmas) — loop labels are marked [[gnu::unused]]
# in the code instead. On voxcast's types the tops are compiled with
# -D__SYNTHESIS__ (pragmas live, host code out); Xilinx's simulation headers
# refuse __SYNTHESIS__, so the vendor builds compile without it, as a C
# simulation does: the top's own file defines VOXCAST_HLS_KERNELS_ONLY (host
# code out, hls/pragma.hpp).
set(voxcast_dialect_flags -std=c++14 -fsyntax-only -Wall -Wextra -Werror -pedantic
    -fno-exceptions -fno-rtti -Wno-unknown-pragmas -I${PROJECT_SOURCE_DIR})
# voxcast_host_cxx_gcc / _clang: found in tests/CMakeLists.txt.

set(voxcast_dialect_types_clone -D__SYNTHESIS__)
set(voxcast_dialect_types_xilinx -DVOXCAST_VENDOR_TYPES
    -isystem ${VOXCAST_VENDOR_DIR}/xilinx-ap-types/include)
set(voxcast_dialect_header_xilinx ${VOXCAST_VENDOR_DIR}/xilinx-ap-types/include/ap_fixed.h)
set(voxcast_dialect_types_catapult -DVOXCAST_AC_TYPES
    -isystem ${VOXCAST_VENDOR_DIR}/ac-types/include)
set(voxcast_dialect_header_catapult ${VOXCAST_VENDOR_DIR}/ac-types/include/ac_fixed.h)

set(voxcast_dialect_top_vizard2 hls/vizard2_synth_top.cpp -DVOXCAST_SYNTH_PROFILE=Vizard2Traits)
set(voxcast_dialect_top_balanced hls/vizard2_synth_top.cpp -DVOXCAST_SYNTH_PROFILE=BalancedTraits)
set(voxcast_dialect_top_precise hls/vizard2_synth_top.cpp -DVOXCAST_SYNTH_PROFILE=PreciseTraits)
set(voxcast_dialect_top_virim hls/virim/virim_synth_top.cpp)

foreach(compiler gcc clang)
  set(cxx ${voxcast_host_cxx_${compiler}})
  if(NOT cxx)
    message(STATUS "dialect tests: no ${compiler} found; its C++14 checks are not registered")
    continue()
  endif()
  foreach(types clone xilinx catapult)
    foreach(top vizard2 balanced precise virim)
      set(name dialect.cxx14.${compiler}.${types}.${top})
      list(GET voxcast_dialect_top_${top} 0 source)
      set(top_flags ${voxcast_dialect_top_${top}})
      list(REMOVE_AT top_flags 0)
      if(DEFINED voxcast_dialect_header_${types} AND NOT EXISTS ${voxcast_dialect_header_${types}})
        # A clone without ../shared/vendor: said in one line, never passed silently.
        add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -E echo
                 "SKIPPED: the vendor headers are absent (${voxcast_dialect_header_${types}})")
        set_tests_properties(${name} PROPERTIES SKIP_REGULAR_EXPRESSION "SKIPPED:")
      else()
        add_test(NAME ${name}
                 COMMAND ${cxx} ${voxcast_dialect_flags} ${voxcast_dialect_types_${types}}
                         ${top_flags} ${PROJECT_SOURCE_DIR}/${source})
      endif()
      set_tests_properties(${name} PROPERTIES LABELS "dialect;hls")
    endforeach()
  endforeach()
endforeach()

# The command a new user types (issue 15), exactly: the preset's value name,
# Xilinx's folder with -I, no other flag.
if(EXISTS ${voxcast_dialect_header_xilinx} AND voxcast_host_cxx_gcc)
  add_test(NAME dialect.cxx14.user_command
           COMMAND ${voxcast_host_cxx_gcc} -std=c++14 -fsyntax-only -DVOXCAST_VENDOR_TYPES
                   -DVOXCAST_SYNTH_PROFILE=kBalanced -I${PROJECT_SOURCE_DIR}
                   -I${VOXCAST_VENDOR_DIR}/xilinx-ap-types/include
                   ${PROJECT_SOURCE_DIR}/hls/vizard2_synth_top.cpp)
  set_tests_properties(dialect.cxx14.user_command PROPERTIES LABELS "dialect;hls")
endif()
