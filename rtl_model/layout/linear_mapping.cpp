#include "rtl_model/layout/linear_mapping.hpp"

namespace voxcast::rtl::layout {

LinearMapping::LinearMapping(const WordGrid& grid, const sdram::Geometry& geometry)
    : AddressMapping(grid, geometry) {
  check_fits(name(), grid.words(), geometry);
  linear_index_ = true;
}

}  // namespace voxcast::rtl::layout
