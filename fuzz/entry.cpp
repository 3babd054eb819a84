// libFuzzer entry for one target (VOXCAST_FUZZ_TARGET names it; fuzz/CMakeLists.txt).
// The contract of every target: an input either succeeds or is rejected with
// voxcast::Error. Anything else escapes this function and is a finding: another
// exception (libFuzzer reports the abort of std::terminate), a crash, a
// sanitizer report, or a fuzz::Finding thrown by a differential check.
#include <cstddef>
#include <cstdint>

#include "fuzz/targets/targets.hpp"
#include "refmodel/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    voxcast::fuzz::VOXCAST_FUZZ_TARGET(data, size);
  } catch (const voxcast::Error&) {
    // A clear rejection of bad input: the expected outcome.
  }
  return 0;
}
