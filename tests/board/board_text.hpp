// Helpers for the board tests: the shipped text with one line changed.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "rtl_model/board/board.hpp"

namespace voxcast::test {

// The shipped board's text with `from` replaced by `to` (exactly once).
inline std::string board_with(const std::string& name, const std::string& from,
                              const std::string& to) {
  std::string text = rtl::board::shipped_board_text(name);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from << " occurs twice";
  return text.replace(at, from.size(), to);
}

}  // namespace voxcast::test
