// The organisation of one DIMM as the controller addresses it: one rank of
// internal banks, each of rows x columns, every column one beat of the
// module's data bus.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

namespace voxcast::rtl::sdram {

struct Geometry {
  std::string module;     // module part number and organisation
  std::string component;  // the SDRAM devices on it
  std::string source;     // datasheet
  std::uint32_t banks = 0;
  std::uint32_t rows = 0;     // per bank
  std::uint32_t columns = 0;  // per row, in bus beats
  std::uint32_t bus_bits = 0;
  // DDR4 bank groups (JESD79-4B: 4 in 8Gb x4/x8 parts); the banks above are
  // all of them, group g holding banks g * banks_per_group() onwards. SDR: 1.
  std::uint32_t bank_groups = 1;

  std::uint32_t banks_per_group() const { return banks / bank_groups; }
  std::uint32_t group_of(std::uint32_t bank) const { return bank / banks_per_group(); }
  std::uint32_t bytes_per_beat() const { return bus_bits / 8; }
  std::uint64_t bytes_per_row() const { return std::uint64_t{columns} * bytes_per_beat(); }
  std::uint64_t bytes() const { return std::uint64_t{banks} * rows * bytes_per_row(); }
};

std::ostream& operator<<(std::ostream& os, const Geometry& g);

namespace geometries {
// Micron MT4LSDT864A, 64 MB (8 Meg x 64), single rank, PC100/PC133 168-pin
// unbuffered DIMM: four MT48LC8M16A2 (128Mb, 2 Meg x 16 x 4 banks), each
// 4,096 rows (A0-A11) x 512 columns (A0-A8) per bank, side by side on the
// 64-bit bus: 4 banks x 4096 rows x 512 columns x 64 bits = 64 MB.
// VIZARD II's 256^3 volume at 64 bits per voxel pair is 32 MB per DIMM.
Geometry mt4lsdt864a();
// Micron MTA18ASF2G72PZ-2G3, 16 GB DDR4 RDIMM, single rank: 18 x MT40A2G4
// (8Gb x4: 4 bank groups x 4 banks, 128K rows A0-A16, 1K columns), 16 on the
// 64 data bits (2 for ECC, not modelled): 16 banks x 131,072 rows x 1,024
// columns x 64 bits = 16 GiB (the U250's DIMM, constraints/boards/alveo_u250.toml).
Geometry mta18asf2g72pz();
}  // namespace geometries

}  // namespace voxcast::rtl::sdram
