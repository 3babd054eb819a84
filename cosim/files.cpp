#include "cosim/files.hpp"

#include <fstream>

#include "refmodel/error.hpp"

namespace voxcast::cosim {

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  f.close();
  if (!f) throw Error(path + ": cannot write");
}

}  // namespace voxcast::cosim
