// What a vendor HLS tool sees of the design.
//
// VOXCAST_HLS_PRAGMA(HLS ...): a vendor HLS pragma, emitted only when a
// synthesis tool compiles the design (__SYNTHESIS__); the host compiler would
// warn about an unknown #pragma.
//
// VOXCAST_HLS_HOST_CODE: 1 where the host side of each unit header (the
// host:: loaders from the bit-true set-up, which use std::vector, strings,
// exceptions and C++20) is compiled, 0 where only the kernels are: under
// __SYNTHESIS__, and under VOXCAST_HLS_KERNELS_ONLY, which the synthesized
// tops' and the testbench's own files define (a C simulation has no
// __SYNTHESIS__, Xilinx's simulation headers refuse it, and those files are
// C++14 like the design; docs/synthesis.md).
#pragma once

#if defined(__SYNTHESIS__)
#define VOXCAST_HLS_PRAGMA(x) _Pragma(#x)
#else
#define VOXCAST_HLS_PRAGMA(x)
#endif

#if defined(__SYNTHESIS__) || defined(VOXCAST_HLS_KERNELS_ONLY)
#define VOXCAST_HLS_HOST_CODE 0
#else
#define VOXCAST_HLS_HOST_CODE 1
#endif

// VOXCAST_HLS_HOST_INLINE: marks a unit function of the per-sample path that the
// host compiler must inline into the engines' sample loop (the hls engine's
// speed, docs/performance.md "Speed of the hls engine"); without it -O2 leaves
// most of them as calls, whose fixed-point arguments then pass through memory.
// Only where VOXCAST_HLS_HOST_FAST is defined: the engines' own instantiations
// (cosim/engines/hls_engine.cpp, rtl_model/engine.cpp), where CMake sets it
// on those files in the builds made for speed: the default fixed-point class,
// optimized, no sanitizer (hls/CMakeLists.txt). Everywhere else (the dialect and
// C-simulation checks, the vendors' headers, the unit tests) the forced
// inlining only costs compile time: it made the Xilinx ap_fixed build 10x
// slower (docs/extremes.md, "CI steps"). Nothing under __SYNTHESIS__: there
// the unit's own INLINE / LATENCY pragmas decide the hierarchy.
#if defined(__SYNTHESIS__) || !defined(VOXCAST_HLS_HOST_FAST)
#define VOXCAST_HLS_HOST_INLINE inline
#else
#define VOXCAST_HLS_HOST_INLINE [[gnu::always_inline]] inline
#endif

// VOXCAST_HLS_HOST_UNROLL: between a loop's label and its `for`, unrolls the loop
// completely on the host (a loop the design unrolls with HLS UNROLL, in the
// per-sample path), so its fixed-point arrays live in registers. Under the same
// condition as VOXCAST_HLS_HOST_INLINE; nothing under __SYNTHESIS__, where the
// loop's own HLS UNROLL pragma applies.
#if defined(__SYNTHESIS__) || !defined(VOXCAST_HLS_HOST_FAST)
#define VOXCAST_HLS_HOST_UNROLL
#else
#define VOXCAST_HLS_HOST_UNROLL _Pragma("GCC unroll 16")
#endif
