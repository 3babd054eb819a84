#include "cosim/reports/junit.hpp"

#include <cstdint>
#include <cstdio>
#include <sstream>

#include <pugixml.hpp>

#include "cosim/reports/files.hpp"

namespace voxcast::cosim {
namespace {

constexpr const char* kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// The length of the well-formed UTF-8 sequence at s[i] (RFC 3629: no overlong
// forms, no surrogates, nothing above U+10FFFF), or 0.
std::size_t utf8_sequence(const std::string& s, std::size_t i) {
  const auto byte = [&s](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  if (b0 >= 0xC2 && b0 <= 0xDF) n = 2;
  else if (b0 == 0xE0) n = 3, lo = 0xA0;
  else if (b0 >= 0xE1 && b0 <= 0xEC) n = 3;
  else if (b0 == 0xED) n = 3, hi = 0x9F;
  else if (b0 >= 0xEE && b0 <= 0xEF) n = 3;
  else if (b0 == 0xF0) n = 4, lo = 0x90;
  else if (b0 >= 0xF1 && b0 <= 0xF3) n = 4;
  else if (b0 == 0xF4) n = 4, hi = 0x8F;
  else return 0;
  if (i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

// Seconds to the millisecond: what a CI server shows, and no noise digits.
std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", s);
  return buf;
}

void add_case(pugi::xml_node suite, const JUnitCase& c) {
  pugi::xml_node tc = suite.append_child("testcase");
  tc.append_attribute("classname") = xml_safe_text(c.classname).c_str();
  tc.append_attribute("name") = xml_safe_text(c.name).c_str();
  tc.append_attribute("time") = seconds_text(c.seconds).c_str();
  if (c.outcome == JUnitCase::Outcome::Failed) {
    pugi::xml_node f = tc.append_child("failure");
    f.append_attribute("message") = xml_safe_text(c.message).c_str();
    f.append_attribute("type") = xml_safe_text(c.type).c_str();
    if (!c.details.empty()) f.text() = xml_safe_text(c.details).c_str();
  } else if (c.outcome == JUnitCase::Outcome::Skipped) {
    tc.append_child("skipped").append_attribute("message") = xml_safe_text(c.message).c_str();
  }
}

}  // namespace

int JUnitSuite::failures() const {
  int n = 0;
  for (const JUnitCase& c : cases) n += c.outcome == JUnitCase::Outcome::Failed ? 1 : 0;
  return n;
}

int JUnitSuite::skipped() const {
  int n = 0;
  for (const JUnitCase& c : cases) n += c.outcome == JUnitCase::Outcome::Skipped ? 1 : 0;
  return n;
}

double JUnitSuite::seconds() const {
  double t = 0.0;
  for (const JUnitCase& c : cases) t += c.seconds;
  return t;
}

std::string xml_safe_text(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence(text, i);
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (n == 0 || (n == 1 && b < 0x20 && b != '\t' && b != '\n' && b != '\r') || b == 0x7F) {
      out += kReplacement;
      i += n == 0 ? 1 : n;
      continue;
    }
    out.append(text, i, n);
    i += n;
  }
  return out;
}

std::string junit_xml(const JUnitSuite& suite) {
  pugi::xml_document doc;
  pugi::xml_node decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  const std::string name = xml_safe_text(suite.name);
  const auto counts = [&suite](pugi::xml_node n) {
    n.append_attribute("tests") = static_cast<long long>(suite.cases.size());
    n.append_attribute("failures") = suite.failures();
    n.append_attribute("errors") = 0;
    n.append_attribute("skipped") = suite.skipped();
    n.append_attribute("time") = seconds_text(suite.seconds()).c_str();
  };
  pugi::xml_node all = doc.append_child("testsuites");
  all.append_attribute("name") = name.c_str();
  counts(all);
  pugi::xml_node one = all.append_child("testsuite");
  one.append_attribute("name") = name.c_str();
  counts(one);
  for (const JUnitCase& c : suite.cases) add_case(one, c);
  std::ostringstream os;
  doc.save(os, "  ", pugi::format_default, pugi::encoding_utf8);
  return os.str();
}

void write_junit_file(const std::string& path, const JUnitSuite& suite) {
  write_text_file(path, junit_xml(suite));
}

}  // namespace voxcast::cosim
