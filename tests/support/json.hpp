// tests/support/json.hpp -- reading the certified reals of uniparam's JSON
// output in CLI tests (the contract of README "JSON").
#pragma once

#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam::test_support {

/// Extracts {"mid": "...", "rad": "..."} of `key` (its first occurrence).
inline bool certified_real(const std::string& json, const std::string& key, std::string& mid, std::string& rad) {
  std::regex re("\"" + key + "\": \\{\\s*\"mid\": \"([^\"]+)\",\\s*\"rad\": \"([^\"]+)\"");
  std::smatch m;
  if (!std::regex_search(json, m, re)) return false;
  mid = m[1];
  rad = m[2];
  return true;
}

/// The value of `key` is a certified real whose interval [mid - rad, mid +
/// rad], read exactly, contains the reference `ref` (known to +- `slack`), and
/// rad <= 10^-digits * max(1, |ref|).
inline ::testing::AssertionResult encloses(const std::string& json, const std::string& key, const char* ref,
                                           const char* slack, long digits) {
  std::string mid, rad;
  if (!certified_real(json, key, mid, rad)) return ::testing::AssertionFailure() << "no certified real " << key;
  const Rational m = Rational::parse(mid), d = Rational::parse(rad), r = Rational::parse(ref),
                 s = Rational::parse(slack);
  if (m - d - s > r || m + d + s < r)
    return ::testing::AssertionFailure() << key << " = " << mid << " +/- " << rad << " misses " << ref;
  Rational bound = Rational::parse("1e-" + std::to_string(digits));
  if (r > Rational(1)) bound = bound * r;
  if (r < Rational(-1)) bound = -bound * r;
  if (d > bound) return ::testing::AssertionFailure() << key << " radius " << rad << " above the digits bound";
  return ::testing::AssertionSuccess();
}

/// The ball of a printed {"mid", "rad"} pair: both read in decimal at 256
/// bits and the result widened by a relative 2^-240 for the reading, so it
/// encloses the printed ball.
inline Ball ball_of(const std::string& mid, const std::string& rad) {
  Ball out, r;
  arb_set_str(out.get(), mid.c_str(), 256);
  arb_set_str(r.get(), rad.c_str(), 256);
  arb_add_error(out.get(), r.get());
  mag_t e;
  mag_init(e);
  arb_get_mag(e, out.get());
  mag_mul_2exp_si(e, e, -240);
  arb_add_error_mag(out.get(), e);
  mag_clear(e);
  return out;
}

/// The certified real `key` of a JSON output as a ball (ball_of); false when
/// the key is missing.
inline bool json_ball(const std::string& json, const std::string& key, Ball& out) {
  std::string mid, rad;
  if (!certified_real(json, key, mid, rad)) return false;
  out = ball_of(mid, rad);
  return true;
}

}  // namespace uniparam::test_support
