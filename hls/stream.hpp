// The FIFO channel between the stages of the streamed top (hls/vizard2_dataflow.hpp):
// voxcast::hls::fifo<T>, with the read()/write()/empty() of the vendors' stream
// types.
//
//   -DVOXCAST_VENDOR_TYPES with Xilinx's <hls_stream.h> on the include path:
//       hls::stream<T> itself (Vitis HLS maps it to a FIFO; STREAM depth pragmas
//       at the declaration set its depth).
//   -DVOXCAST_AC_TYPES: Catapult's ac_channel<T> (<ac_channel.h>).
//   otherwise, and with the Xilinx ap_ headers but without <hls_stream.h>
//   (the headers in ../shared/vendor are the type headers only): the
//   stand-in below, which has hls::stream's C simulation semantics.
//
// The stand-in: in a C simulation the processes of a DATAFLOW region run one
// after another, in call order, so every channel has to hold everything its
// producer writes before its consumer starts. hls::stream's own simulation
// model is therefore an unbounded queue (a std::deque), and so is this one;
// reading an empty channel is the C simulation's "read while empty" error,
// which here stops the program with a message (a dataflow region whose
// producer wrote fewer tokens than its consumer reads has a bug that would
// hang the hardware). The streamed top runs its region once per image row, so
// a channel holds at most one row's samples.
//
// Under __SYNTHESIS__ without a vendor stream header the stand-in is a
// declaration the synthesizability checker parses (tools/synth_lint, where
// this header is exempt like the fixed-point clone): a vendor tool brings its
// own stream type. C++14.
#pragma once

#if defined(VOXCAST_AC_TYPES)
#include <ac_channel.h>
#elif defined(VOXCAST_VENDOR_TYPES) && defined(__has_include)
#if __has_include(<hls_stream.h>)
#include <hls_stream.h>
#define VOXCAST_HLS_STREAM_FROM_VENDOR 1
#endif
#endif

#if !defined(VOXCAST_AC_TYPES) && !defined(VOXCAST_HLS_STREAM_FROM_VENDOR)
#include <cstdio>
#include <cstdlib>
#include <deque>
#endif

namespace voxcast {
namespace hls {

#if defined(VOXCAST_AC_TYPES)
template <class T>
using fifo = ac_channel<T>;
#elif defined(VOXCAST_HLS_STREAM_FROM_VENDOR)
template <class T>
using fifo = ::hls::stream<T>;
#else
template <class T>
class fifo {
 public:
  fifo() = default;
  fifo(const fifo&) = delete;  // a channel is a wire between two processes
  fifo& operator=(const fifo&) = delete;

  void write(const T& t) { queue_.push_back(t); }
  T read() {
    if (queue_.empty()) {
      std::fprintf(stderr, "voxcast::hls::fifo: read while empty (a dataflow process read more "
                           "tokens than its producer wrote)\n");
      std::abort();
    }
    T t = queue_.front();
    queue_.pop_front();
    return t;
  }
  bool empty() const { return queue_.empty(); }
  unsigned size() const { return static_cast<unsigned>(queue_.size()); }

 private:
  std::deque<T> queue_;
};
#endif

}  // namespace hls
}  // namespace voxcast
