// voxcast::Error — the one exception type for bad input in the host-side code.
//
// Every user-facing failure (a broken volume file, an unknown scene key, an
// impossible camera, a width that cannot hold a value) is reported as one line
// that names what is wrong and where: "scene.toml:12: render.oversampling = 32
// is outside [0.25, 16]". The command line prints what() and exits non-zero.
// (hls/ never throws: it is synthesizable.)
#pragma once

#include <stdexcept>
#include <string>

namespace voxcast {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace voxcast
