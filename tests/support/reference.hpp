// tests/support/reference.hpp -- comparing certified balls with published
// decimal reference values.
#pragma once

#include <arb.h>

#include <cstring>

#include "uniparam/core/ball.hpp"

namespace uniparam::test_support {

/// True when the ball overlaps the reference value, read from its decimal
/// text and widened by one unit of its last printed decimal (the reference
/// itself is rounded).
inline bool contains_ref(const Ball& b, const char* decimal) {
  Ball r;
  arb_set_str(r.get(), decimal, 256);
  const char* dot = std::strchr(decimal, '.');
  const long decimals = dot ? static_cast<long>(std::strlen(dot + 1)) : 0;
  mag_t m;
  mag_init(m);
  mag_set_ui_2exp_si(m, 1, -static_cast<slong>(decimals * 3.3219280948873623) + 1);
  arb_add_error_mag(r.get(), m);
  mag_clear(m);
  return arb_overlaps(b.get(), r.get());
}

}  // namespace uniparam::test_support
