// Headerless raw volumes: dims[0]*dims[1]*dims[2] voxels, x fastest, no padding.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::ref {
namespace {

constexpr int kMaxDim = 65535;

const char* type_name(RawType t) {
  switch (t) {
    case RawType::U8:
      return "u8";
    case RawType::U16:
      return "u16";
    case RawType::I16:
      return "i16";
  }
  return "?";
}

std::uint64_t bytes_per_voxel(RawType t) { return t == RawType::U8 ? 1 : 2; }

std::string dims_text(const std::array<int, 3>& d) {
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

}  // namespace

Volume load_raw(const std::string& path, const RawSpec& spec) {
  // Step 1: the spec.
  static const char* const kAxis[3] = {"x", "y", "z"};
  std::uint64_t voxels = 1;
  for (int a = 0; a < 3; ++a) {
    if (spec.dims[a] < 1 || spec.dims[a] > kMaxDim)
      throw Error(path + ": volume.dims " + kAxis[a] + " = " + std::to_string(spec.dims[a]) +
                  " is not a valid size (1.." + std::to_string(kMaxDim) + ")");
    voxels *= static_cast<std::uint64_t>(spec.dims[a]);
  }
  if (voxels > kMaxLoadVoxels)
    throw Error(path + ": volume.dims " + dims_text(spec.dims) + " hold " + std::to_string(voxels) +
                " voxels, more than the limit of 2^31");

  // Step 2: the file must hold exactly the voxels the spec describes.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw Error(path + ": no such file");
  if (!std::filesystem::is_regular_file(status)) throw Error(path + ": not a regular file");
  const std::uint64_t have = std::filesystem::file_size(path, ec);
  if (ec) throw Error(path + ": cannot read its size (" + ec.message() + ")");
  const std::uint64_t need = voxels * bytes_per_voxel(spec.type);
  if (have != need)
    throw Error(path + ": holds " + std::to_string(have) + " bytes, dims " + dims_text(spec.dims) +
                " of " + type_name(spec.type) + " need " + std::to_string(need));

  std::vector<unsigned char> bytes(need);
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open for reading");
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(need));
    if (static_cast<std::uint64_t>(in.gcount()) != need)
      throw Error(path + ": read " + std::to_string(in.gcount()) + " of " + std::to_string(need) +
                  " bytes");
  }

  // Step 3: values. Signed data are shifted so the smallest value is stored as
  // 0 (only if it is negative); the intercept records the shift.
  Volume v;
  v.dims = spec.dims;
  v.spacing = spec.spacing;
  v.source = path;
  v.data.resize(static_cast<std::size_t>(voxels));
  const std::size_t n = v.data.size();
  if (spec.type == RawType::U8) {
    for (std::size_t i = 0; i < n; ++i) v.data[i] = bytes[i];
  } else {
    const std::size_t hi = spec.big_endian ? 0 : 1, lo = 1 - hi;
    for (std::size_t i = 0; i < n; ++i)
      v.data[i] = static_cast<std::uint16_t>((bytes[2 * i + hi] << 8) | bytes[2 * i + lo]);
  }
  if (spec.type == RawType::I16) {
    // Two's complement: the bit pattern w is the value w - 65536 when w >= 32768.
    auto value = [](std::uint16_t w) { return w >= 0x8000 ? static_cast<int>(w) - 0x10000 : w; };
    int min_value = std::numeric_limits<int>::max();
    for (std::uint16_t w : v.data) min_value = std::min(min_value, static_cast<int>(value(w)));
    const int shift = std::min(min_value, 0);
    for (std::uint16_t& w : v.data) w = static_cast<std::uint16_t>(value(w) - shift);
    v.intercept = shift;
  }
  const std::uint16_t max_stored =
      v.data.empty() ? std::uint16_t{0} : *std::max_element(v.data.begin(), v.data.end());
  v.bits = bits_for(max_stored);
  v.slope = 1.0;
  validate(v, path);
  return v;
}

}  // namespace voxcast::ref
