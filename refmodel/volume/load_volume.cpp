// volume.source resolution: phantoms, NIfTI files, DICOM folders, raw files.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <string>
#include <system_error>

#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::ref {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPhantomPrefix = "phantom:";
constexpr int kDefaultPhantomSize = 128;  // as docs/scenes.md states

// A whole number from a phantom parameter, or an Error naming it.
int parse_phantom_int(const std::string& source, const std::string& key, const std::string& text) {
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, err] = std::from_chars(text.data(), end, value);
  if (text.empty() || err != std::errc{} || ptr != end)
    throw Error("volume.source \"" + source + "\": " + key + " \"" + text +
                "\" is not a whole number");
  return value;
}

// "phantom:NAME" with optional parameters "?size=N&aa=N" in any order.
Volume load_phantom(const std::string& source) {
  const std::string spec = source.substr(std::char_traits<char>::length(kPhantomPrefix));
  const std::size_t q = spec.find('?');
  const std::string name = spec.substr(0, q);
  if (name.empty())
    throw Error("volume.source \"" + source + "\": no phantom name after \"phantom:\"");
  int size = kDefaultPhantomSize;
  int aa = 1;
  std::string query = q == std::string::npos ? "" : spec.substr(q + 1);
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string param = query.substr(0, amp);
    query = amp == std::string::npos ? "" : query.substr(amp + 1);
    const std::size_t eq = param.find('=');
    const std::string key = param.substr(0, eq);
    const std::string text = eq == std::string::npos ? "" : param.substr(eq + 1);
    if (key == "size")
      size = parse_phantom_int(source, key, text);
    else if (key == "aa")
      aa = parse_phantom_int(source, key, text);
    else
      throw Error("volume.source \"" + source + "\": unknown phantom parameter \"" + param +
                  "\" (size=N, aa=N)");
  }
  return make_phantom(name, size, aa);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool is_nifti_name(const fs::path& p) {
  std::string name = p.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ends_with(name, ".nii") || ends_with(name, ".nii.gz") || ends_with(name, ".hdr") ||
         ends_with(name, ".hdr.gz");
}

}  // namespace

Volume load_volume(const std::string& source, const std::string& base_dir, const RawSpec* raw,
                   const DicomOptions& dicom) {
  if (source.empty()) throw Error("volume.source is empty");
  if (source.starts_with(kPhantomPrefix)) return load_phantom(source);

  fs::path path(source);
  if (path.is_relative() && !base_dir.empty()) path = fs::path(base_dir) / path;
  const std::string shown = path.lexically_normal().string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status))
    throw Error(shown + ": no such file or folder (volume.source = \"" + source + "\")");
  if (fs::is_directory(status)) return load_dicom_series(shown, dicom);
  if (is_nifti_name(path)) return load_nifti(shown);
  if (raw == nullptr)
    throw Error(shown +
                " is not a NIfTI file or DICOM folder; give volume.dims and volume.type "
                "to read it as raw");
  return load_raw(shown, *raw);
}

}  // namespace voxcast::ref
