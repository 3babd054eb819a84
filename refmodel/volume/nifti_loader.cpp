// NIfTI-1 volumes (.nii, .nii.gz, .hdr/.img) through niftilib.
//
// niftilib parses the header and resolves the data file and byte order; the
// data are then read here through its znzlib with an exact byte count, because
// nifti_image_load() silently zero-fills a truncated file.
#include <nifti1_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::ref {
namespace {

constexpr std::uint32_t kMaxStored16 = 0xFFFF;

struct HeaderFree {
  void operator()(nifti_1_header* h) const { std::free(h); }
};
struct ImageFree {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
struct ZnzClose {
  void operator()(znzptr* f) const {
    znzFile file = f;
    znzclose(file);
  }
};

std::string unreadable(const std::string& path, const std::string& why) {
  return path + ": not a readable NIfTI-1 file (" + why + ")";
}

std::string num(double value) {
  std::string s = std::to_string(value);
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  return std::isfinite(value) ? s : (std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf"));
}

// Millimetres per unit of the header's xyz_units (unknown units are taken as mm).
double mm_per_unit(int xyzt_units) {
  switch (XYZT_TO_SPACE(xyzt_units)) {
    case NIFTI_UNITS_METER:
      return 1000.0;
    case NIFTI_UNITS_MICRON:
      return 0.001;
    default:
      return 1.0;
  }
}

// Step 1: the header fields this loader relies on, checked before any data are
// read so that a bad header gets a message naming its field.
void check_header(const std::string& path, const nifti_1_header& h) {
  const bool magic_ok = std::memcmp(h.magic, "n+1", 4) == 0 || std::memcmp(h.magic, "ni1", 4) == 0;
  if (h.sizeof_hdr != 348 || !magic_ok)
    throw Error(unreadable(path, "no NIfTI-1 signature: sizeof_hdr " +
                                     std::to_string(h.sizeof_hdr) + ", magic not n+1/ni1"));
  const int ndim = h.dim[0];
  if (ndim < 3 || ndim > 7)
    throw Error(path + ": dim[0] = " + std::to_string(ndim) +
                " is not a 3-D volume (need 3, or 4..7 with dim[4..] = 1)");
  for (int a = 4; a <= ndim; ++a)
    if (h.dim[a] != 1)
      throw Error(path + ": dim[" + std::to_string(a) + "] = " + std::to_string(h.dim[a]) +
                  ": a series of volumes is not supported (need dim[" + std::to_string(a) +
                  "] = 1)");
  std::uint64_t voxels = 1;
  for (int a = 1; a <= 3; ++a) {
    // dim[] is a 16-bit signed field in NIfTI-1, so only the lower bound can fail.
    if (h.dim[a] < 1)
      throw Error(path + ": dim[" + std::to_string(a) + "] = " + std::to_string(h.dim[a]) +
                  " is not a valid size (must be >= 1)");
    voxels *= static_cast<std::uint64_t>(h.dim[a]);
  }
  if (voxels > kMaxLoadVoxels)
    throw Error(path + ": dim " + std::to_string(h.dim[1]) + "x" + std::to_string(h.dim[2]) + "x" +
                std::to_string(h.dim[3]) + " = " + std::to_string(voxels) +
                " voxels, more than the limit of 2^31");
  switch (h.datatype) {
    case DT_UINT8:
    case DT_INT8:
    case DT_UINT16:
    case DT_INT16:
    case DT_UINT32:
    case DT_INT32:
    case DT_FLOAT32:
    case DT_FLOAT64:
      break;
    default:
      throw Error(path + ": datatype " + std::to_string(h.datatype) + " (" +
                  nifti_datatype_string(h.datatype) +
                  ") is not supported (u8, i8, u16, i16, u32, i32, float32, float64 are)");
  }
  for (int a = 1; a <= 3; ++a)
    if (!std::isfinite(h.pixdim[a]))
      throw Error(path + ": pixdim[" + std::to_string(a) + "] = " + num(h.pixdim[a]) +
                  " is not a number");
  if (!std::isfinite(h.scl_slope))
    throw Error(path + ": scl_slope = " + num(h.scl_slope) + " is not a number");
  if (h.scl_slope != 0.0f && !std::isfinite(h.scl_inter))
    throw Error(path + ": scl_inter = " + num(h.scl_inter) + " is not a number");
  // Single-file data start after the 348-byte header and the 4-byte extension
  // flag; niftilib silently falls back to byte 348 for a smaller offset, which
  // shifts the whole volume by 4 bytes.
  if (std::memcmp(h.magic, "n+1", 4) == 0 &&
      (!std::isfinite(h.vox_offset) || h.vox_offset < 352.0f || h.vox_offset > 1e9f))
    throw Error(path + ": vox_offset = " + num(h.vox_offset) +
                " is not valid (single-file data start at byte 352 or later)");
}

// Step 2: the voxel data, exactly nvox values or an Error.
template <typename T>
std::vector<T> read_data(const std::string& path, const nifti_image& nim) {
  const std::size_t bytes = nim.nvox * sizeof(T);
  std::unique_ptr<znzptr, ZnzClose> file(znzopen(nim.iname, "rb", nifti_is_gzfile(nim.iname)));
  if (!file) throw Error(std::string(nim.iname) + ": cannot open the image data for reading");
  // znzseek returns 0 (plain file) or the new offset (gzip); -1 on failure.
  if (znzseek(file.get(), nim.iname_offset, SEEK_SET) < 0)
    throw Error(unreadable(
        path, "truncated: the data should start at byte " + std::to_string(nim.iname_offset)));
  // The header's size is only a claim: the buffer grows as data arrive (16 MiB
  // at a time), so a small file claiming 2^31 voxels is reported as truncated
  // instead of allocating gigabytes first (fuzz finding
  // tests/fuzz_regress/data/nifti/huge_dims_tiny_file.nii).
  constexpr std::size_t kChunk = std::size_t{16} << 20;  // a multiple of sizeof(T)
  std::vector<T> values;
  std::size_t got = 0;
  while (got < bytes) {
    const std::size_t want = std::min(kChunk, bytes - got);
    values.resize((got + want) / sizeof(T));
    const std::size_t n = znzread(reinterpret_cast<char*>(values.data()) + got, 1, want, file.get());
    got += std::min(n, want);
    if (n != want) break;
  }
  if (got != bytes)
    throw Error(unreadable(path, "truncated or corrupt data: " +
                                     (got > bytes ? std::string("a read error")
                                                  : std::to_string(got) + " of " +
                                                        std::to_string(bytes) + " data bytes")));
  if (nim.byteorder != nifti_short_order() && sizeof(T) > 1)
    nifti_swap_Nbytes(values.size(), static_cast<int>(sizeof(T)), values.data());
  return values;
}

std::string voxel_text(const Volume& v, std::size_t i) {
  const std::size_t nx = static_cast<std::size_t>(v.dims[0]);
  const std::size_t ny = static_cast<std::size_t>(v.dims[1]);
  return "voxel " + std::to_string(i) + " (x " + std::to_string(i % nx) + ", y " +
         std::to_string(i / nx % ny) + ", z " + std::to_string(i / (nx * ny)) + ")";
}

// Step 3a: integer data keep their values, shifted up by -min if min < 0.
// Physical = s * raw + i = s * stored + (i + s * min).
template <typename T>
void convert_integers(const std::string& path, const std::vector<T>& raw, double s, double i,
                      Volume& v) {
  std::int64_t lo = std::numeric_limits<std::int64_t>::max();
  std::int64_t hi = std::numeric_limits<std::int64_t>::min();
  for (T r : raw) {
    lo = std::min<std::int64_t>(lo, static_cast<std::int64_t>(r));
    hi = std::max<std::int64_t>(hi, static_cast<std::int64_t>(r));
  }
  const std::int64_t shift = std::min<std::int64_t>(lo, 0);
  if (hi - shift > kMaxStored16)
    throw Error(path + ": values span " + std::to_string(lo) + ".." + std::to_string(hi) +
                (shift < 0 ? " (" + std::to_string(hi - shift) + " after shifting to 0)" : "") +
                ", wider than 16 bits");
  v.data.resize(raw.size());
  for (std::size_t k = 0; k < raw.size(); ++k)
    v.data[k] = static_cast<std::uint16_t>(static_cast<std::int64_t>(raw[k]) - shift);
  v.slope = s;
  v.intercept = i + s * static_cast<double>(shift);
  v.bits = bits_for(static_cast<std::uint32_t>(hi - shift));
}

// Step 3b: float data are quantised to 16 bits over [min, max]:
// stored = round((raw - min) * 65535 / (max - min)), so
// physical = s * (min + stored * (max - min) / 65535) + i.
template <typename T>
void convert_floats(const std::string& path, const std::vector<T>& raw, double s, double i,
                    Volume& v) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < raw.size(); ++k) {
    const double r = static_cast<double>(raw[k]);
    if (!std::isfinite(r))
      throw Error(path + ": " + voxel_text(v, k) + " holds " + num(r) + ", not a finite value");
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  const double range = hi - lo;
  if (!std::isfinite(range))
    throw Error(path + ": values span " + num(lo) + ".." + num(hi) + ", too wide to quantise");
  v.data.resize(raw.size());
  if (range == 0.0) {
    std::fill(v.data.begin(), v.data.end(), std::uint16_t{0});
    v.slope = s;
    v.intercept = s * lo + i;
    v.bits = 1;
    return;
  }
  const double scale = static_cast<double>(kMaxStored16) / range;
  for (std::size_t k = 0; k < raw.size(); ++k) {
    const double q = std::round((static_cast<double>(raw[k]) - lo) * scale);
    v.data[k] = static_cast<std::uint16_t>(std::clamp(q, 0.0, static_cast<double>(kMaxStored16)));
  }
  v.slope = s * (range / static_cast<double>(kMaxStored16));
  v.intercept = s * lo + i;
  v.bits = 16;
}

template <typename T>
void convert(const std::string& path, const nifti_image& nim, double s, double i, Volume& v) {
  const std::vector<T> raw = read_data<T>(path, nim);
  if constexpr (std::is_integral_v<T>)
    convert_integers(path, raw, s, i, v);
  else
    convert_floats(path, raw, s, i, v);
}

void quiet_niftilib() {
  static std::once_flag once;
  std::call_once(once, [] { nifti_set_debug_level(0); });
}

}  // namespace

Volume load_nifti(const std::string& path) {
  quiet_niftilib();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": no such file");

  // Step 1: the raw header (native byte order), checked field by field.
  int swapped = 0;
  std::unique_ptr<nifti_1_header, HeaderFree> header(nifti_read_header(path.c_str(), &swapped, 0));
  if (!header) throw Error(unreadable(path, "truncated or corrupt header"));
  check_header(path, *header);

  // niftilib's own parse: data file name, offset, byte order and its checks.
  std::unique_ptr<nifti_image, ImageFree> nim(nifti_image_read(path.c_str(), 0));
  if (!nim) throw Error(unreadable(path, "truncated or corrupt header/data"));
  if (nim->nifti_type == NIFTI_FTYPE_ASCII)
    throw Error(path + ": ASCII NIfTI files are not supported");
  if (nim->nvox != static_cast<std::size_t>(header->dim[1]) *
                       static_cast<std::size_t>(header->dim[2]) *
                       static_cast<std::size_t>(header->dim[3]))
    throw Error(unreadable(path, "niftilib counts " + std::to_string(nim->nvox) + " voxels"));

  Volume v;
  v.source = path;
  v.dims = {header->dim[1], header->dim[2], header->dim[3]};
  const double unit = mm_per_unit(header->xyzt_units);
  for (int a = 0; a < 3; ++a) {
    const double d = std::abs(static_cast<double>(header->pixdim[a + 1]));
    v.spacing[a] = (d == 0.0 ? 1.0 : d) * unit;
  }

  // NIfTI-1: scl_slope = 0 means the values are not scaled (scl_inter ignored).
  const bool scaled = header->scl_slope != 0.0f;
  const double s = scaled ? static_cast<double>(header->scl_slope) : 1.0;
  const double i = scaled ? static_cast<double>(header->scl_inter) : 0.0;

  // Steps 2 and 3: read and convert.
  switch (header->datatype) {
    case DT_UINT8:
      convert<std::uint8_t>(path, *nim, s, i, v);
      break;
    case DT_INT8:
      convert<std::int8_t>(path, *nim, s, i, v);
      break;
    case DT_UINT16:
      convert<std::uint16_t>(path, *nim, s, i, v);
      break;
    case DT_INT16:
      convert<std::int16_t>(path, *nim, s, i, v);
      break;
    case DT_UINT32:
      convert<std::uint32_t>(path, *nim, s, i, v);
      break;
    case DT_INT32:
      convert<std::int32_t>(path, *nim, s, i, v);
      break;
    case DT_FLOAT32:
      convert<float>(path, *nim, s, i, v);
      break;
    case DT_FLOAT64:
      convert<double>(path, *nim, s, i, v);
      break;
    default:
      throw Error(path + ": datatype " + std::to_string(header->datatype) + " unsupported");
  }
  validate(v, path);
  return v;
}

}  // namespace voxcast::ref
