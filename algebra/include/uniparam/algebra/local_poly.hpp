// uniparam/algebra/local_poly.hpp -- certified evaluation of an exact
// polynomial (and its first two derivatives) on complex balls near [0, 1],
// from cached local Taylor expansions.
//
// Why: the power-basis coefficients of a high-degree curve (a Bezier curve of
// degree 150 has coefficients near 2^150 times its values) make Horner lose
// about as many bits to cancellation, and a centred form on a wide ball needs
// a Taylor shift of the whole polynomial (O(n^2) ball operations, about a
// millisecond at degree 150) for every ball. A local expansion at a nearby
// dyadic centre has coefficients of the size of p's values there, and away
// from p's complex zeros only K << n of its terms matter. So (the cells:
// algebra/src/local_cells.cpp, on the expansions of local_expansion.hpp;
// this class adds the power-basis and double-precision paths and the
// deflation by a RealAlgebraic root):
//   * [0, 1] is covered by dyadic cells; level l has centres
//     c = (j + 1/2) 2^-l and half-width h = 2^-(l+1), j = 0 .. 2^l - 1;
//   * a cell holds p's Taylor coefficients at c, from an exact integer Taylor
//     shift (FLINT) rounded to the working precision (levels 0-3; deeper
//     cells: a ball shift of their parent's expansion, rebuilt exactly down
//     to level 6 where that lost accuracy), truncated after K terms, with a
//     rigorous bound of the dropped tail and of its first two derivatives on
//     the disc |t - c| <= 2h;
//   * a ball is evaluated in w = t - c by the powers of w and one dot product
//     per output (O(K)); the cell depends on the ball alone: level 6 for
//     narrow balls (quadrature nodes), for wide ones (is_wide_ball,
//     core/ball_regions.hpp: radius >= 2^-24:
//     segments, ellipses) the deepest level whose disc holds the ball, which
//     bounds p on a disc at most about twice the ball's radius;
//   * wide balls only bound p (their enclosures are as wide as p's variation
//     on them), so they use coarse cells: truncated at 2^-24 of p's scale on
//     the cell instead of 2^-wp, a few terms instead of hundreds at high
//     degree (cheap shifts from the coarse parent, cheap evaluations).
// Wide balls with a real midpoint, of polynomials of degree <= 64 whose
// power basis loses at most ~52 bits on [0, 1], take the centred form in
// double at their own midpoint first (DoubleCentredForm: O(n^2) flops, no
// cell), unless its rounding part exceeds 2^-10 of the enclosure (near p's
// zeros), where the cells do better; p / (t - gamma) likewise
// (DoubleCentredForm::eval_deflated).
// Balls that no cell's disc contains (far from [0, 1]) fall back to the
// power basis (Horner on narrow balls, a centred form on wide ones), and so
// do narrow balls within 2^-16 of 0, where the power basis is p's own
// expansion about 0 and a cell's about 2^-7 would lose bits next to a root
// at or near 0.
#pragma once

#include <acb.h>
#include <acb_poly.h>

#include <memory>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/ball_regions.hpp"  // is_wide_ball
#include "uniparam/core/cdisk.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {

/// An exact integer polynomial with a cache of local expansions (see the
/// file comment). Copies share the cache, and every member may be called
/// from several threads at once on one LocalPoly or on its copies: the cache
/// is locked, and a cell's content depends only on (level, index, working
/// precision, variant), never on the order of the evaluations, so results do
/// not depend on threads. A moved-from LocalPoly may only be destroyed or
/// assigned to.
class LocalPoly {
 public:
  LocalPoly();
  /// \pre none: any integer polynomial (the zero polynomial evaluates to 0).
  explicit LocalPoly(const Poly& p);
  LocalPoly(const LocalPoly& o);
  LocalPoly& operator=(const LocalPoly& o);
  LocalPoly(LocalPoly&&) noexcept;
  LocalPoly& operator=(LocalPoly&&) noexcept;
  ~LocalPoly();

  /// Enclosures of p(z), and of p'(z), p''(z) where d1, d2 are non-null, on a
  /// complex ball z, computed at working precision prec (>= 2).
  /// \post every output contains the exact value at every point of z; an
  ///       output may be infinite (e.g. a non-finite z), never wrong. A
  ///       narrow ball's enclosure is accurate to about prec bits of p's
  ///       size near z (within 2^-16 of 0: of the size of p's power-basis
  ///       terms at z, so next to a root at 0 of p itself); a wide one
  ///       (radius >= 2^-24) may be wider than p's variation on z by about
  ///       2^-24 of p's size on the discs of the (coarse) cells used. A
  ///       narrow ball wider than a point of prec (a real or imaginary
  ///       radius from 2^(16 - prec), both below 2^-24: a tiny
  ///       subinterval's error bound) also gets the mean-value form
  ///       p(m) + p'(z) (z - m) at its midpoint m (and p'(m) +
  ///       p''(z) (z - m) for p'), intersected with the direct enclosure:
  ///       so its enclosure stays about as wide as p's
  ///       variation on it next to a near double root of p, where Horner's
  ///       rule or a cell's expansion about a farther centre multiply the
  ///       radius by the size of p's coefficients.
  ///       v may not alias d1 or d2 (z may alias none of them).
  void eval(acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const;
  /// Same as eval(v, nullptr, nullptr, z, prec).
  void eval(acb_t v, const acb_t z, long prec) const { eval(v, nullptr, nullptr, z, prec); }
  /// A disc (core/cdisk.hpp) that contains p(t) for every t in z, for
  /// callers that bound a function of several polynomials on a wide ball
  /// in disc arithmetic: the centred form in double at z's midpoint
  /// (DoubleCentredForm, any length up to its degree limit) where it
  /// serves as in eval, otherwise eval's enclosure at prec as a disc.
  /// \post contains p(t) for every t in z, or is not finite (nothing known).
  CDisk eval_disk(const acb_t z, long prec) const;
  /// eval_disk with p' and p'' (outputs may be null): discs that contain
  /// p(t), p'(t), p''(t) for every t in z, or are not finite.
  void eval_disks(CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, long prec) const;
  /// Whether eval_disk has the centred form in double (not only eval's
  /// enclosures converted to discs, up to sqrt(2) wider than Arb's boxes).
  bool has_disk_form() const;

  /// Enclosure of p(z) / (z - gamma) for a real root gamma of p: the
  /// removable singularity removed by deflation (docs/math.md section 4), in the
  /// local basis of each cell: p(c + w) = (w - (gamma - c)) Q(w) by exact
  /// synthetic division of the cell's coefficients (balls containing the
  /// exact ones) by an enclosure of gamma - c, so no division by z - gamma
  /// and no cancellation near gamma. Low degrees, balls far from [0, 1] and
  /// narrow balls within 2^-16 of 0 (as in eval) use the deflated power
  /// basis (deflate()).
  /// \pre gamma is a root of p (checked exactly, once per gamma;
  ///      DomainError otherwise).
  /// \post v contains p(t) / (t - gamma) for every t in z (may be infinite).
  void eval_deflated(acb_t v, const acb_t z, const RealAlgebraic& gamma, long prec) const;

  /// UNCERTIFIED: p(t), p'(t), p''(t) in IEEE double (outputs may be null),
  /// by Horner on the midpoints of the local expansion around t (no
  /// power-basis cancellation, so about 15 digits relative to p's size near
  /// t). For floating-point search only (the optimiser's choice of
  /// breakpoints), never for a reported number. t outside [0, 1] uses the
  /// power basis.
  void eval_double(double t, double* v, double* d1, double* d2) const;
  /// UNCERTIFIED, as eval_double: the Taylor coefficients b[j] = p^(j)(t) / j!,
  /// j = 0 .. order, in IEEE double, from the same local expansion (so the
  /// same cells as eval_double). \pre 0 <= order <= 15 (InvalidArgument).
  void eval_double_taylor(double t, int order, double* b) const;

  /// The polynomial p, and its number of coefficients (degree + 1).
  const Poly& poly() const { return p_; }
  long length() const { return p_.degree() + 1; }

  /// Number of cached cells (for tests and profiling).
  std::size_t cells() const;
  /// Number of cells built so far by this LocalPoly and its copies. Each
  /// cell is built once while it stays cached: a thread asking for a cell
  /// another is building waits for it. So builds() == cells() until the
  /// cache is emptied (at 20000 cells, to bound memory). For tests and
  /// profiling.
  std::size_t builds() const;

 private:
  struct Cache;
  struct PowerBasis;  // p, p', p'' as ball polynomials
  // The power basis (the fallback, and lengths <= 3) at working precision
  // prec: exact_ where p's coefficients have at most prec + 32 bits, else
  // a cached copy rounded to prec + 32 bits (exact coefficients of
  // thousands of bits would make every product cost as much as they do,
  // for no accuracy: each product is rounded to prec anyway).
  std::shared_ptr<const PowerBasis> power_at(long prec) const;
  // eval's enclosures from one path (power basis, centred form in double,
  // or a cell) without the mean-value form of narrow regions.
  void eval_direct(acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const;
  Poly p_;
  std::shared_ptr<const PowerBasis> exact_;
  long bits_ = 0;  // p_.max_bits()
  std::shared_ptr<Cache> cache_;  // shared by copies; locked inside
};

}  // namespace uniparam
