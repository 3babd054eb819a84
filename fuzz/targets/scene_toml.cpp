// Fuzz target: the scene parser (refmodel/scene/scene_toml.cpp) on arbitrary text.
#include <string>

#include "fuzz/targets/targets.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::fuzz {

void scene_toml(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // base_dir is never read by the parser itself (volumes load later): a
  // relative volume path is only made absolute by scene_to_toml.
  const ref::Scene scene = ref::parse_scene(text, "fuzz.toml", "/fuzz");
  // scene_to_toml promises a text parse_scene reads back to an equal scene;
  // failing that (or rejecting its own output) is a finding, not bad input.
  const std::string first = ref::scene_to_toml(scene);
  std::string second;
  try {
    second = ref::scene_to_toml(ref::parse_scene(first, "round-trip.toml", "/fuzz"));
  } catch (const Error& e) {
    throw Finding("parse_scene rejects scene_to_toml's output: " + std::string(e.what()) +
                  "\n--- scene_to_toml:\n" + first);
  }
  if (first != second)
    throw Finding("scene_to_toml -> parse_scene -> scene_to_toml changed the scene\n--- first:\n" +
                  first + "\n--- second:\n" + second);
}

}  // namespace voxcast::fuzz
