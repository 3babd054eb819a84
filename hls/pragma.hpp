// VOXCAST_HLS_PRAGMA(HLS ...): a vendor HLS pragma, emitted only when a
// synthesis tool compiles the design (__SYNTHESIS__); the host compiler would
// warn about an unknown #pragma.
#pragma once

#if defined(__SYNTHESIS__)
#define VOXCAST_HLS_PRAGMA(x) _Pragma(#x)
#else
#define VOXCAST_HLS_PRAGMA(x)
#endif
