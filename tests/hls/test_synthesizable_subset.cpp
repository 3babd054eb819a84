// The kernels in hls/ stay inside the synthesizable subset a vendor HLS tool
// accepts: no heap, exceptions, virtual calls, RTTI, floating point or
// standard containers in the datapath, and a label on every loop. Host-side
// code (loaders from the bit-true set-up) sits in `#ifndef __SYNTHESIS__`
// blocks and is exempt. The checker is tested on snippets first, so it is
// known to fail on each forbidden construct. (The build also compiles the top
// level with -D__SYNTHESIS__ -fno-exceptions -fno-rtti: tests/CMakeLists.txt.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace VOXCAST_UNITY_ID {

// Removes comments and string/char literals, keeping line breaks.
std::string strip_comments_and_strings(const std::string& src) {
  std::string out;
  enum { Code, Line, Block, Str, Chr } st = Code;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const char c = src[i];
    const char n = i + 1 < src.size() ? src[i + 1] : '\0';
    switch (st) {
      case Code:
        if (c == '/' && n == '/') st = Line, ++i;
        else if (c == '/' && n == '*') st = Block, ++i;
        else if (c == '"') st = Str, out += "\"\"";
        else if (c == '\'') st = Chr, out += "' '";
        else out += c;
        break;
      case Line:
        if (c == '\n') st = Code, out += c;
        break;
      case Block:
        if (c == '*' && n == '/') st = Code, ++i;
        else if (c == '\n') out += c;
        break;
      case Str:
        if (c == '\\') ++i;
        else if (c == '"') st = Code;
        break;
      case Chr:
        if (c == '\\') ++i;
        else if (c == '\'') st = Code;
        break;
    }
  }
  return out;
}

// Drops the lines inside `#ifndef __SYNTHESIS__ ... #endif` (nesting aware):
// what the synthesis tool never sees.
std::string synthesized_part(const std::string& src) {
  std::istringstream in(src);
  std::string line, out;
  int depth = 0;       // #if nesting depth
  int host_from = -1;  // depth at which a host-only block started
  const std::regex if_re(R"(^\s*#\s*if)"), endif_re(R"(^\s*#\s*endif)"),
      host_re(R"(^\s*#\s*ifndef\s+__SYNTHESIS__)");
  while (std::getline(in, line)) {
    if (std::regex_search(line, if_re)) {
      ++depth;
      if (host_from < 0 && std::regex_search(line, host_re)) host_from = depth;
      out += "\n";
      continue;
    }
    if (std::regex_search(line, endif_re)) {
      if (depth == host_from) host_from = -1;
      --depth;
      out += "\n";
      continue;
    }
    out += (host_from >= 0 ? "" : line) + "\n";
  }
  return out;
}

struct Violation {
  int line;
  std::string what;
};

std::vector<Violation> check_subset(const std::string& source) {
  static const std::vector<std::pair<std::regex, std::string>> rules = {
      {std::regex(R"(\bnew\b)"), "heap allocation (new)"},
      {std::regex(R"(\bdelete\b)"), "heap deallocation (delete)"},
      {std::regex(R"(\b(malloc|calloc|realloc|free)\s*\()"), "C heap allocation"},
      {std::regex(R"(\b(throw|try|catch)\b)"), "exceptions"},
      {std::regex(R"(\bvirtual\b)"), "virtual call"},
      {std::regex(R"(\b(dynamic_cast|typeid)\b)"), "RTTI"},
      {std::regex(R"(\b(float|double|long\s+double)\b)"), "floating point in the datapath"},
      {std::regex(R"(\bstd::(vector|string|map|unordered_map|list|deque|set|function|unique_ptr|shared_ptr)\b)"),
       "standard container or owning pointer"},
      {std::regex(R"(\b(goto|setjmp|longjmp)\b)"), "non-structured control flow"},
  };
  // A loop is labelled when `name :` (optionally after [[attributes]]) opens
  // its statement; HLS reports and pragmas refer to loops by these labels.
  static const std::regex loop_re(R"(\b(for|while)\s*\()");
  static const std::regex label_re(R"(\b[A-Za-z_]\w*\s*:\s*$)");
  std::vector<Violation> v;
  const std::string code = synthesized_part(strip_comments_and_strings(source));
  std::istringstream in(code);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    for (const auto& [re, what] : rules)
      if (std::regex_search(line, re)) v.push_back({n, what});
    std::smatch m;
    if (std::regex_search(line, m, loop_re)) {
      const std::string before = m.prefix().str();
      if (!std::regex_search(before, label_re)) v.push_back({n, "unlabelled loop"});
    }
  }
  return v;
}

TEST(SynthesizableSubset, CheckerCatchesEachForbiddenConstruct) {
  const char* const bad[] = {
      "int* p = new int[4];",
      "delete p;",
      "void* q = malloc(8);",
      "if (x) throw 1;",
      "virtual int f();",
      "double y = x;",
      "std::vector<int> v;",
      "auto id = typeid(x);",
      "for (int i = 0; i < 4; ++i) {}",
      "while (k < n) {}",
  };
  for (const char* s : bad) EXPECT_FALSE(check_subset(s).empty()) << s;
  // Comments, strings, labelled loops and host-only blocks are fine.
  EXPECT_TRUE(check_subset("// new double std::vector\nint x = 0; /* throw */").empty());
  EXPECT_TRUE(check_subset("const char* s = \"new double\";").empty());
  EXPECT_TRUE(check_subset("[[maybe_unused]] step_loop : for (int i = 0; i < 4; ++i) {}").empty());
  EXPECT_TRUE(check_subset("lerp_loop:\n  for (int i = 0; i < 4; ++i) {}").size() == 1)
      << "a label on the previous line does not count: keep label and loop together";
  EXPECT_TRUE(check_subset("#ifndef __SYNTHESIS__\n#include <vector>\nstd::vector<double> v;\n"
                           "#if 1\nnew int;\n#endif\n#endif\nint y;")
                  .empty());
  EXPECT_FALSE(check_subset("#ifndef __SYNTHESIS__\nint x;\n#endif\nnew int;").empty());
}

TEST(SynthesizableSubset, KernelsUseOnlyTheSubset) {
  // The type library (fixed_point.hpp) is exempt: a vendor build replaces it
  // with ap_fixed (types.hpp).
  const std::filesystem::path dir = std::filesystem::path(VOXCAST_SOURCE_DIR) / "hls";
  int checked = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().lexically_relative(dir).string();
    if (entry.path().extension() != ".hpp" || name == "fixed_point.hpp") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    for (const Violation& v : check_subset(text.str()))
      ADD_FAILURE() << "hls/" << name << ":" << v.line << ": " << v.what;
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

}  // namespace
