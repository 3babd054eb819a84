// C simulation testbench of vizard2_frame_top (Vitis HLS csim_design /
// cosim_design): loads the frame state, the 8 packed voxel banks and the
// expected image that `voxcast synth-script` wrote for the scene
// (csim_frame.bin, docs/synthesis.md "C simulation"), runs the top and
// compares every pixel, bit for bit. Exit status 0 only if no pixel and not
// the sample count differs; a broken or mismatched data file is an error
// naming what is wrong.
//
//   csim_design -argv {<dir holding csim_frame.bin>}
//
// C++14 against the vendor's types, compiled like the top (same -cflags:
// -include elaborated_config.hpp, VOXCAST_HLS_KERNELS_ONLY). ctest compiles
// and runs it with g++ against Xilinx's headers (tests/CMakeLists.txt).
// A synthesized top's translation unit never takes the host-side loaders
// (C++20, hls/pragma.hpp): not under a vendor's synthesis, and not in a C
// simulation or a plain C++14 compile against the vendor's simulation headers.
#ifndef VOXCAST_HLS_KERNELS_ONLY
#define VOXCAST_HLS_KERNELS_ONLY
#endif
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "hls/frame_image.hpp"
#include "hls/vizard2_synth_config.hpp"

using voxcast::hls::top::Frame;
using voxcast::hls::top::Pixel;
using voxcast::hls::top::TopUnits;
using voxcast::hls::top::Word;

namespace {

// The data file: little-endian 64-bit words (cosim/hardware/synth_script.cpp writes it).
class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open");
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() % 8 != 0) fail("its size is not a whole number of 64-bit words");
    words_.resize(bytes.size() / 8);
    for (std::size_t i = 0; i < words_.size(); ++i) {
      std::uint64_t w = 0;
      for (int b = 7; b >= 0; --b)
        w = (w << 8) | static_cast<unsigned char>(bytes[i * 8 + static_cast<std::size_t>(b)]);
      words_[i] = w;
    }
  }
  std::uint64_t next(const char* what) {
    if (pos_ >= words_.size()) fail(std::string("ends before ") + what);
    return words_[pos_++];
  }
  void expect(std::uint64_t value, const char* what) {
    const std::uint64_t got = next(what);
    if (got != value)
      fail(std::string(what) + " is " + std::to_string(got) + ", this top expects " +
           std::to_string(value));
  }
  bool at_end() const { return pos_ == words_.size(); }
  [[noreturn]] void fail(const std::string& why) const {
    std::fprintf(stderr, "vizard2_frame_tb: %s: %s (word %zu)\n", path_.c_str(), why.c_str(), pos_);
    std::exit(2);
  }

  // The frame-state visitor (hls/frame_image.hpp): the fields in their order.
  template <class T>
  void bits(T& x) {
    for (int k = 0; k < voxcast::hls::image::chunks(T::width); ++k)
      voxcast::hls::image::set_chunk(x, k, next("the frame state"));
  }
  void flag(bool& b) { b = next("the frame state") != 0; }
  void mode(voxcast::hls::FrameMode& m) {
    const std::uint64_t v = next("the frame state");
    if (v > 2) fail("frame mode " + std::to_string(v) + " is not 0, 1 or 2");
    m = static_cast<voxcast::hls::FrameMode>(v);
  }

 private:
  std::string path_;
  std::vector<std::uint64_t> words_;
  std::size_t pos_ = 0;
};

constexpr std::uint64_t kMagic = 0x31454d4152465856ull;  // "VXFRAME1" as little-endian bytes

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  Reader in(dir + "/csim_frame.bin");
  in.expect(kMagic, "the file tag");
  in.expect(static_cast<std::uint64_t>(voxcast::hls::image::chunks(Word::width)),
            "the chunks per voxel word");
  const int width = static_cast<int>(in.next("the width"));
  const int height = static_cast<int>(in.next("the height"));
  if (width < 1 || height < 1 || width > 8192 || height > 8192)
    in.fail("image size " + std::to_string(width) + "x" + std::to_string(height) +
            " is outside 1..8192");

  // The frame state: megabytes for the wide profiles, so on the heap.
  std::unique_ptr<Frame> frame(new Frame());
  voxcast::hls::image::visit_frame(*frame, voxcast::hls::units_of<TopUnits>(), in);

  std::vector<Word> banks[8];
  for (std::vector<Word>& bank : banks) {
    const std::uint64_t n = in.next("a bank's word count");
    if (n > (std::uint64_t{1} << 30)) in.fail("a bank of " + std::to_string(n) + " words");
    bank.resize(static_cast<std::size_t>(n));
    for (Word& w : bank) in.bits(w);
  }

  std::vector<Pixel> fb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  std::uint64_t samples = 0;
  vizard2_frame_top(frame.get(), banks[0].data(), banks[1].data(), banks[2].data(),
                    banks[3].data(), banks[4].data(), banks[5].data(), banks[6].data(),
                    banks[7].data(), width, height, fb.data(), &samples);

  const std::uint64_t expected_samples = in.next("the expected sample count");
  std::size_t differ = 0;
  for (std::size_t i = 0; i < fb.size(); ++i) {
    bool same = true;
    for (int c = 0; c < 4; ++c) {
      const std::uint64_t want = in.next("the expected image");
      same = same && voxcast::hls::read_bits(fb[i].ch[c]) == want;
    }
    if (!same && differ++ < 10)
      std::printf("pixel (%zu, %zu) differs\n", i % static_cast<std::size_t>(width),
                  i / static_cast<std::size_t>(width));
  }
  if (!in.at_end()) in.fail("has words after the expected image");
  std::printf("vizard2_frame_tb: %dx%d pixels, %zu differ; %llu samples (expected %llu)\n", width,
              height, differ, static_cast<unsigned long long>(samples),
              static_cast<unsigned long long>(expected_samples));
  return differ == 0 && samples == expected_samples ? 0 : 1;
}
