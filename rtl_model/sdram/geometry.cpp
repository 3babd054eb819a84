#include "rtl_model/sdram/geometry.hpp"

#include <ostream>

namespace voxcast::rtl::sdram {

std::ostream& operator<<(std::ostream& os, const Geometry& g) {
  os << g.module << ": " << g.banks << " banks";
  if (g.bank_groups > 1) os << " (" << g.bank_groups << " groups)";
  return os << " x " << g.rows << " rows x " << g.columns << " columns x " << g.bus_bits
            << " bits = " << (g.bytes() >> 20) << " MB";
}

namespace geometries {
Geometry mt4lsdt864a() {
  return Geometry{
      .module = "Micron MT4LSDT864A (64 MB, 8 Meg x 64, single rank)",
      .component = "4 x Micron MT48LC8M16A2 (128Mb, 2 Meg x 16 x 4 banks)",
      .source =
          "Micron 32MB/64MB/128MB (x64, SR) 168-pin SDRAM UDIMM data sheet "
          "(SD4C4_8_16X64AG, Rev. D 1/07), p. 1; component addressing from the Micron "
          "128Mb x16 SDRAM data sheet (8 Meg x 16: 4 banks, 4K rows A0-A11, "
          "512 columns A0-A8)",
      .banks = 4,
      .rows = 4096,
      .columns = 512,
      .bus_bits = 64,
  };
}

Geometry mta18asf2g72pz() {
  return Geometry{
      .module = "Micron MTA18ASF2G72PZ-2G3 (16 GB RDIMM, 2 Gig x 72, single rank)",
      .component = "18 x Micron MT40A2G4 (8Gb, 512 Meg x 4 x 16 banks in 4 bank groups)",
      .source =
          "Micron 16GB (x72, ECC, SR) 288-pin DDR4 RDIMM data sheet (MTA18ASF2G72PZ); 8Gb x4 "
          "addressing from JESD79-4B (4 bank groups BG0-BG1, 4 banks BA0-BA1, 128K rows "
          "A0-A16, 1K columns A0-A9)",
      .banks = 16,
      .rows = 131072,
      .columns = 1024,
      .bus_bits = 64,
      .bank_groups = 4,
  };
}
}  // namespace geometries

}  // namespace voxcast::rtl::sdram
