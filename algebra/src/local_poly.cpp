// LocalPoly (local_poly.hpp): the evaluation paths (power basis and centred
// forms, the centred form in double, the cells of local_cells.hpp) and the
// deflation by a RealAlgebraic root.
#include "uniparam/algebra/local_poly.hpp"

#include <acb_poly.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "local_cells.hpp"
#include "uniparam/algebra/deflation.hpp"
#include "uniparam/algebra/double_centred.hpp"
#include "uniparam/core/ball_regions.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/horner_loss.hpp"

namespace uniparam {

namespace {

// sum_{k > j} k!/(k-j)! |c_k| r^(k-j), by Horner on upper bounds: the
// centred-form bound of p^(j)(z) - j! c_j for j <= 2.
void centred_error(mag_t err, const acb_poly_t c, int j, const mag_t r) {
  mag_t ck, f;
  mag_init(ck);
  mag_init(f);
  mag_zero(err);
  for (slong k = acb_poly_length(c) - 1; k > j; --k) {
    acb_get_mag(ck, acb_poly_get_coeff_ptr(c, k));
    mag_set_ui(f, static_cast<ulong>(j == 0 ? 1 : j == 1 ? k : k * (k - 1)));
    mag_mul(ck, ck, f);
    mag_add(err, err, ck);
    mag_mul(err, err, r);
  }
  mag_clear(ck);
  mag_clear(f);
}

// c_k = p^(k)(m) / k! with m the exact midpoint of z. The shift at precision
// wp loses to cancellation about as many bits as evaluating p at m does
// (power-basis coefficients far larger than the values). When that rounding
// error dominates the enclosure of p(z) (it would hide the true variation
// sum |c_k| r^k, or exclude nothing), the shift is redone with the lost bits
// added (the coefficients of p are exact).
void centred_shift(acb_poly_t c, const BallPoly& p, const acb_t z, const mag_t r, long prec) {
  acb_t m;
  acb_init(m);
  arf_set(arb_midref(acb_realref(m)), arb_midref(acb_realref(z)));
  arf_set(arb_midref(acb_imagref(m)), arb_midref(acb_imagref(z)));
  mag_t err, rad, target;
  mag_init(err);
  mag_init(rad);
  mag_init(target);
  for (long wp = prec;;) {
    acb_poly_set_arb_poly(c, p.get());
    acb_poly_taylor_shift(c, c, m, wp);
    if (acb_poly_length(c) == 0 || wp >= 4 * prec + 256) break;
    centred_error(err, c, 0, r);
    const acb_struct* c0 = acb_poly_get_coeff_ptr(c, 0);
    // target: a 16th of max(variation, |c_0| 2^-prec)
    acb_get_mag_lower(target, c0);
    mag_mul_2exp_si(target, target, -prec);
    mag_max(target, target, err);
    mag_mul_2exp_si(target, target, -4);
    mag_hypot(rad, arb_radref(acb_realref(c0)), arb_radref(acb_imagref(c0)));
    if (mag_cmp(rad, target) <= 0 || mag_is_zero(target)) break;
    // lost bits ~ log2(rounding / target), plus a margin
    const long lost = mag_is_inf(rad) ? wp : fmpz_get_si(MAG_EXPREF(rad)) - fmpz_get_si(MAG_EXPREF(target));
    wp += std::max(lost, 0L) + 16;
  }
  mag_clear(err);
  mag_clear(rad);
  mag_clear(target);
  acb_clear(m);
}

// Outputs of the centred form from the coefficients c at the midpoint of a
// ball of radius r; `real`: the ball is real (then so are c and the values,
// and the error widens the real parts only).
void centred_outputs(acb_ptr outs[3], const acb_poly_t c, const mag_t r, bool real, long prec) {
  const slong n = acb_poly_length(c);
  mag_t err;
  mag_init(err);
  for (int j = 0; j <= 2; ++j) {
    acb_ptr out = outs[j];
    if (!out) continue;
    centred_error(err, c, j, r);
    if (n > j) acb_mul_ui(out, acb_poly_get_coeff_ptr(c, j), static_cast<ulong>(j == 2 ? 2 : 1), prec);
    else acb_zero(out);
    if (real) {
      arb_zero(acb_imagref(out));
      arb_add_error_mag(acb_realref(out), err);
    } else {
      acb_add_error_mag(out, err);
    }
  }
  mag_clear(err);
}

// Polynomials of at most this length are evaluated in the power basis: the
// cells cost more than they save (and low degrees lose little to
// cancellation).
constexpr long kMinLength = 3;

// A narrow ball (not is_wide_ball) inside the disc |z| <= 2^-kNearZeroBits,
// where LocalPoly::eval_direct takes the power basis.
constexpr long kNearZeroBits = 16;
bool near_zero(const acb_t z) {
  if (is_wide_ball(z)) return false;
  mag_t m;
  mag_init(m);
  acb_get_mag(m, z);
  const bool near = mag_cmp_2exp_si(m, -kNearZeroBits) <= 0;
  mag_clear(m);
  return near;
}

// Enclosures of p(z), and p'(z), p''(z) where d1, d2 are non-null, for a
// polynomial with ball coefficients p and its derivatives p1 = p', p2 = p''
// (the power-basis fallback). Narrow balls (radius < 2^kCoarseBallLog2,
// core/ball_regions.hpp) and lengths <= 2:
// Horner. Wide balls: the centred form at the exact midpoint m of z,
//     p^(j)(z) in j! c_j + sum_{k > j} k!/(k-j)! |c_k| r^(k-j) (unit disc),
// c_k = p^(k)(m)/k! by one Taylor shift (centred_shift).
void centred_eval(acb_t v, acb_t d1, acb_t d2, const BallPoly& p, const BallPoly& p1, const BallPoly& p2,
                  const acb_t z, long prec) {
  mag_t r;
  mag_init(r);
  ball_radius(r, z);
  // Narrow balls (the quadrature's nodes) and low degrees: Horner is tight.
  if (p.length() <= 2 || mag_cmp_2exp_si(r, kCoarseBallLog2) < 0) {
    mag_clear(r);
    p.evaluate(v, z, prec);
    if (d1) p1.evaluate(d1, z, prec);
    if (d2) p2.evaluate(d2, z, prec);
    return;
  }
  acb_poly_t c;
  acb_poly_init(c);
  centred_shift(c, p, z, r, prec);
  acb_ptr outs[3] = {v, d1, d2};
  centred_outputs(outs, c, r, acb_is_real(z), prec);
  acb_poly_clear(c);
  mag_clear(r);
}

}  // namespace

// p, p', p'' in the power basis as balls.
struct LocalPoly::PowerBasis {
  BallPoly p, p1, p2;
};

namespace {

// Guard bits of the rounded power basis (LocalPoly::power_at) over the
// working precision: Horner at prec already commits errors of 2^-prec times
// sum |c_k| |z|^k, so coefficients rounded to prec + 32 bits widen an
// enclosure by a factor of at most 1 + 2^-32.
constexpr long kRoundGuard = 32;

}  // namespace

struct LocalPoly::Cache {
  // the cells of p and of its deflations: variant i is p / (t - roots[i].value)
  detail::LocalCells cells;
  std::mutex mu;  // guards roots and deflated
  // roots[i].value lies in [mid - rad, mid + rad] (doubles, for
  // DoubleCentredForm::eval_deflated)
  struct Root {
    RealAlgebraic value;
    double mid, rad;
  };
  std::vector<Root> roots;
  // fallback for p / (t - roots[i]): the deflated power basis, per (i, prec)
  std::map<std::pair<int, long>, std::shared_ptr<const BallPoly>> deflated;
  // the power basis and its two derivatives with coefficients rounded to
  // prec + kRoundGuard bits, per prec, for coefficients wider than that
  // (power_at)
  std::map<long, std::shared_ptr<const PowerBasis>> rounded;
  // Set once, at construction (from horner_loss_bits, core/horner_loss.hpp):
  // eval_double may take Horner's rule on the power basis
  bool double_horner = false;
  // wide real-centred balls take the centred form in double (when usable)
  DoubleCentredForm centred;
};

namespace {

// eval_double takes Horner's rule on the power basis up to this degree and
// loss (horner_loss_bits): there the cells cost more than they save (their
// builds were 16% of dense-plane d=6 `--pieces 3`, for an optimiser's
// steering).
constexpr long kDoubleHornerMaxDegree = 16;
constexpr double kDoubleHornerMaxLoss = 8;

// Wide balls take the centred form in double (DoubleCentredForm) up to
// this loss: its rounding errors are about 2n 2^-53 of the Taylor
// coefficients of |p| at the centre, so past ~52 bits they reach p's values
// on [0, 1] and it could never be used.
constexpr double kDoubleCentredMaxLoss = 52;
// A wide ball's centred form in double whose rounding part exceeds this
// fraction of its value and variation is refused, for the cells: there p is
// small against its coefficients (near its zeros), where the cells' local
// expansions do better. The quadrature's ellipses need no more accuracy
// than that, and stricter costs: bez-rat-space d=12 uniformity 50 M
// instructions at 2^-20, 44 M at 2^-10, 43 M without the check (callgrind,
// one thread).
constexpr double kDoubleCentredMaxError = 0x1p-10;

}  // namespace

LocalPoly::LocalPoly()
    : exact_(std::make_shared<const PowerBasis>()), cache_(std::make_shared<Cache>()) {}
LocalPoly::LocalPoly(const Poly& p)
    : p_(p),
      exact_(std::make_shared<const PowerBasis>(PowerBasis{BallPoly(p), BallPoly(p.derivative()),
                                                           BallPoly(p.derivative().derivative())})),
      bits_(p.max_bits()),
      cache_(std::make_shared<Cache>()) {
  const long n = p.degree();
  if (n < 0 || n > std::max(kDoubleHornerMaxDegree, DoubleCentredForm::kMaxDegree)) return;
  const double loss = horner_loss_bits(p, 0, 1, 2);
  cache_->double_horner = n <= kDoubleHornerMaxDegree && loss <= kDoubleHornerMaxLoss;
  // (eval takes it above kMinLength only; eval_disk at any length)
  if (loss <= kDoubleCentredMaxLoss) cache_->centred = DoubleCentredForm(p);
}
LocalPoly::LocalPoly(const LocalPoly& o) = default;
LocalPoly& LocalPoly::operator=(const LocalPoly& o) = default;
LocalPoly::LocalPoly(LocalPoly&&) noexcept = default;
LocalPoly& LocalPoly::operator=(LocalPoly&&) noexcept = default;
LocalPoly::~LocalPoly() = default;

std::size_t LocalPoly::cells() const { return cache_ ? cache_->cells.cells() : 0; }  // 0: moved from

std::size_t LocalPoly::builds() const { return cache_ ? cache_->cells.builds() : 0; }

void LocalPoly::eval_double(double t, double* v, double* d1, double* d2) const {
  double c[3] = {0, 0, 0};
  const long n = p_.degree();
  if (n < 1 || cache_->double_horner || !(t >= 0 && t <= 1)) {
    for (long k = n; k >= 0; --k) {  // Horner with two derivatives
      c[2] = c[2] * t + c[1];
      c[1] = c[1] * t + c[0];
      c[0] = c[0] * t + fmpz_get_d(p_.get()->coeffs + k);
    }
    c[2] *= 2;
  } else {
    const detail::Cell& cell = cache_->cells.point_cell(p_, t);
    const double w = t - arf_get_d(cell.e.centre, ARF_RND_NEAR);
    for (std::size_t k = cell.mid.size(); k-- > 0;) {
      c[2] = c[2] * w + c[1];
      c[1] = c[1] * w + c[0];
      c[0] = c[0] * w + cell.mid[k];
    }
    c[2] *= 2;
  }
  if (v) *v = c[0];
  if (d1) *d1 = c[1];
  if (d2) *d2 = c[2];
}

void LocalPoly::eval_double_taylor(double t, int order, double* b) const {
  if (order < 0 || order > 15) throw InvalidArgument("eval_double_taylor: order must be in [0, 15]");
  // coefficients in w around a centre, then shifted by w (the thread's
  // buffer: no allocation per evaluation)
  thread_local std::vector<double> a;
  a.clear();
  double w = t;
  const long n = p_.degree();
  if (n < 1 || (n + 1 <= kMinLength && cache_->double_horner) || !(t >= 0 && t <= 1)) {
    for (long k = 0; k <= n; ++k) a.push_back(fmpz_get_d(p_.get()->coeffs + k));
  } else {
    const detail::Cell& cell = cache_->cells.point_cell(p_, t);  // eval_double's cells
    a.assign(cell.mid.begin(), cell.mid.end());
    w = t - arf_get_d(cell.e.centre, ARF_RND_NEAR);
  }
  // Taylor shift by w (repeated synthetic division): after pass j, a[j] is
  // the j-th coefficient at t; only the first order + 1 passes are needed.
  const long len = static_cast<long>(a.size());
  for (long j = 0; j <= order; ++j) {
    if (j >= len) {
      b[j] = 0;
      continue;
    }
    for (long k = len - 2; k >= j; --k) a[static_cast<std::size_t>(k)] += w * a[static_cast<std::size_t>(k + 1)];
    b[j] = a[static_cast<std::size_t>(j)];
  }
}

namespace {

// A narrow ball (below 2^kCoarseBallLog2) is a point of the working
// precision when its radius is below 2^(kPointGuardBits - prec) (a
// quadrature node: radius about 2^-prec); wider narrow balls (the error
// bounds of tiny subintervals, interval Newton steps) take the mean-value
// form as well (eval).
constexpr long kPointGuardBits = 16;

// x = x intersected with y, real and imaginary parts (both contain the same
// value); x is left as it is if the intersection is empty (it cannot be for
// two true enclosures, but a non-finite y must not spoil x).
void intersect(acb_t x, const acb_t y, long prec) {
  if (!acb_is_finite(y)) return;
  arb_t re, im;
  arb_init(re);
  arb_init(im);
  if (arb_intersection(re, acb_realref(x), acb_realref(y), prec) &&
      arb_intersection(im, acb_imagref(x), acb_imagref(y), prec)) {
    arb_swap(acb_realref(x), re);
    arb_swap(acb_imagref(x), im);
  }
  arb_clear(re);
  arb_clear(im);
}

}  // namespace

void LocalPoly::eval(acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const {
  // Horner's rule and a cell's expansion about a centre c wrap a ball of
  // radius r into about r sum_k k |a_k| |z - c|^(k-1): where p' is small next
  // to its absolute-value bound (close to a near double root, as next to the
  // peak of 1 + C (t - 3/5)^2), a narrow ball well wider than a point
  // gets an enclosure many orders wider than p's variation on it. The
  // mean-value form p(m) + p'(z) (z - m) at z's exact midpoint m wraps only
  // at second order (p'' r^2), and both are intersected.
  // (the radius of either part, as is_wide_ball reads it: no hypot per node)
  const bool region = p_.degree() >= 2 && acb_is_finite(z) && !is_wide_ball(z) &&
                      (mag_cmp_2exp_si(arb_radref(acb_realref(z)), kPointGuardBits - prec) >= 0 ||
                       mag_cmp_2exp_si(arb_radref(acb_imagref(z)), kPointGuardBits - prec) >= 0);
  if (!region) {
    eval_direct(v, d1, d2, z, prec);
    return;
  }
  acb_t D1, D2, m, w, vm, dm, alt;
  acb_init(D1);
  acb_init(D2);
  acb_init(m);
  acb_init(w);
  acb_init(vm);
  acb_init(dm);
  acb_init(alt);
  eval_direct(v, D1, (d1 || d2) ? D2 : nullptr, z, prec);
  acb_get_mid(m, z);
  acb_sub(w, z, m, prec);
  eval_direct(vm, d1 ? dm : nullptr, nullptr, m, prec);
  acb_mul(alt, D1, w, prec);
  acb_add(alt, alt, vm, prec);
  intersect(v, alt, prec);
  if (d1) {
    acb_mul(alt, D2, w, prec);
    acb_add(alt, alt, dm, prec);
    intersect(D1, alt, prec);
    acb_swap(d1, D1);
  }
  if (d2) acb_swap(d2, D2);
  acb_clear(D1);
  acb_clear(D2);
  acb_clear(m);
  acb_clear(w);
  acb_clear(vm);
  acb_clear(dm);
  acb_clear(alt);
}

void LocalPoly::eval_direct(acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const {
  // Narrow balls within 2^-kNearZeroBits of 0 take the power basis, p's
  // expansion about 0: a cell's about its centre 2^-7 sums terms of p's
  // size on that cell, and next to a root of p at or near 0 (a narrow
  // feature moved to 0 by an exact change of variable), at |z| = 2^-k, that is
  // 2^(k - 7) times p(z) or more: all of prec's bits lost from k ~ prec.
  if (p_.degree() + 1 <= kMinLength || !acb_is_finite(z) || near_zero(z)) {
    const std::shared_ptr<const PowerBasis> b = power_at(prec);
    centred_eval(v, d1, d2, b->p, b->p1, b->p2, z, prec);
    return;
  }
  // Wide balls of low degree: the centred form in double, cheaper than a
  // cell's build and centred at the ball's own midpoint.
  if (cache_->centred.usable() && is_wide_ball(z) && cache_->centred.eval(v, d1, d2, z, kDoubleCentredMaxError))
    return;
  if (!cache_->cells.eval(p_, -1, v, d1, d2, z, prec)) {
    const std::shared_ptr<const PowerBasis> b = power_at(prec);
    centred_eval(v, d1, d2, b->p, b->p1, b->p2, z, prec);
  }
}

std::shared_ptr<const LocalPoly::PowerBasis> LocalPoly::power_at(long prec) const {
  if (bits_ <= prec + kRoundGuard) return exact_;
  Cache& cache = *cache_;
  {
    std::lock_guard<std::mutex> lock(cache.mu);
    auto it = cache.rounded.find(prec);
    if (it != cache.rounded.end()) return it->second;
  }
  auto round = [prec](const BallPoly& e) {
    BallPoly r;
    arb_poly_set_round(r.get(), e.get(), prec + kRoundGuard);
    return r;
  };
  auto b = std::make_shared<const PowerBasis>(PowerBasis{round(exact_->p), round(exact_->p1), round(exact_->p2)});
  std::lock_guard<std::mutex> lock(cache.mu);
  if (cache.rounded.size() > 16) cache.rounded.clear();
  return cache.rounded.emplace(prec, std::move(b)).first->second;
}

bool LocalPoly::has_disk_form() const { return cache_->centred.usable(); }

void LocalPoly::eval_disks(CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, long prec) const {
  if (cache_->centred.usable() && acb_is_finite(z) && cache_->centred.eval_disks(v, d1, d2, z, kDoubleCentredMaxError))
    return;
  acb_t a[3];
  for (auto& x : a) acb_init(x);
  eval(a[0], d1 ? a[1] : nullptr, d2 ? a[2] : nullptr, z, prec);
  CDisk* outs[3] = {v, d1, d2};
  for (int j = 0; j < 3; ++j)
    if (outs[j]) *outs[j] = cdisk_set_acb(a[j]);
  for (auto& x : a) acb_clear(x);
}

CDisk LocalPoly::eval_disk(const acb_t z, long prec) const {
  CDisk d;
  eval_disks(&d, nullptr, nullptr, z, prec);
  return d;
}

void LocalPoly::eval_deflated(acb_t v, const acb_t z, const RealAlgebraic& gamma, long prec) const {
  Cache& cache = *cache_;
  int variant = -1;
  double g_mid = 0, g_rad = 0;
  {
    std::lock_guard<std::mutex> lock(cache.mu);
    for (std::size_t i = 0; i < cache.roots.size(); ++i)
      if (cache.roots[i].value == gamma) variant = static_cast<int>(i);
    if (variant >= 0) {
      g_mid = cache.roots[static_cast<std::size_t>(variant)].mid;
      g_rad = cache.roots[static_cast<std::size_t>(variant)].rad;
    }
  }
  if (variant < 0) {
    if (p_.is_zero() || root_multiplicity(p_, gamma) < 1)
      throw DomainError("eval_deflated: " + gamma.str() + " is not a root of " + p_.str());
    // gamma's enclosure in doubles: the nearest double to an 80-bit ball's
    // midpoint, and a radius covering the ball and that rounding
    const Ball g = gamma.to_ball(80);
    g_mid = arf_get_d(arb_midref(g.get()), ARF_RND_NEAR);
    g_rad = (mag_get_d(arb_radref(g.get())) + std::fabs(g_mid) * 0x1p-52 + 0x1p-1070) * (1 + 0x1p-50);
    if (!std::isfinite(g_mid) || !std::isfinite(g_rad)) g_rad = HUGE_VAL;  // (never used then)
    std::lock_guard<std::mutex> lock(cache.mu);
    for (std::size_t i = 0; i < cache.roots.size() && variant < 0; ++i)  // another thread may have added it
      if (cache.roots[i].value == gamma) variant = static_cast<int>(i);
    if (variant < 0) {
      cache.roots.push_back({gamma, g_mid, g_rad});
      // the cells' variant of the same index: p / (t - gamma), gamma enclosed
      // by a copy of the RealAlgebraic (each call refines its own copy)
      variant = cache.cells.add_variant([gamma](long bits) { return gamma.to_ball(bits); });
    }
  }
  // Wide balls of low degree: the centred form of the quotient in double.
  if (cache.centred.usable() && is_wide_ball(z) && acb_is_finite(z) &&
      cache.centred.eval_deflated(v, z, g_mid, g_rad, kDoubleCentredMaxError))
    return;
  if (p_.degree() + 1 > kMinLength && acb_is_finite(z) && !near_zero(z) &&
      cache.cells.eval(p_, variant, v, nullptr, nullptr, z, prec))
    return;
  // Low degree, far from [0, 1], or a narrow ball next to 0 (as in
  // eval_direct): the deflated power basis (exact synthetic division in
  // Z[gamma], see deflate), centred form.
  const auto key = std::make_pair(variant, prec);
  std::shared_ptr<const BallPoly> q;
  {
    std::lock_guard<std::mutex> lock(cache.mu);
    auto it = cache.deflated.find(key);
    if (it != cache.deflated.end()) q = it->second;
  }
  if (!q) {
    q = std::make_shared<const BallPoly>(deflate(p_, gamma, 1, prec + 16));
    std::lock_guard<std::mutex> lock(cache.mu);
    if (cache.deflated.size() > 64) cache.deflated.clear();
    cache.deflated.emplace(key, q);
  }
  centred_eval(v, nullptr, nullptr, *q, *q, *q, z, prec);
}

}  // namespace uniparam
