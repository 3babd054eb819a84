// VIRIM's data RAM (virim-1994.txt, "Rotator Board" and footnote 4;
// docs/heidelberg.md §7.2): the cube in 8 units by the parities of (x, y, z),
// so any 2x2x2 neighbourhood is one parallel access; each unit in two banks
// read ping-pong (bank = bit 1 of x); a repeated access to the same address is
// suppressed and the held data returned; addresses outside the software-set
// bounds read 0 (marked invalid: the LUT is not applied to them).
#pragma once

#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/virim/params.hpp"

namespace voxcast {
namespace hls {
namespace virim {

template <class HP>
struct MemoryRegisters {
  typename VirimParams<HP>::box_t lo[3], hi[3];  // inclusive bounds (crop)
  typename VirimParams<HP>::half_t hy, hx2;      // ceil(Ny/2), ceil(Nx/4)
};

// Member counters (statistics, not datapath): what suppression and bounds saved.
struct MemoryStats {
  std::uint64_t accesses = 0;     // unit reads requested (8 per neighbourhood)
  std::uint64_t suppressed = 0;   // same address as the unit's previous read: data held
  std::uint64_t out_of_bounds = 0;
  std::uint64_t bank_reads[2] = {0, 0};
};

template <class HP>
struct ParityMemory {
  using V = VirimParams<HP>;
  const std::uint16_t* bank[16];  // [unit * 2 + bank]
  MemoryRegisters<HP> regs;
  // Per unit: the last address read and the data held on its output.
  bool held[8];
  uint_t<1> held_bank[8];
  typename V::word_addr_t held_addr[8];
  std::uint16_t held_data[8];
  MemoryStats stats;

  void reset() {
    [[gnu::unused]] reset_loop : for (int u = 0; u < 8; ++u) {
      VOXCAST_HLS_PRAGMA(HLS UNROLL)
      held[u] = false;
    }
  }

  // One unit's read of voxel (x, y, z), whose parities select the unit.
  std::uint16_t unit_read(int u, const typename V::coord_t& x, const typename V::coord_t& y,
                          const typename V::coord_t& z, bool& valid) {
    ++stats.accesses;
    valid = !(x < regs.lo[0] || y < regs.lo[1] || z < regs.lo[2] || x > regs.hi[0] ||
              y > regs.hi[1] || z > regs.hi[2]);
    if (!valid) {
      ++stats.out_of_bounds;
      return 0;
    }
    const std::uint64_t ux = x.to_uint64(), uy = y.to_uint64(), uz = z.to_uint64();
    const uint_t<1> b = (ux >> 1) & 1;
    const typename V::word_addr_t addr =
        ((uz >> 1) * regs.hy.to_uint64() + (uy >> 1)) * regs.hx2.to_uint64() + (ux >> 2);
    if (held[u] && held_bank[u] == b && held_addr[u] == addr) {
      ++stats.suppressed;
      return held_data[u];
    }
    ++stats.bank_reads[b.to_uint64()];
    held[u] = true;
    held_bank[u] = b;
    held_addr[u] = addr;
    held_data[u] = bank[u * 2 + b.to_int()][addr.to_uint64()];
    return held_data[u];
  }

  // The neighbourhood of lower corner x0: value[c] and valid[c] of corner
  // c = cx + 2cy + 4cz; unit u serves corner u ^ parity(x0).
  void read8(const typename V::coord_t x0[3], std::uint16_t value[8], bool valid[8]) {
    const int p0 = (x0[0] & 1).to_int() + 2 * (x0[1] & 1).to_int() + 4 * (x0[2] & 1).to_int();
    [[gnu::unused]] unit_loop : for (int u = 0; u < 8; ++u) {
      VOXCAST_HLS_PRAGMA(HLS UNROLL)
      const int c = u ^ p0;
      const typename V::coord_t x = x0[0] + (c & 1), y = x0[1] + ((c >> 1) & 1),
                                z = x0[2] + ((c >> 2) & 1);
      value[c] = unit_read(u, x, y, z, valid[c]);
    }
  }
};

}  // namespace virim
}  // namespace hls
}  // namespace voxcast
