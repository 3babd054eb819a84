#include "rtl_model/layout/address_mapping.hpp"

#include <bit>
#include <ostream>
#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/layout/bricked_mapping.hpp"
#include "rtl_model/layout/linear_mapping.hpp"
#include "rtl_model/layout/morton_mapping.hpp"

namespace voxcast::rtl::layout {

std::ostream& operator<<(std::ostream& os, const WordCoord& c) {
  return os << "word (x " << c.x << ", y2 " << c.y2 << ", z2 " << c.z2 << ")";
}

std::ostream& operator<<(std::ostream& os, const WordGrid& g) {
  return os << g.nx << " x " << g.ny2 << " x " << g.nz2 << " words";
}

std::ostream& operator<<(std::ostream& os, const MappingSpec& s) {
  os << s.name;
  if (s.name == "bricked") os << " " << s.brick[0] << "x" << s.brick[1] << "x" << s.brick[2];
  return os;
}

sdram::Address split_row_bank_column(std::uint64_t index, const sdram::Geometry& g) {
  const int cb = std::countr_zero(g.columns);
  const int bb = std::countr_zero(g.banks);
  sdram::Address a;
  a.column = static_cast<std::uint32_t>(index & (g.columns - 1u));
  a.bank = static_cast<std::uint32_t>((index >> cb) & (g.banks - 1u));
  a.row = static_cast<std::uint32_t>(index >> (cb + bb));
  return a;
}

void check_fits(std::string_view mapping, std::uint64_t index_space, const sdram::Geometry& g) {
  std::ostringstream os;
  os << "address mapping '" << mapping << "': ";
  if (!std::has_single_bit(g.columns) || !std::has_single_bit(g.banks)) {
    os << "banks and columns must be powers of two (" << g << ")";
    throw Error(os.str());
  }
  const std::uint64_t capacity = std::uint64_t{g.banks} * g.rows * g.columns;
  if (index_space > capacity) {
    os << index_space << " words do not fit the DIMM's " << capacity << " (" << g.module << ")";
    throw CapacityError(os.str());
  }
}

std::vector<std::string> mapping_names() {
  return {"linear", "bricked", "bricked-swizzled", "morton"};
}

std::unique_ptr<AddressMapping> make_address_mapping(const MappingSpec& spec, const WordGrid& grid,
                                                     const sdram::Geometry& geometry) {
  if (spec.name == "linear") return std::make_unique<LinearMapping>(grid, geometry);
  if (spec.name == "bricked") return std::make_unique<BrickedMapping>(grid, geometry, spec.brick);
  if (spec.name == "bricked-swizzled")
    return std::make_unique<BrickedMapping>(grid, geometry, spec.brick, true);
  if (spec.name == "morton") return std::make_unique<MortonMapping>(grid, geometry);
  throw Error("unknown address mapping '" + spec.name +
              "' (known: linear, bricked, bricked-swizzled, morton)");
}

}  // namespace voxcast::rtl::layout
