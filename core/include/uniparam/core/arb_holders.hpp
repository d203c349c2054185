// uniparam/core/arb_holders.hpp -- owning holders of single Arb temporaries
// (arb_t, acb_t, mag_t) for local use: initialised on construction, cleared
// on scope exit, so that an exception thrown between the two (a time
// budget, an integrand's error) leaks nothing. Not copyable, not movable.
#pragma once

#include <acb.h>
#include <arb.h>
#include <mag.h>

namespace uniparam {

/// An arb_t, 0 after construction.
struct ArbVar {
  arb_t v;
  ArbVar() noexcept { arb_init(v); }
  ~ArbVar() { arb_clear(v); }
  ArbVar(const ArbVar&) = delete;
  ArbVar& operator=(const ArbVar&) = delete;
};

/// An acb_t, 0 after construction.
struct AcbVar {
  acb_t v;
  AcbVar() noexcept { acb_init(v); }
  ~AcbVar() { acb_clear(v); }
  AcbVar(const AcbVar&) = delete;
  AcbVar& operator=(const AcbVar&) = delete;
};

/// A mag_t, 0 after construction.
struct MagVar {
  mag_t v;
  MagVar() noexcept { mag_init(v); }
  ~MagVar() { mag_clear(v); }
  MagVar(const MagVar&) = delete;
  MagVar& operator=(const MagVar&) = delete;
};

}  // namespace uniparam
