// The exhaustive quantization sweep (tests/hls/fixed_quantize_sweep.hpp) for unsigned targets,
// W = 1..6: every target format, source pattern, C int and double of the sweep.
#include "tests/hls/fixed_quantize_sweep.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::fixed_quantize_sweep::run_sweep;

TEST(FixedQuantizeExhaustive, UnsignedW1) { run_sweep<1, false>(); }
TEST(FixedQuantizeExhaustive, UnsignedW2) { run_sweep<2, false>(); }
TEST(FixedQuantizeExhaustive, UnsignedW3) { run_sweep<3, false>(); }
TEST(FixedQuantizeExhaustive, UnsignedW4) { run_sweep<4, false>(); }
TEST(FixedQuantizeExhaustive, UnsignedW5) { run_sweep<5, false>(); }
TEST(FixedQuantizeExhaustive, UnsignedW6) { run_sweep<6, false>(); }

}  // namespace
