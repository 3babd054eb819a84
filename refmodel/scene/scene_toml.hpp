// Scene files (TOML) and `--set key=value` overrides.
//
// Errors name the origin, line and key: "head.toml:12: render.oversampling = 32
// is outside [0.25, 16]". Unknown keys, wrong types, NaN/Inf and out-of-range
// values are all errors.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"

namespace voxcast::ref {

// "key=value" strings as given on the command line. The value is read as a TOML
// value ("4", "[1, 2, 3]", "\"ramp\""); a bare word that is not valid TOML
// (ramp, phantom:box) is taken as a string.
using Overrides = std::vector<std::string>;

Scene load_scene_file(const std::string& path, const Overrides& overrides = {});

// Edit distance (insertions, deletions, substitutions) between two words: the
// "did you mean" of an unknown key or subcommand.
std::size_t edit_distance(const std::string& a, const std::string& b);
Scene parse_scene(const std::string& toml_text, const std::string& origin,
                  const std::string& base_dir, const Overrides& overrides = {});

// The embedded default scene (scenes/default.toml, compiled in).
const std::string& default_scene_text();
Scene default_scene(const Overrides& overrides = {});

// The scene as TOML that parse_scene reads back to an equal scene (relative
// volume paths are made absolute), for reproducers and reports.
std::string scene_to_toml(const Scene& scene);

// The names [rtl]'s string keys accept ("scheduler", "refresh", "sdram",
// "layout", "traversal"); empty for any other key. The cycle model's
// registries must know exactly these (tests/rtl checks).
const std::vector<std::string>& rtl_choices(const std::string& key);

// Every key the parser accepts, dotted ("render.oversampling",
// "lights[].intensity"); docs/scenes.md must document each one (a test checks).
std::vector<std::string> known_scene_keys();

}  // namespace voxcast::ref
