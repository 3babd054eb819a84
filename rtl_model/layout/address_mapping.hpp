// Where a DIMM word of the volume lives inside the DIMM: the policy that maps
// the VIZARD II word grid (vizard2_layout.hpp) onto (bank, row, column) of the
// module geometry. One interface, one implementation per file (Ramulator 2's
// address mappers):
//   linear_mapping.hpp   x fastest, then y2, then z2 (the card's obvious layout)
//   bricked_mapping.hpp  bricks of bx x by x bz words, each brick contiguous
//                        (and bricked-swizzled: banks rotated per brick y + z)
//   morton_mapping.hpp   Z-order (bit-interleaved x, y2, z2)
// Every implementation turns a coordinate into a DIMM-local word index and
// splits it with split_row_bank_column(): column bits lowest, bank bits next,
// row bits on top (Ramulator's "RoBaCo"), so consecutive indices stream
// through one row and the next row of the sequence opens in another bank.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/sdram/command.hpp"
#include "rtl_model/sdram/geometry.hpp"

namespace voxcast::rtl::layout {

// One 64-bit word of one DIMM in the VIZARD II layout: x in [0, nx), y2 = y >> 1,
// z2 = z >> 1 (vizard2_layout.hpp).
struct WordCoord {
  std::uint32_t x = 0, y2 = 0, z2 = 0;
  friend bool operator==(const WordCoord&, const WordCoord&) = default;
};

std::ostream& operator<<(std::ostream& os, const WordCoord& c);

// The words of one DIMM: nx x ny2 x nz2.
struct WordGrid {
  std::uint32_t nx = 0, ny2 = 0, nz2 = 0;

  std::uint64_t words() const { return std::uint64_t{nx} * ny2 * nz2; }
  // x fastest.
  std::uint64_t linear(const WordCoord& c) const {
    return c.x + std::uint64_t{nx} * (c.y2 + std::uint64_t{ny2} * c.z2);
  }
};

std::ostream& operator<<(std::ostream& os, const WordGrid& g);

// Column bits lowest, then bank, then row. Banks and columns must be powers
// of two (checked by check_fits).
sdram::Address split_row_bank_column(std::uint64_t index, const sdram::Geometry& g);

// A volume larger than the card's memory: not a fault of the scene or the
// model, so `voxcast cosim` runs the engines that have no such limit and names
// the cycle model as not run (its own exit status) instead of failing.
class CapacityError : public Error {
 public:
  using Error::Error;
};

// Throws CapacityError naming the mapping when `index_space` words do not fit
// the DIMM, and voxcast::Error when its banks or columns are not powers of two.
void check_fits(std::string_view mapping, std::uint64_t index_space, const sdram::Geometry& g);

// Contract (an address mapping):
//   - map() is a pure function of the coordinate and injective over the grid
//     given at construction: two words never share (bank, row, column), and
//     every result is inside the geometry (the tests check both exhaustively
//     on small grids).
//   - Constructors throw voxcast::Error when the grid does not fit the DIMM.
//   - index() is the DIMM-local word index that map() splits; it tells how
//     the policy orders words (the tests and the statistics use it).
class AddressMapping {
 public:
  virtual ~AddressMapping() = default;
  virtual std::string_view name() const = 0;
  virtual std::uint64_t index(const WordCoord& c) const = 0;
  // split_row_bank_column(index(c), geometry()), its shifts and masks
  // computed once (the address generator maps four words per sample).
  sdram::Address map(const WordCoord& c) const {
    // The linear mapping (the baseline's) without the virtual call.
    return split(linear_index_ ? grid_.linear(c) : index(c));
  }
  // split_row_bank_column(i, geometry()) (for a caller that has the index
  // from the final class, without the virtual call).
  sdram::Address split(std::uint64_t i) const {
    sdram::Address a;
    a.column = static_cast<std::uint32_t>(i & column_mask_);
    a.bank = static_cast<std::uint32_t>((i >> bank_shift_) & bank_mask_);
    a.row = static_cast<std::uint32_t>(i >> row_shift_);
    return a;
  }
  const sdram::Geometry& geometry() const { return geometry_; }
  const WordGrid& grid() const { return grid_; }

 protected:
  AddressMapping(const WordGrid& grid, const sdram::Geometry& geometry)
      : grid_(grid),
        geometry_(geometry),
        column_mask_(geometry.columns - 1u),
        bank_mask_(geometry.banks - 1u),
        bank_shift_(std::countr_zero(geometry.columns)),
        row_shift_(std::countr_zero(geometry.columns) + std::countr_zero(geometry.banks)) {}
  // Set by a mapping whose index() is grid().linear(c).
  bool linear_index_ = false;

 private:
  WordGrid grid_;
  sdram::Geometry geometry_;
  std::uint64_t column_mask_, bank_mask_;  // split_row_bank_column's
  int bank_shift_, row_shift_;
};

// The runtime choice of a mapping.
struct MappingSpec {
  std::string name = "linear";                  // "linear", "bricked", "bricked-swizzled", "morton"
  std::array<std::uint32_t, 3> brick{8, 8, 8};  // bricked: words per brick edge (powers of two)
};

std::ostream& operator<<(std::ostream& os, const MappingSpec& s);

// Throws voxcast::Error for an unknown name (naming the known ones).
std::unique_ptr<AddressMapping> make_address_mapping(const MappingSpec& spec, const WordGrid& grid,
                                                     const sdram::Geometry& geometry);
std::vector<std::string> mapping_names();

}  // namespace voxcast::rtl::layout
