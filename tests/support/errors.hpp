// tests/support/errors.hpp -- the message of the exception a call throws.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "uniparam/core/error.hpp"

namespace uniparam::test_support {

/// Calls f and returns the what() of the E it throws; records a test failure
/// (and returns "") when f returns normally. Any other exception propagates,
/// so a test that expects E fails on it too.
template <class E = Error>
std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception";
  return "";
}

}  // namespace uniparam::test_support
