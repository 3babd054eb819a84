// Small file helpers shared by the subcommands that write text reports.
#pragma once

#include <string>

namespace voxcast::cosim {

// Writes `text` to `path` byte for byte (no newline translation); throws
// voxcast::Error naming the path if it cannot be written completely.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace voxcast::cosim
