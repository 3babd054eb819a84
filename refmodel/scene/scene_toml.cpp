#include "refmodel/scene/scene_toml.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <type_traits>

#include <toml++/toml.h>

#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/scene/rtl_keys.hpp"

namespace voxcast::ref {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

namespace {

std::vector<std::string> precision_keys() {
  std::vector<std::string> keys = {"profile"};
  for (const ProfileField& f : profile_fields()) keys.push_back(f.name);
  return keys;
}

// --- Schema: the keys each table accepts ------------------------------------
// Unknown keys are errors (a typo must not silently fall back to a default);
// docs/scenes.md documents each of these (tests/refmodel/test_scene.cpp checks).
const std::map<std::string, std::vector<std::string>>& schema() {
  static const std::map<std::string, std::vector<std::string>> s = {
      {"", {"volume", "classification", "camera", "render", "lights", "precision", "rtl",
            "heidelberg"}},
      {"rtl", rtl_key_names()},
      {"precision", precision_keys()},
      {"volume", {"source", "dims", "type", "spacing", "endian", "crop", "gradient", "resample"}},
      {"volume.crop", {"lo", "hi"}},
      {"classification", {"interpolation", "points", "ka", "kd", "ks", "shininess"}},
      {"classification.points[]", {"value", "color", "alpha"}},
      {"camera",
       {"projection", "eye", "center", "up", "fov_deg", "height", "stereo_deg", "path", "dolly"}},
      {"camera.path[]", {"eye", "center", "up"}},
      {"render", {"width", "height", "mode", "oversampling", "ert_threshold", "background",
                  "frames", "threads", "algorithm", "space_leaping", "leap_block", "jitter",
                  "partial_segments", "classification"}},
      {"lights[]", {"type", "direction", "intensity"}},
      // VIRIM (docs/heidelberg.md).
      {"heidelberg", {"diffuse_0", "diffuse_45", "specular_45", "luminosity", "light",
                      "shininess", "background_threshold", "interpolation", "gaussian_sigma",
                      "weight_bits", "gradient", "axis", "angle_deg", "translation", "zoom",
                      "perspective", "depth", "stereo_deg", "modules", "rotator_mhz",
                      "dsp_mhz", "bus_mhz"}},
  };
  return s;
}

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// Where a key came from, for messages: "scene.toml:12" or "--set render.width=0".
struct Origins {
  std::string file;
  std::map<std::string, std::string> overridden;  // dotted key -> "--set k=v"

  std::string where(const std::string& key, const toml::node* node) const {
    for (const auto& [k, o] : overridden)
      if (key == k || key.rfind(k + ".", 0) == 0 || key.rfind(k + "[", 0) == 0) return o;
    if (node && node->source().begin.line > 0)
      return file + ":" + std::to_string(node->source().begin.line);
    // A table no line of the file holds was made by an override of a key in it
    // (--set bogus.key=1 makes the table "bogus").
    for (const auto& [k, o] : overridden)
      if (k.rfind(key + ".", 0) == 0 || k.rfind(key + "[", 0) == 0) return o;
    return file;
  }
};

// Reads one TOML table against its schema entry. Every accessor checks the
// type and range and names the key; finish() rejects keys it does not know.
class TableReader {
 public:
  TableReader(const toml::table* table, std::string path, std::string schema_key,
              const Origins& origins)
      : table_(table), path_(std::move(path)), schema_key_(std::move(schema_key)),
        origins_(origins) {
    reject_unknown_keys();
  }

  bool has(const std::string& key) const { return table_ && table_->contains(key); }
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    fail_at(key, node(key), what);
  }
  // `n` locates the error (an array element has no key of its own to look up).
  [[noreturn]] void fail_at(const std::string& key, const toml::node* n,
                            const std::string& what) const {
    throw Error(origins_.where(key_path(key), n) + ": " + key_path(key) + " " + what);
  }

  double number(const std::string& key, double def, double lo, double hi,
                bool lo_open = false, bool hi_open = false) const {
    const toml::node* n = node(key);
    if (!n) return def;
    const double v = as_number(key, *n);
    check_range(key, n, v, lo, hi, lo_open, hi_open);
    return v;
  }

  bool boolean(const std::string& key, bool def) const {
    const toml::node* n = node(key);
    if (!n) return def;
    const auto v = n->value_exact<bool>();
    if (!v) fail(key, "must be true or false, not " + type_name(*n));
    return *v;
  }

  int integer(const std::string& key, int def, int lo, int hi) const {
    const toml::node* n = node(key);
    if (!n) return def;
    const auto v = n->value_exact<int64_t>();
    if (!v) fail(key, "must be an integer, not " + type_name(*n));
    if (*v < lo || *v > hi)
      fail(key, "= " + std::to_string(*v) + " is outside [" + std::to_string(lo) + ", " +
                    std::to_string(hi) + "]");
    return static_cast<int>(*v);
  }

  std::string string(const std::string& key, const std::string& def,
                     const std::vector<std::string>& allowed = {}) const {
    const toml::node* n = node(key);
    if (!n) return def;
    const auto v = n->value_exact<std::string>();
    if (!v) fail(key, "must be a string, not " + type_name(*n));
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), *v) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
      fail(key, "= \"" + *v + "\" is not one of " + list);
    }
    return *v;
  }

  glm::dvec3 vec3(const std::string& key, glm::dvec3 def, double lo, double hi) const {
    const toml::node* n = node(key);
    if (!n) return def;
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3) fail(key, "must be an array of 3 numbers");
    glm::dvec3 v;
    for (std::size_t i = 0; i < 3; ++i) {
      const toml::node& e = *a->get(i);
      const std::string ek = key + "[" + std::to_string(i) + "]";
      v[static_cast<int>(i)] = as_number(ek, e);
      check_range(ek, &e, v[static_cast<int>(i)], lo, hi, false, false);
    }
    return v;
  }

  std::array<int, 3> int3(const std::string& key, int lo, int hi) const {
    const toml::node* n = node(key);
    const toml::array* a = n ? n->as_array() : nullptr;
    if (!a || a->size() != 3) fail(key, "must be an array of 3 integers");
    std::array<int, 3> v{};
    for (std::size_t i = 0; i < 3; ++i) {
      const toml::node* en = a->get(i);
      const auto e = en->value_exact<int64_t>();
      const std::string ek = key + "[" + std::to_string(i) + "]";
      if (!e) fail_at(ek, en, "must be an integer");
      if (*e < lo || *e > hi)
        fail_at(ek, en, "= " + std::to_string(*e) + " is outside [" + std::to_string(lo) + ", " +
                            std::to_string(hi) + "]");
      v[i] = static_cast<int>(*e);
    }
    return v;
  }

  TableReader table(const std::string& key) const {
    const toml::node* n = node(key);
    if (n && !n->is_table()) fail(key, "must be a table");
    return TableReader(n ? n->as_table() : nullptr, key_path(key), schema_child(key), origins_);
  }

  // Array of tables (TOML [[x]] or [{...}, {...}]).
  std::vector<TableReader> tables(const std::string& key) const {
    std::vector<TableReader> out;
    const toml::node* n = node(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a) fail(key, "must be an array of tables");
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::table* t = a->get(i)->as_table();
      const std::string item = key + "[" + std::to_string(i) + "]";
      if (!t) fail(item, "must be a table");
      out.emplace_back(t, key_path(item), schema_child(key) + "[]", origins_);
    }
    return out;
  }

 private:
  const toml::node* node(const std::string& key) const {
    return table_ ? table_->get(key) : nullptr;
  }
  std::string schema_child(const std::string& key) const {
    return schema_key_.empty() ? key : schema_key_ + "." + key;
  }
  static std::string type_name(const toml::node& n) {
    std::ostringstream os;
    os << n.type();
    return os.str();
  }
  double as_number(const std::string& key, const toml::node& n) const {
    double v;
    if (auto i = n.value_exact<int64_t>())
      v = static_cast<double>(*i);
    else if (auto d = n.value_exact<double>())
      v = *d;
    else
      fail_at(key, &n, "must be a number, not " + type_name(n));
    if (!std::isfinite(v)) fail_at(key, &n, "= " + fmt(v) + " is not a finite number");
    return v;
  }
  void check_range(const std::string& key, const toml::node* n, double v, double lo, double hi,
                   bool lo_open, bool hi_open) const {
    const bool bad = lo_open ? !(v > lo) : !(v >= lo);
    const bool bad_hi = hi_open ? !(v < hi) : !(v <= hi);
    if (bad || bad_hi)
      fail_at(key, n, "= " + fmt(v) + " is outside " + (lo_open ? "(" : "[") + fmt(lo) + ", " +
                    fmt(hi) + (hi_open ? ")" : "]"));
  }
  void reject_unknown_keys() const {
    if (!table_) return;
    const auto& allowed = schema().at(schema_key_);
    for (const auto& [k, n] : *table_) {
      const std::string key(k.str());
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string hint;
      std::size_t best = 3;
      for (const auto& a : allowed)
        if (const std::size_t d = edit_distance(key, a); d < best) best = d, hint = a;
      throw Error(origins_.where(key_path(key), &n) + ": unknown key " + key_path(key) +
                  (hint.empty() ? "" : " (did you mean " + key_path(hint) + "?)"));
    }
  }

  const toml::table* table_;
  std::string path_;
  std::string schema_key_;
  const Origins& origins_;
};

// --- --set overrides ------------------------------------------------------------

// Splits "lights[0].intensity" / "lights.0.intensity" into its parts.
std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : key) {
    if (c == '.' || c == '[' || c == ']') {
      if (!cur.empty()) parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) parts.push_back(cur);
  return parts;
}

bool is_index(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string canonical_key(const std::vector<std::string>& parts) {
  std::string k;
  for (const auto& p : parts) k += is_index(p) ? "[" + p + "]" : (k.empty() ? "" : ".") + p;
  return k;
}

toml::node_view<toml::node> value_of_override(const std::string& text, toml::table& holder) {
  try {
    holder = toml::parse("v = " + text);
  } catch (const toml::parse_error&) {
    holder = toml::table{{"v", text}};  // a bare word: take it as a string
  }
  return holder["v"];
}

void apply_override(toml::table& root, const std::string& assignment, Origins& origins) {
  const auto eq = assignment.find('=');
  const std::string where = "--set " + assignment;
  if (eq == std::string::npos || eq == 0)
    throw Error(where + ": expected key=value (e.g. render.oversampling=4)");
  const std::vector<std::string> parts = split_key(assignment.substr(0, eq));
  if (parts.empty()) throw Error(where + ": empty key");
  toml::table holder;
  toml::node_view<toml::node> value = value_of_override(assignment.substr(eq + 1), holder);

  // Walk to the parent of the last part, creating tables/arrays as needed.
  toml::node* cur = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& p = parts[i];
    const bool next_is_index = is_index(parts[i + 1]);
    toml::node* child = nullptr;
    if (auto* t = cur->as_table()) {
      if (!t->contains(p)) {
        if (next_is_index)
          t->insert(p, toml::array{});
        else
          t->insert(p, toml::table{});
      }
      child = t->get(p);
    } else if (auto* a = cur->as_array()) {
      if (!is_index(p)) throw Error(where + ": expected an array index before " + p);
      const std::size_t idx = std::stoul(p);
      if (idx > a->size()) throw Error(where + ": index " + p + " is past the end of the array");
      if (idx == a->size()) a->push_back(toml::table{});
      child = a->get(idx);
    }
    if (!child || (!child->is_table() && !child->is_array()))
      throw Error(where + ": " + p + " holds a value, not a table or array");
    cur = child;
  }
  const std::string& last = parts.back();
  if (auto* t = cur->as_table()) {
    t->insert_or_assign(last, *value.node());
  } else if (auto* a = cur->as_array()) {
    if (!is_index(last)) throw Error(where + ": expected an array index, got " + last);
    const std::size_t idx = std::stoul(last);
    if (idx > a->size()) throw Error(where + ": index " + last + " is past the end of the array");
    if (idx == a->size())
      a->push_back(*value.node());
    else
      a->replace(a->begin() + static_cast<long>(idx), *value.node());
  } else {
    throw Error(where + ": the parent of " + last + " is not a table");
  }
  origins.overridden[canonical_key(parts)] = where;
}

// --- Sections ------------------------------------------------------------------

void read_volume(const TableReader& r, VolumeDesc& v) {
  v.source = r.string("source", v.source);
  if (v.source.empty()) r.fail("source", "is empty");
  v.gradient = parse_gradient_operator(r.string("gradient", "central", {"central", "sobel"}));
  v.resample = r.boolean("resample", v.resample);
  if (r.has("dims") || r.has("type")) {
    RawSpec raw;
    if (!r.has("dims")) r.fail("dims", "is required when volume.type is given (raw files)");
    raw.dims = r.int3("dims", 1, 65535);
    const std::string type = r.string("type", "u8", {"u8", "u16", "i16"});
    raw.type = type == "u8" ? RawType::U8 : type == "u16" ? RawType::U16 : RawType::I16;
    raw.spacing = r.vec3("spacing", raw.spacing, 1e-6, 1e6);
    if (raw.spacing.x <= 0 || raw.spacing.y <= 0 || raw.spacing.z <= 0)
      r.fail("spacing", "must be > 0 along every axis");
    raw.big_endian = r.string("endian", "little", {"little", "big"}) == "big";
    v.raw = raw;
  } else {
    for (const char* k : {"spacing", "endian"})
      if (r.has(k)) r.fail(k, "applies to raw files only: give volume.dims and volume.type too");
  }
  if (r.has("crop")) {
    const TableReader c = r.table("crop");
    Crop crop;
    crop.lo = c.int3("lo", 0, 65535);
    crop.hi = c.int3("hi", 0, 65535);
    for (int a = 0; a < 3; ++a)
      if (crop.lo[a] > crop.hi[a]) c.fail("lo", "must not exceed volume.crop.hi on any axis");
    v.crop = crop;
  }
}

void read_classification(const TableReader& r, Scene& s) {
  s.tf_interpolation = parse_tf_interpolation(r.string("interpolation", "ramp", {"ramp", "binary"}));
  s.material.ka = r.number("ka", s.material.ka, 0.0, 1.0);
  s.material.kd = r.number("kd", s.material.kd, 0.0, 1.0);
  s.material.ks = r.number("ks", s.material.ks, 0.0, 1.0);
  s.material.shininess = r.number("shininess", s.material.shininess, 1.0, 256.0);
  if (!r.has("points")) r.fail("points", "is required: at least one control point");
  s.tf_points.clear();
  for (const TableReader& p : r.tables("points")) {
    TfPoint pt;
    if (!p.has("value")) p.fail("value", "is required");
    pt.value = p.number("value", 0.0, -1e9, 1e9);
    pt.color = p.vec3("color", pt.color, 0.0, 1.0);
    pt.alpha = p.number("alpha", 0.0, 0.0, 1.0);
    if (!s.tf_points.empty() && pt.value < s.tf_points.back().value)
      p.fail("value", "= " + fmt(pt.value) + " is below the previous point's " +
                          fmt(s.tf_points.back().value) + ": points must be sorted by value");
    s.tf_points.push_back(pt);
  }
  if (s.tf_points.empty()) r.fail("points", "is empty: at least one control point is needed");
}

CameraPose read_pose(const TableReader& r, const CameraPose& def, bool required) {
  CameraPose p = def;
  for (const char* k : {"eye", "center"})
    if (required && !r.has(k)) r.fail(k, "is required");
  p.eye = r.vec3("eye", p.eye, -1e6, 1e6);
  p.center = r.vec3("center", p.center, -1e6, 1e6);
  p.up = r.vec3("up", p.up, -1e6, 1e6);
  const glm::dvec3 f = p.center - p.eye;
  if (f.x == 0 && f.y == 0 && f.z == 0) r.fail("center", "equals the eye: no view direction");
  if (p.up.x == 0 && p.up.y == 0 && p.up.z == 0) r.fail("up", "is the zero vector");
  const glm::dvec3 c{f.y * p.up.z - f.z * p.up.y, f.z * p.up.x - f.x * p.up.z,
                     f.x * p.up.y - f.y * p.up.x};
  const double fl = std::sqrt(f.x * f.x + f.y * f.y + f.z * f.z);
  const double ul = std::sqrt(p.up.x * p.up.x + p.up.y * p.up.y + p.up.z * p.up.z);
  if (std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z) <= 1e-9 * fl * ul)
    r.fail("up", "is parallel to the view direction (center - eye)");
  return p;
}

void read_camera(const TableReader& r, CameraDesc& c) {
  c.projection = r.string("projection", "perspective", {"perspective", "parallel"}) == "parallel"
                     ? Projection::Parallel
                     : Projection::Perspective;
  c.pose = read_pose(r, c.pose, true);
  c.fov_deg = r.number("fov_deg", c.fov_deg, 0.0, 180.0, true, true);
  c.height = r.number("height", c.height, 0.0, 1e6, true, false);
  c.stereo_deg = r.number("stereo_deg", c.stereo_deg, 0.0, 30.0);
  c.path.clear();
  for (const TableReader& k : r.tables("path")) c.path.push_back(read_pose(k, c.pose, false));
  // camera.dolly = f: the eye f times as far from the centre, the field of view
  // narrowed so the framing at the centre stays (a dolly zoom; a parallel view
  // keeps its height). Applied here, so the scene holds the moved camera and
  // writes it back without the key. For sweeps over the eye's distance.
  const double dolly = r.number("dolly", 1.0, 1e-3, 1e3);
  if (dolly != 1.0) {
    c.pose.eye = c.pose.center + dolly * (c.pose.eye - c.pose.center);
    const double half = std::tan(c.fov_deg * std::numbers::pi / 360.0) / dolly;
    c.fov_deg = 360.0 / std::numbers::pi * std::atan(half);
  }
}

void read_render(const TableReader& r, RenderDesc& d) {
  d.width = r.integer("width", d.width, 1, 8192);
  d.height = r.integer("height", d.height, 1, 8192);
  const std::string mode = r.string("mode", "shaded", {"shaded", "unshaded", "mip"});
  d.mode = mode == "shaded" ? RenderMode::Shaded : mode == "unshaded" ? RenderMode::Unshaded
                                                                      : RenderMode::Mip;
  d.oversampling = r.number("oversampling", d.oversampling, 0.25, 16.0);
  d.ert_threshold = r.number("ert_threshold", d.ert_threshold, 0.0, 1.0, true, false);
  d.background = r.vec3("background", d.background, 0.0, 1.0);
  d.frames = r.integer("frames", d.frames, 1, 100000);
  d.threads = r.integer("threads", d.threads, 0, 1024);
  d.space_leaping = r.boolean("space_leaping", d.space_leaping);
  d.leap_block = r.integer("leap_block", d.leap_block, 4, 64);
  if ((d.leap_block & (d.leap_block - 1)) != 0)
    r.fail("leap_block", "= " + std::to_string(d.leap_block) + " must be a power of two (4..64)");
  d.jitter = r.boolean("jitter", d.jitter);
  d.partial_segments = r.boolean("partial_segments", d.partial_segments);
  d.classification =
      r.string("classification", ref::to_string(d.classification), {"post", "preintegrated"}) ==
              "preintegrated"
          ? ClassificationMode::Preintegrated
          : ClassificationMode::Post;
  if (d.preintegrated()) {
    // §4a: a segment table classifies whole steps between two samples.
    if (d.space_leaping)
      r.fail("space_leaping", "= true cannot be combined with classification = "
                              "\"preintegrated\": a leap drops the sample in front of the "
                              "next segment (docs/pipeline.md §4a)");
    if (r.has("partial_segments") && d.partial_segments)
      r.fail("partial_segments", "= true cannot be combined with classification = "
                                 "\"preintegrated\": the segment table holds whole steps "
                                 "(docs/pipeline.md §4a)");
    d.partial_segments = false;
  }
}

void read_lights(const TableReader& root, std::vector<Light>& lights) {
  lights.clear();
  for (const TableReader& r : root.tables("lights")) {
    Light l;
    l.type = r.string("type", "headlight", {"directional", "headlight"}) == "directional"
                 ? LightType::Directional
                 : LightType::Headlight;
    if (l.type == LightType::Directional) {
      if (!r.has("direction")) r.fail("direction", "is required for a directional light");
      l.direction = r.vec3("direction", l.direction, -1e6, 1e6);
      if (l.direction.x == 0 && l.direction.y == 0 && l.direction.z == 0)
        r.fail("direction", "is the zero vector");
    } else if (r.has("direction")) {
      r.fail("direction", "does not apply to a headlight (it shines along the view direction)");
    }
    l.intensity = r.number("intensity", l.intensity, 0.0, 100.0);
    lights.push_back(l);
  }
}

// --- [heidelberg] and render.algorithm (VIRIM, docs/heidelberg.md) ---
void read_heidelberg(const TableReader& r, HeidelbergDesc& h) {
  h.diffuse_0 = r.number("diffuse_0", h.diffuse_0, 0.0, 1.0);
  h.diffuse_45 = r.number("diffuse_45", h.diffuse_45, 0.0, 1.0);
  h.specular_45 = r.number("specular_45", h.specular_45, 0.0, 1.0);
  h.luminosity = r.number("luminosity", h.luminosity, 0.0, 1.0);
  h.light = r.number("light", h.light, 0.0, 1.0, true, false);
  h.shininess = r.integer("shininess", h.shininess, 1, 127);
  h.background_threshold = r.number("background_threshold", h.background_threshold, 0.0, 1.0);
  h.interpolation = r.string("interpolation", "gaussian", {"gaussian", "trilinear"}) == "trilinear"
                        ? HeidelbergInterpolation::Trilinear
                        : HeidelbergInterpolation::Gaussian;
  h.gaussian_sigma = r.number("gaussian_sigma", h.gaussian_sigma, 0.1, 4.0);
  h.weight_bits = r.integer("weight_bits", h.weight_bits, 1, 8);
  h.gradient = r.string("gradient", "2d", {"2d", "3d"}) == "3d" ? HeidelbergGradient::Sobel3D
                                                                : HeidelbergGradient::Sobel2D;
  h.axis = r.vec3("axis", h.axis, -1e6, 1e6);
  if (h.axis.x == 0 && h.axis.y == 0 && h.axis.z == 0) r.fail("axis", "is the zero vector");
  h.angle_deg = r.number("angle_deg", h.angle_deg, -3600.0, 3600.0);
  h.translation = r.vec3("translation", h.translation, -1e4, 1e4);
  h.zoom = r.number("zoom", h.zoom, 1.0 / 16.0, 16.0);
  h.depth = r.integer("depth", h.depth, 0, 4096);
  h.perspective = r.number("perspective", h.perspective, 0.0, 1e6);
  if (h.perspective > 0.0 && h.depth > 0 && h.perspective <= 0.5 * h.depth)
    r.fail("perspective", "= " + fmt(h.perspective) +
                              " must exceed half of heidelberg.depth (the eye is outside the cube)");
  h.stereo_deg = r.number("stereo_deg", h.stereo_deg, 0.0, 30.0);
  h.modules = r.integer("modules", h.modules, 1, 64);
  h.rotator_mhz = r.number("rotator_mhz", h.rotator_mhz, 1.0, 1000.0);
  h.dsp_mhz = r.number("dsp_mhz", h.dsp_mhz, 1.0, 1000.0);
  h.bus_mhz = r.number("bus_mhz", h.bus_mhz, 1.0, 1000.0);
}

void read_precision(const TableReader& r, Scene& s) {
  std::vector<std::string> presets = preset_names();
  const std::string name = r.string("profile", "balanced", presets);
  s.precision = preset_profile(name);
  s.precision_name = name;
  for (const ProfileField& f : profile_fields()) {
    if (!r.has(f.name)) continue;
    s.precision.*f.member = r.integer(f.name, s.precision.*f.member, f.min, f.max);
    s.precision_name += std::string(s.precision_name == name ? "+" : ",") + f.name + "=" +
                        std::to_string(s.precision.*f.member);
  }
}

bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

void read_rtl(const TableReader& r, const std::string& base_dir, RtlDesc& d) {
  d.board = r.string("board", d.board);
  if (d.board.empty()) r.fail("board", "must name a shipped board or a .toml file");
  // A board file, like a volume file, is relative to the scene's folder.
  if (d.board.size() > 5 && d.board.compare(d.board.size() - 5, 5, ".toml") == 0 &&
      std::filesystem::path(d.board).is_relative())
    d.board = (std::filesystem::path(base_dir) / d.board).lexically_normal().string();
  d.scheduler = r.string("scheduler", d.scheduler, rtl_choices("scheduler"));
  d.reorder_window = r.integer("reorder_window", d.reorder_window, 1, 64);
  d.starvation_limit = r.integer("starvation_limit", d.starvation_limit, 0, 1 << 20);
  d.refresh = r.string("refresh", d.refresh, rtl_choices("refresh"));
  // (2 + postpone) * tREFI must stay below tRAS(max) (sdram/refresh.hpp).
  d.refresh_postpone = r.integer("refresh_postpone", d.refresh_postpone, 0, 5);
  d.sdram = r.string("sdram", d.sdram, rtl_choices("sdram"));
  d.layout = r.string("layout", d.layout, rtl_choices("layout"));
  if (r.has("brick")) {
    d.brick = r.int3("brick", 1, 1024);
    for (int v : d.brick)
      if (!is_power_of_two(v)) r.fail("brick", "edges must be powers of two");
  }
  d.traversal = r.string("traversal", d.traversal, rtl_choices("traversal"));
  d.tile = r.integer("tile", d.tile, 1, 8192);
  d.ray_slots = r.integer("ray_slots", d.ray_slots, 1, 1024);
  d.issue = r.string("issue", d.issue, rtl_choices("issue"));
  d.issue_burst = r.integer("issue_burst", d.issue_burst, 0, 1 << 20);
  d.issue_bypass_limit = r.integer("issue_bypass_limit", d.issue_bypass_limit, 0, 1 << 20);
  if (d.issue == "row-hit" && d.issue_burst != 0)
    r.fail("issue_burst", "= " + std::to_string(d.issue_burst) +
                              " applies to rtl.issue = \"oldest\" only (row-hit picks a ray every sample)");
  d.sample_buffer = r.integer("sample_buffer", d.sample_buffer, 1, 4096);
  d.queue_depth = r.integer("queue_depth", d.queue_depth, 1, 64);
  d.return_depth = r.integer("return_depth", d.return_depth, 1, 64);
  d.auto_precharge = r.boolean("auto_precharge", d.auto_precharge);
  d.pipelines = r.integer("pipelines", d.pipelines, 1, 64);
  if (d.reorder_window > d.queue_depth)
    r.fail("reorder_window", "= " + std::to_string(d.reorder_window) +
                                 " exceeds rtl.queue_depth = " + std::to_string(d.queue_depth) +
                                 " (the scheduler sees only the queue)");
}

}  // namespace

const std::vector<std::string>& rtl_choices(const std::string& key) {
  static const std::map<std::string, std::vector<std::string>> choices = {
      {"scheduler", {"in-order", "fr-fcfs", "lookahead"}},
      {"refresh", {"eager"}},
      {"issue", {"oldest", "row-hit"}},
      {"sdram", {"board", "pc100-cl2", "pc100-cl3"}},
      {"layout", {"linear", "bricked", "bricked-swizzled", "morton"}},
      {"traversal", {"scanline", "tiles"}},
  };
  static const std::vector<std::string> none;
  const auto it = choices.find(key);
  return it == choices.end() ? none : it->second;
}

Scene parse_scene(const std::string& toml_text, const std::string& origin,
                  const std::string& base_dir, const Overrides& overrides) {
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    throw Error(origin + ":" + std::to_string(e.source().begin.line) + ": " +
                std::string(e.description()));
  }
  Origins origins{origin, {}};
  for (const std::string& o : overrides) apply_override(root, o, origins);

  Scene s;
  s.origin = origin;
  s.base_dir = base_dir;
  const TableReader top(&root, "", "", origins);
  if (!top.has("volume")) top.fail("volume", "table is required (volume.source)");
  // VIRIM: a Heidelberg scene's view is the rotator's ([heidelberg]); the camera is optional.
  s.algorithm = top.table("render").string("algorithm", "raycast", {"raycast", "heidelberg"}) ==
                        "heidelberg"
                    ? Algorithm::Heidelberg
                    : Algorithm::Raycast;
  if (top.has("heidelberg") && s.algorithm != Algorithm::Heidelberg)
    top.fail("heidelberg", "applies only with render.algorithm = \"heidelberg\"");
  read_heidelberg(top.table("heidelberg"), s.heidelberg);
  if (!top.has("camera") && s.algorithm == Algorithm::Raycast)
    top.fail("camera", "table is required (camera.eye, camera.center)");
  if (!top.has("classification")) top.fail("classification", "table is required");
  read_volume(top.table("volume"), s.volume);
  read_classification(top.table("classification"), s);
  if (top.has("camera")) read_camera(top.table("camera"), s.camera);
  read_render(top.table("render"), s.render);
  if (s.render.preintegrated() && s.algorithm == Algorithm::Heidelberg)
    top.table("render").fail("classification",
                             "= \"preintegrated\" applies only to the ray caster (VIRIM "
                             "composites whole slices)");
  read_lights(top, s.lights);
  read_precision(top.table("precision"), s);
  read_rtl(top.table("rtl"), s.base_dir, s.rtl);
  if (!top.has("lights")) s.lights = {Light{}};  // one headlight of intensity 1
  return s;
}

Scene load_scene_file(const std::string& path, const Overrides& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open scene file");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_scene(text.str(), path, dir.empty() ? "." : dir, overrides);
}

Scene default_scene(const Overrides& overrides) {
  return parse_scene(default_scene_text(), "default scene", ".", overrides);
}

namespace {
toml::array to_array(const glm::dvec3& v) { return toml::array{v.x, v.y, v.z}; }
toml::array to_array(const std::array<int, 3>& v) { return toml::array{v[0], v[1], v[2]}; }
toml::table pose_table(const CameraPose& p) {
  return toml::table{{"eye", to_array(p.eye)}, {"center", to_array(p.center)},
                     {"up", to_array(p.up)}};
}
}  // namespace

// VIRIM: render.algorithm and [heidelberg]; a Heidelberg scene's camera is not
// written when it was not given (its default pose is not a valid view).
static void heidelberg_to_toml(const Scene& s, toml::table& root) {
  const HeidelbergDesc& h = s.heidelberg;
  root["render"].as_table()->insert_or_assign("algorithm", "heidelberg");
  if (s.camera.pose.eye == s.camera.pose.center) root.erase("camera");
  root.insert_or_assign(
      "heidelberg",
      toml::table{{"diffuse_0", h.diffuse_0}, {"diffuse_45", h.diffuse_45},
                  {"specular_45", h.specular_45}, {"luminosity", h.luminosity},
                  {"light", h.light}, {"shininess", h.shininess},
                  {"background_threshold", h.background_threshold},
                  {"interpolation", h.interpolation == HeidelbergInterpolation::Trilinear
                                        ? "trilinear" : "gaussian"},
                  {"gaussian_sigma", h.gaussian_sigma}, {"weight_bits", h.weight_bits},
                  {"gradient", h.gradient == HeidelbergGradient::Sobel3D ? "3d" : "2d"},
                  {"axis", to_array(h.axis)}, {"angle_deg", h.angle_deg},
                  {"translation", to_array(h.translation)}, {"zoom", h.zoom},
                  {"perspective", h.perspective}, {"depth", h.depth},
                  {"stereo_deg", h.stereo_deg}, {"modules", h.modules},
                  {"rotator_mhz", h.rotator_mhz}, {"dsp_mhz", h.dsp_mhz},
                  {"bus_mhz", h.bus_mhz}});
}

std::string scene_to_toml(const Scene& s) {
  toml::table volume{{"source", s.volume.source},
                     {"gradient", to_string(s.volume.gradient)},
                     {"resample", s.volume.resample}};
  if (s.volume.source.rfind("phantom:", 0) != 0) {
    const std::filesystem::path src(s.volume.source);
    volume.insert_or_assign(
        "source", (src.is_absolute() ? src : std::filesystem::absolute(
                                                  std::filesystem::path(s.base_dir) / src))
                      .lexically_normal()
                      .string());
  }
  if (s.volume.raw) {
    const RawSpec& r = *s.volume.raw;
    volume.insert("dims", to_array(r.dims));
    volume.insert("type", r.type == RawType::U8 ? "u8" : r.type == RawType::U16 ? "u16" : "i16");
    volume.insert("spacing", to_array(r.spacing));
    volume.insert("endian", r.big_endian ? "big" : "little");
  }
  if (s.volume.crop)
    volume.insert("crop", toml::table{{"lo", to_array(s.volume.crop->lo)},
                                      {"hi", to_array(s.volume.crop->hi)}});
  toml::array points;
  for (const TfPoint& p : s.tf_points)
    points.push_back(toml::table{{"value", p.value}, {"color", to_array(p.color)},
                                 {"alpha", p.alpha}});
  toml::table classification{{"interpolation", to_string(s.tf_interpolation)},
                             {"points", points},
                             {"ka", s.material.ka},
                             {"kd", s.material.kd},
                             {"ks", s.material.ks},
                             {"shininess", s.material.shininess}};
  toml::table camera = pose_table(s.camera.pose);
  camera.insert("projection", to_string(s.camera.projection));
  camera.insert("fov_deg", s.camera.fov_deg);
  camera.insert("height", s.camera.height);
  camera.insert("stereo_deg", s.camera.stereo_deg);
  if (!s.camera.path.empty()) {
    toml::array path;
    for (const CameraPose& k : s.camera.path) path.push_back(pose_table(k));
    camera.insert("path", path);
  }
  toml::table render{{"width", s.render.width},
                     {"height", s.render.height},
                     {"mode", to_string(s.render.mode)},
                     {"oversampling", s.render.oversampling},
                     {"ert_threshold", s.render.ert_threshold},
                     {"background", to_array(s.render.background)},
                     {"frames", s.render.frames},
                     {"threads", s.render.threads},
                     {"space_leaping", s.render.space_leaping},
                     {"leap_block", s.render.leap_block},
                     {"jitter", s.render.jitter},
                     {"partial_segments", s.render.partial_segments},
                     {"classification", ref::to_string(s.render.classification)}};
  toml::array lights;
  for (const Light& l : s.lights) {
    toml::table t{{"type", to_string(l.type)}, {"intensity", l.intensity}};
    if (l.type == LightType::Directional) t.insert("direction", to_array(l.direction));
    lights.push_back(t);
  }
  const std::string preset = s.precision_name.substr(0, s.precision_name.find('+'));
  toml::table precision{{"profile", preset}};
  const PrecisionProfile base = preset_profile(preset);
  for (const ProfileField& f : profile_fields())
    if (s.precision.*f.member != base.*f.member) precision.insert(f.name, s.precision.*f.member);
  toml::table rtl;
  for_each_rtl_key(s.rtl, [&rtl](std::string_view key, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::array<int, 3>>)
      rtl.insert(key, to_array(value));
    else
      rtl.insert(key, value);
  });
  toml::table root{{"volume", volume}, {"classification", classification},
                         {"camera", camera}, {"render", render},
                         {"lights", lights}, {"precision", precision},
                         {"rtl", rtl}};
  if (s.algorithm == Algorithm::Heidelberg) heidelberg_to_toml(s, root);
  std::ostringstream os;
  os << root << "\n";
  return os.str();
}

const char* to_string(Algorithm a) {
  return a == Algorithm::Heidelberg ? "heidelberg" : "raycast";
}

std::vector<std::string> known_scene_keys() {
  std::vector<std::string> keys;
  for (const auto& [table, names] : schema())
    for (const auto& n : names) keys.push_back(table.empty() ? n : table + "." + n);
  return keys;
}

}  // namespace voxcast::ref
