// The exhaustive quantization sweep (tests/hls/fixed_quantize_sweep.hpp) for signed targets,
// W = 1..6: every target format, source pattern, C int and double of the sweep.
#include "tests/hls/fixed_quantize_sweep.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::fixed_quantize_sweep::run_sweep;

TEST(FixedQuantizeExhaustive, SignedW1) { run_sweep<1, true>(); }
TEST(FixedQuantizeExhaustive, SignedW2) { run_sweep<2, true>(); }
TEST(FixedQuantizeExhaustive, SignedW3) { run_sweep<3, true>(); }
TEST(FixedQuantizeExhaustive, SignedW4) { run_sweep<4, true>(); }
TEST(FixedQuantizeExhaustive, SignedW5) { run_sweep<5, true>(); }
TEST(FixedQuantizeExhaustive, SignedW6) { run_sweep<6, true>(); }

}  // namespace
