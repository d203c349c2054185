// Private to the algebra layer (not installed): the cache of local
// expansions behind LocalPoly (local_poly.hpp), below the root isolation
// (it knows roots only by their enclosures, not as RealAlgebraic).
//
// [0, 1] is covered by dyadic cells; level l has centres c = (j + 1/2) 2^-l
// and half-width h = 2^-(l+1). A cell holds the Taylor coefficients of p (or
// of a variant p / (t - gamma)) at c (local_expansion.hpp): from an exact
// integer Taylor shift rounded to the working precision (levels 0-3; deeper
// cells: a ball shift of their parent's expansion, rebuilt exactly down to
// level 6 where that lost accuracy), truncated after K terms, with a
// rigorous bound of the dropped tail and of its first two derivatives on the
// disc |t - c| <= 2h. A ball is evaluated in w = t - c by the powers of w
// and one dot product per output (O(K)); the cell depends on the ball
// alone: level 6 for narrow balls, for wide ones (is_wide_ball,
// core/ball_regions.hpp) the deepest level whose disc holds the ball, with
// coarse cells truncated at 2^-24 of p's scale on the cell.
#pragma once

#include <acb.h>
#include <arb_poly.h>

#include <functional>
#include <memory>
#include <vector>

#include "uniparam/algebra/local_expansion.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam::detail {

/// One cell: the expansion e of p at the cell's centre c, p(c + w) =
/// P(w) + T(w) with |T^(j)(w)| <= tail[j] for |w| <= 2h, h = 2^-(level+1)
/// (local_expansion.hpp); P1 = P', P2 = P''.
struct Cell {
  LocalExpansion e;
  arb_poly_t P1, P2;
  std::vector<double> mid;  // midpoints of P in double (eval_double)
  Cell() {
    arb_poly_init(P1);
    arb_poly_init(P2);
  }
  ~Cell() {
    arb_poly_clear(P1);
    arb_poly_clear(P2);
  }
  Cell(const Cell&) = delete;
  Cell& operator=(const Cell&) = delete;
};

using CellPtr = std::shared_ptr<const Cell>;

/// An enclosure, at the given working precision, of a real root gamma of p.
/// Called on a copy, outside any lock (it may refine state of its own).
using RootEnclosure = std::function<Ball(long prec)>;

/// The cells of one polynomial p (the caller passes the same p to every
/// call), built on demand, once each. Every member may be called from
/// several threads at once: a cell is built outside the lock by the first
/// thread that asks for it, others wait for that build, and its content
/// depends only on (level, index, working precision, variant, coarse),
/// never on the order of the evaluations. The cache is emptied at 20000
/// cells (bounded memory).
class LocalCells {
 public:
  LocalCells();
  ~LocalCells();
  LocalCells(const LocalCells&) = delete;
  LocalCells& operator=(const LocalCells&) = delete;

  /// Registers the variant p / (t - gamma) for a root gamma of p (the
  /// caller checked that it is one) and returns its index (0, 1, ...).
  int add_variant(RootEnclosure enclosure);

  /// Enclosures of q(z), and q'(z), q''(z) where d1, d2 are non-null, for q
  /// = p (variant -1) or a registered variant, from the cells at working
  /// precision prec (>= 2). Returns false (outputs unspecified) when no
  /// cell's disc holds z (z far from [0, 1], or not finite).
  /// \post on true, every output contains the exact value at every point
  ///       of z (see LocalPoly::eval for the widths).
  bool eval(const Poly& p, int variant, acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const;

  /// The narrow-ball cell (level 6, at the working precision of a 64-bit
  /// evaluation) of p whose closure holds t (t clamped to [0, 1]).
  /// For the double-precision paths, called per evaluation: the calling
  /// thread keeps its recent cells, so a repeated cell costs no lock (once
  /// a process has threads, every lock is an atomic operation).
  /// \post the reference stays valid until this thread's next call of
  ///       point_cell (on any LocalCells).
  const Cell& point_cell(const Poly& p, double t) const;

  /// Cells cached, and builds started (see LocalPoly::cells, builds).
  std::size_t cells() const;
  std::size_t builds() const;

 private:
  struct Store;
  std::unique_ptr<Store> store_;
};

}  // namespace uniparam::detail
