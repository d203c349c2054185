// Single-point evaluations of the quadrature: node_fast at a narrow real
// ball, and the error that an end's enclosure (an algebraic end's ball)
// adds to the integrals.
#include <mag.h>

#include <vector>

#include "quadrature_internal.hpp"

namespace uniparam {
namespace quadrature_detail {

/// node_fast's values at the narrow real ball t, as Arb balls in
/// out[0 .. count): true when there is a node_fast, prec <= kNodeFastMaxPrec
/// and it answered finite balls (then they hold f_k on t, by its contract);
/// false otherwise (out unspecified), and the caller asks f. Exceptions from
/// node_fast propagate.
bool fast_point(acb_ptr out, const NodeIntegrand& fast, std::size_t count, const arb_t t, long prec) {
  if (!fast || prec > kNodeFastMaxPrec) return false;
  DDBall x;
  if (!dd_set_arb(x, t)) return false;
  std::vector<DDBall> v(count);
  if (!fast(v.data(), x, prec)) return false;
  for (std::size_t k = 0; k < count; ++k)
    if (!dd_is_finite(v[k])) return false;
  for (std::size_t k = 0; k < count; ++k) {
    dd_get_arb(acb_realref(out + k), v[k]);
    arb_zero(acb_imagref(out + k));
  }
  return true;
}

namespace {

/// add_end_error first bounds f on the ball of radius 2^kEndWideExp around
/// the end (see there).
constexpr long kEndWideExp = -12;

}  // namespace

/// Adds rad(end) * sup |f_k(end)| to the error of each res[k]: the integral
/// over the piece between the true end and the midpoint of its enclosure
/// `end`. The bound is node_fast's where it answers, else f's.
void add_end_error(acb_ptr res, const Integrand& f, const NodeIntegrand& fast, std::size_t count, const Ball& end,
                   long prec) {
  const mag_struct* rad = arb_radref(end.get());
  if (mag_is_zero(rad)) return;  // exact dyadic end: nothing to add, f not evaluated
  AcbVar z;
  AcbVec fz(count);
  if (!fast_point(fz.v, fast, count, end.get(), prec)) {
    // First on a wider ball around the end (a superset: its bound holds on
    // the end ball too): wide balls take cheap coarse evaluations, while a
    // narrow one needs accurate local expansions there, built for this one
    // point (integrands next to a zero of the speed, where node_fast refuses
    // the end). Where that bound is not finite, the end ball itself.
    acb_set_arb(z.v, end.get());
    if (mag_cmp_2exp_si(rad, kEndWideExp) < 0) {
      AcbVar w;
      acb_set(w.v, z.v);
      mag_set_ui_2exp_si(arb_radref(acb_realref(w.v)), 1, kEndWideExp);
      f(fz.v, w.v, false, prec);  // exceptions propagate; the holders clean up
    }
    bool finite = mag_cmp_2exp_si(rad, kEndWideExp) < 0;
    for (std::size_t k = 0; k < count && finite; ++k) finite = acb_is_finite(fz.v + k);
    if (!finite) f(fz.v, z.v, false, prec);
  }
  MagVar bound;
  for (std::size_t k = 0; k < count; ++k) {
    acb_get_mag(bound.v, fz.v + k);  // upper bound of |f_k| on the end ball (inf if not finite)
    mag_mul(bound.v, bound.v, rad);
    acb_add_error_mag(res + k, bound.v);
  }
}

}  // namespace quadrature_detail
}  // namespace uniparam
