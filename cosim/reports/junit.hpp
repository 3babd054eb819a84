// JUnit XML: the test-result format the CI servers hardware teams run read
// (Jenkins' junit step, GitLab's artifacts:reports:junit), so a regression or
// a cosim shows there as cases that passed or broke, and since when.
//
// One <testsuites> holding one <testsuite>; a case is a <testcase> with a
// classname ("regress.colin27") and a name ("balanced"); a failing case
// carries one <failure message="..." type="...">, a case that could not run a
// <skipped message="...">. Text from users (scene and file names) may be any
// bytes: what is not UTF-8, and the control characters XML 1.0 cannot hold,
// become U+FFFD; markup characters are escaped by the XML writer (pugixml).
#pragma once

#include <string>
#include <vector>

namespace voxcast::cosim {

struct JUnitCase {
  std::string classname;
  std::string name;
  double seconds = 0.0;
  enum class Outcome { Passed, Failed, Skipped } outcome = Outcome::Passed;
  std::string type = {};     // failure: its kind ("CHANGED", "MISMATCH", "MISSING", ...)
  std::string message = {};  // failure or skip: one line naming what is wrong
  std::string details = {};  // failure: the element's text (more lines), may be empty
};

struct JUnitSuite {
  std::string name;  // "voxcast regress", "voxcast cosim"
  std::vector<JUnitCase> cases;
  int failures() const;
  int skipped() const;
  double seconds() const;
};

// The document, indented, with the XML declaration.
std::string junit_xml(const JUnitSuite& suite);

// Writes junit_xml(suite) to `path` (made before the file opens, as
// write_json_file); throws voxcast::Error naming the path if it cannot.
void write_junit_file(const std::string& path, const JUnitSuite& suite);

// `text` as XML 1.0 character data can hold it: invalid UTF-8 and the C0
// controls other than tab, line feed and carriage return become U+FFFD.
std::string xml_safe_text(const std::string& text);

}  // namespace voxcast::cosim
