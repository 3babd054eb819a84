// Small file helpers shared by the subcommands that write files.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace voxcast::cosim {

// Writes `text` to `path` byte for byte (no newline translation); throws
// voxcast::Error naming the path if it cannot be written completely.
void write_text_file(const std::string& path, const std::string& text);

// Writes `bytes` to `path` so that no reader ever sees a part of it: into a
// temporary file beside it (PATH.tmp.PID.N), then renamed over `path`. A run
// killed at any moment leaves the old file or the new one, and at worst a
// temporary file (which readers skip). Throws voxcast::Error naming the path.
void write_file_atomically(const std::string& path, const std::string& bytes);

// Writes `j` as indented JSON (a trailing newline). The text is made before the
// file is opened, so a failure leaves no file behind; bytes that are not UTF-8
// (a path a user named in another encoding) become U+FFFD instead of failing
// the run.
void write_json_file(const std::string& path, const nlohmann::json& j);

// Creates the output folder `dir` (and its parents) unless it exists; throws
// voxcast::Error "cannot create the output folder DIR: REASON" (a file in the
// way, no permission) instead of the library's filesystem_error.
void make_output_dir(const std::string& dir);

// make_output_dir of the folder that will hold the file `path`, if it names one.
void make_parent_dir(const std::string& path);

}  // namespace voxcast::cosim
