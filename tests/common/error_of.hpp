// The message of the voxcast::Error a callable throws: the tests' way to assert
// that bad input is rejected with a clear one-line error.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "refmodel/error.hpp"

namespace voxcast::test {

// The message of the voxcast::Error that fn throws ("" and a failure if none).
template <typename Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no voxcast::Error thrown";
  return "";
}

}  // namespace voxcast::test
