// tests/support/errors.hpp -- the message of the exception a call throws,
// and random edits of valid inputs that must give a result or an Error.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <functional>
#include <random>
#include <string>
#include <vector>

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

/// Mutation fuzzing of a text reader: `count` times a text of `seeds` (drawn
/// by rng when there are several), edited 1 to max_edits times at random
/// places (a character deleted, or one of `alphabet` inserted or put in its
/// place), is given to `read`. A uniparam::Error is an accepted answer; any
/// other exception records a test failure naming the text.
/// \return how many texts `read` returned from (results, not errors).
inline int mutated_results(const std::vector<std::string>& seeds, const std::string& alphabet, int max_edits,
                           std::mt19937_64& rng, int count, const std::function<void(const std::string&)>& read) {
  int results = 0;
  for (int it = 0; it < count; ++it) {
    std::string t = seeds.size() > 1 ? seeds[rng() % seeds.size()] : seeds.front();
    for (int k = 1 + static_cast<int>(rng() % static_cast<unsigned>(max_edits)); k > 0; --k) {
      const std::size_t at = rng() % (t.size() + 1);
      switch (rng() % 3) {
        case 0: if (at < t.size()) t.erase(at, 1); break;
        case 1: t.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
        default: if (at < t.size()) t[at] = alphabet[rng() % alphabet.size()];
      }
    }
    try {
      read(t);
      ++results;
    } catch (const Error&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << t << ": " << e.what();
    }
  }
  return results;
}

}  // namespace uniparam::test_support
