// Tests of uniparam/algebra/local_poly.hpp: the enclosures of p, p', p'' and
// of p / (t - gamma) from local expansions contain the values at every
// sampled point of random balls (narrow and wide, inside and outside
// [0, 1]), checked against evaluations at 4000 bits at exact points; and
// narrow balls do not pay for the power basis' cancellation.
#include <acb_poly.h>
#include <arb_poly.h>
#include <flint/flint.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "support/balls.hpp"
#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::expect_encloses_at_points;
using test_support::iterations;
using test_support::offsets;
using test_support::point_of;
using test_support::random_poly;

constexpr long kRefPrec = 4000;

/// Power-basis coefficients of sum_k b_k C(n,k) t^k (1-t)^(n-k): a Bezier
/// polynomial, whose power-basis coefficients dwarf its values on [0, 1].
Poly bernstein(const std::vector<long>& b) {
  const long n = static_cast<long>(b.size()) - 1;
  fmpz_poly_t acc, term, lin, one_minus;
  fmpz_poly_init(acc);
  fmpz_poly_init(term);
  fmpz_poly_init(lin);
  fmpz_poly_init(one_minus);
  fmpz_poly_set_coeff_si(lin, 1, 1);
  fmpz_poly_set_coeff_si(one_minus, 0, 1);
  fmpz_poly_set_coeff_si(one_minus, 1, -1);
  fmpz_t binom;
  fmpz_init(binom);
  for (long k = 0; k <= n; ++k) {
    fmpz_poly_pow(term, lin, static_cast<ulong>(k));
    fmpz_poly_t r;
    fmpz_poly_init(r);
    fmpz_poly_pow(r, one_minus, static_cast<ulong>(n - k));
    fmpz_poly_mul(term, term, r);
    fmpz_poly_clear(r);
    fmpz_bin_uiui(binom, static_cast<ulong>(n), static_cast<ulong>(k));
    fmpz_mul_si(binom, binom, b[static_cast<std::size_t>(k)]);
    fmpz_poly_scalar_mul_fmpz(term, term, binom);
    fmpz_poly_add(acc, acc, term);
  }
  Poly p;
  fmpz_poly_set(p.get(), acc);
  fmpz_clear(binom);
  fmpz_poly_clear(acc);
  fmpz_poly_clear(term);
  fmpz_poly_clear(lin);
  fmpz_poly_clear(one_minus);
  return p;
}

/// A random test polynomial of degree >= 11 (the cells' range): dense small
/// coefficients, or a Bezier polynomial of degree up to 160.
Poly random_test_poly(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 1);
  if (kind(rng) == 0) return random_poly(rng, std::uniform_int_distribution<long>(11, 90)(rng), 20);
  const long n = std::uniform_int_distribution<long>(11, 160)(rng);
  std::uniform_int_distribution<long> c(-1000, 1000);
  std::vector<long> b(static_cast<std::size_t>(n + 1));
  for (auto& x : b) x = c(rng);
  return bernstein(b);
}

/// A random complex ball: midpoint in [-0.2, 1.2] (+ a small imaginary part
/// sometimes), radius 0 (a point), tiny, or wide (2^-3 .. 2^-20).
void random_ball(acb_t z, std::mt19937_64& rng) {
  std::uniform_int_distribution<long> re(-209715, 1258291);  // [-0.2, 1.2] * 2^20
  std::uniform_int_distribution<long> num(-(1L << 20), 1L << 20);
  std::uniform_int_distribution<int> pick(0, 3);
  acb_zero(z);
  arb_set_si(acb_realref(z), re(rng));
  arb_mul_2exp_si(acb_realref(z), acb_realref(z), -20);
  if (pick(rng) == 0) {
    arb_set_si(acb_imagref(z), num(rng));
    arb_mul_2exp_si(acb_imagref(z), acb_imagref(z), -27);
  }
  const int k = pick(rng);
  if (k == 0) return;  // a point
  const long e = k == 1 ? -std::uniform_int_distribution<long>(26, 60)(rng)
                        : -std::uniform_int_distribution<long>(3, 20)(rng);
  mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1 + std::uniform_int_distribution<ulong>(0, 7)(rng), e - 3);
  if (pick(rng) != 0) mag_set_ui_2exp_si(arb_radref(acb_imagref(z)), 1 + std::uniform_int_distribution<ulong>(0, 7)(rng), e - 3);
}

/// p, p', p'' as exact Arb polynomials (the reference evaluations).
struct RefDerivatives {
  arb_poly_t r[3];
  explicit RefDerivatives(const Poly& p) {
    for (auto& x : r) arb_poly_init(x);
    arb_poly_set_fmpz_poly(r[0], p.get(), ARF_PREC_EXACT);
    arb_poly_derivative(r[1], r[0], ARF_PREC_EXACT);
    arb_poly_derivative(r[2], r[1], ARF_PREC_EXACT);
  }
  ~RefDerivatives() {
    for (auto& x : r) arb_poly_clear(x);
  }
  RefDerivatives(const RefDerivatives&) = delete;
  RefDerivatives& operator=(const RefDerivatives&) = delete;
};

TEST(LocalPoly, EnclosesValueAndDerivativesOnRandomBalls) {
  std::mt19937_64 rng(20261122);
  const long precs[] = {30, 64, 128, 200};
  for (long it = 0; it < iterations(60); ++it) {
    const Poly p = random_test_poly(rng);
    const LocalPoly lp(p);
    const RefDerivatives rd(p);
    const auto& ref = rd.r;
    for (int b = 0; b < 25; ++b) {
      acb_t z, v, d1, d2, t, exact;
      for (acb_ptr x : {z, v, d1, d2, t, exact}) acb_init(x);
      random_ball(z, rng);
      const long prec = precs[std::uniform_int_distribution<int>(0, 3)(rng)];
      lp.eval(v, d1, d2, z, prec);
      const acb_struct* outs[3] = {v, d1, d2};
      for (const auto& [a, c] : offsets(rng)) {
        point_of(t, z, a, c);
        ASSERT_TRUE(acb_contains(z, t));
        for (int j = 0; j < 3; ++j) {
          arb_poly_evaluate_acb(exact, ref[j], t, kRefPrec);
          ASSERT_TRUE(acb_contains(outs[j], exact))
              << "derivative " << j << " of a degree-" << p.degree() << " polynomial at prec " << prec;
        }
      }
      for (acb_ptr x : {z, v, d1, d2, t, exact}) acb_clear(x);
    }
  }
}

TEST(LocalPoly, DiscsHoldValueAndDerivativesOnRandomBalls) {
  // eval_disks: the centred form's discs (degree <= 64, any length) or
  // eval's enclosures as discs (higher degrees), on the same balls as above
  // plus short polynomials (lengths 1-3, which eval leaves to Arb).
  std::mt19937_64 rng(20261201);
  long centred = 0;
  for (long it = 0; it < iterations(60); ++it) {
    const Poly p = it % 3 == 0 ? random_poly(rng, it % 9 / 3, 20) : random_test_poly(rng);
    const LocalPoly lp(p);
    centred += lp.has_disk_form();
    const RefDerivatives rd(p);
    const auto& ref = rd.r;
    for (int b = 0; b < 25; ++b) {
      acb_t z, t, exact, w;
      for (acb_ptr x : {z, t, exact, w}) acb_init(x);
      random_ball(z, rng);
      CDisk o[4];
      lp.eval_disks(&o[0], &o[1], &o[2], z, 64);
      o[3] = lp.eval_disk(z, 64);  // the value alone (the centred form may serve it and not p'')
      for (const auto& [a, c] : offsets(rng)) {
        point_of(t, z, a, c);
        for (int j = 0; j < 4; ++j) {
          if (!cdisk_is_finite(o[j])) continue;
          arb_poly_evaluate_acb(exact, ref[j % 3], t, kRefPrec);
          // |exact - centre| <= rad
          acb_set_d_d(w, o[j].re, o[j].im);
          acb_sub(w, exact, w, kRefPrec);
          arb_t m, r;
          arb_init(m);
          arb_init(r);
          acb_abs(m, w, kRefPrec);
          arb_set_d(r, o[j].rad);
          ASSERT_TRUE(arb_le(m, r)) << "derivative " << j << " of a degree-" << p.degree() << " polynomial";
          arb_clear(m);
          arb_clear(r);
        }
      }
      for (acb_ptr x : {z, t, exact, w}) acb_clear(x);
    }
  }
  EXPECT_GT(centred, iterations(60) / 3);  // both paths ran
  EXPECT_LT(centred, iterations(60));
}

TEST(LocalPoly, DeflatedEnclosesQuotientNearAndFarFromTheRoot) {
  std::mt19937_64 rng(7);
  // p = q (2t^2 - 1): gamma = 1/sqrt(2), p / (t - gamma) = 2 q (t + gamma).
  const Poly f(std::vector<long>{-1, 0, 2});
  const RealAlgebraic gamma(f, Rational(1, 2), Rational(1));
  for (long it = 0; it < iterations(40); ++it) {
    const Poly q = random_test_poly(rng);
    const LocalPoly lp(q * f);
    arb_poly_t qb;
    arb_poly_init(qb);
    arb_poly_set_fmpz_poly(qb, q.get(), ARF_PREC_EXACT);
    const Ball g = gamma.to_ball(kRefPrec);
    for (int b = 0; b < 25; ++b) {
      acb_t z, v, t, exact, s;
      for (acb_ptr x : {z, v, t, exact, s}) acb_init(x);
      random_ball(z, rng);
      if (b % 2 == 0) {  // centred on gamma (to 80 bits): the ball holds it or nearly
        arb_set_round(acb_realref(s), g.get(), 80);
        arf_set(arb_midref(acb_realref(z)), arb_midref(acb_realref(s)));
      }
      const long prec = b % 3 == 0 ? 64 : 128;
      lp.eval_deflated(v, z, gamma, prec);
      for (const auto& [a, c] : offsets(rng)) {
        point_of(t, z, a, c);
        arb_poly_evaluate_acb(exact, qb, t, kRefPrec);
        acb_add_arb(s, t, g.get(), kRefPrec);
        acb_mul(exact, exact, s, kRefPrec);
        acb_mul_2exp_si(exact, exact, 1);
        ASSERT_TRUE(acb_contains(v, exact)) << "degree " << q.degree() + 2 << ", prec " << prec;
      }
      for (acb_ptr x : {z, v, t, exact, s}) acb_clear(x);
    }
    arb_poly_clear(qb);
  }
}

TEST(LocalPoly, DeflatedRefusesANonRoot) {
  const LocalPoly lp(Poly(std::vector<long>{-1, 0, 2}) * Poly(std::vector<long>{1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1}));
  const RealAlgebraic not_root(Rational(1, 3));
  acb_t z, v;
  acb_init(z);
  acb_init(v);
  EXPECT_THROW(lp.eval_deflated(v, z, not_root, 64), DomainError);
  acb_clear(z);
  acb_clear(v);
}

// The point of the local bases: at a node in [0, 1], a Bezier polynomial of
// degree n (power-basis coefficients ~2^n times its values) evaluated at 80
// bits is accurate to about 80 bits of the size of its Bernstein
// coefficients, where Horner in the power basis would lose ~n bits. The
// nodes' cells (level 6) are ball shifts of their parents' expansions, whose
// discs reach where p is far larger: they must not lose those bits.
TEST(LocalPoly, NarrowBallsDoNotPayForPowerBasisCancellation) {
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<long> c(-1000, 1000);
  for (long n : {150L, 300L}) {
    std::vector<long> b(static_cast<std::size_t>(n + 1));
    for (auto& x : b) x = c(rng);
    const LocalPoly lp(bernstein(b));
    std::uniform_int_distribution<long> num(0, 1L << 30);
    for (int i = 0; i < 300; ++i) {
      acb_t z, v;
      acb_init(z);
      acb_init(v);
      arb_set_si(acb_realref(z), num(rng));
      arb_mul_2exp_si(acb_realref(z), acb_realref(z), -30);
      lp.eval(v, z, 80);
      // |p| <= 1000 on [0, 1]; the radius must stay near 1000 * 2^-80.
      EXPECT_LT(mag_cmp_2exp_si(arb_radref(acb_realref(v)), 10 - 60), 0) << "degree " << n << ", node " << i;
      acb_clear(z);
      acb_clear(v);
    }
    EXPECT_GT(lp.cells(), 0u);
  }
}

// Wide balls (the quadrature's ellipses and segments) use coarse cells, which
// keep p's expansion only to about 2^-24 of its size. Their enclosures must
// stay about as tight as p's variation on the ball: with c_j the exact Taylor
// coefficients of p at the ball's midpoint (4000 bits) and r the ball's
// radius, the enclosure's radius is at most twice the majorant
// sum_{j >= 1} |c_j| (8r)^j of p - p(mid), plus 2^-20 of the majorant of p
// there (the cell's centre c is within 2.9r of the midpoint m, and the
// enclosure sums the expansion at c on |t - c| <= |m - c| + 1.5r, which the
// expansion at m majorises on the radius 2|m - c| + 1.5r < 8r; the coarse
// tails are 2^-24 of p's size on the cell). Cells truncated far below 24
// bits break it (at 8 bits, 19 of the 180 balls fail).
TEST(LocalPoly, WideBallsAreAboutAsTightAsTheVariationOfP) {
  std::mt19937_64 rng(4242);
  std::uniform_int_distribution<long> c(-1000, 1000);
  std::uniform_int_distribution<long> num(0, 1L << 20);
  std::uniform_int_distribution<long> ex(3, 20);
  std::uniform_int_distribution<ulong> frac(0, 8);
  for (long n : {40L, 150L, 300L}) {
    std::vector<long> b(static_cast<std::size_t>(n + 1));
    for (auto& x : b) x = c(rng);
    const Poly p = bernstein(b);
    const LocalPoly lp(p);
    arb_poly_t exact, shifted;
    arb_poly_init(exact);
    arb_poly_init(shifted);
    arb_poly_set_fmpz_poly(exact, p.get(), kRefPrec);
    for (long i = 0; i < iterations(60); ++i) {
      acb_t z, v;
      acb_init(z);
      acb_init(v);
      // an ellipse-like box: real radius r = 2^-e, imaginary radius <= r
      const long e = ex(rng);
      arb_set_si(acb_realref(z), num(rng));
      arb_mul_2exp_si(acb_realref(z), acb_realref(z), -20);
      mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1, -e);
      mag_set_ui_2exp_si(arb_radref(acb_imagref(z)), frac(rng), -e - 3);
      lp.eval(v, z, 80);
      // majorants at radius 8r from the exact expansion at the midpoint
      arb_t m;
      arb_init(m);
      arb_set_arf(m, arb_midref(acb_realref(z)));
      arb_poly_taylor_shift(shifted, exact, m, kRefPrec);
      mag_t rho, term, var, all;
      mag_init(rho);
      mag_init(term);
      mag_init(var);
      mag_init(all);
      mag_set_ui_2exp_si(rho, 1, 3 - e);
      // all = sum_{j >= 0} |c_j| rho^j, var = sum_{j >= 1} |c_j| rho^j
      mag_one(term);
      for (slong j = 0; j < arb_poly_length(shifted); ++j) {
        mag_t cj;
        mag_init(cj);
        arb_get_mag(cj, shifted->coeffs + j);
        mag_mul(cj, cj, term);
        mag_add(all, all, cj);
        if (j >= 1) mag_add(var, var, cj);
        mag_clear(cj);
        mag_mul(term, term, rho);
      }
      mag_mul_2exp_si(var, var, 1);
      mag_mul_2exp_si(all, all, -20);
      mag_add(var, var, all);
      mag_t rad;
      mag_init(rad);
      mag_hypot(rad, arb_radref(acb_realref(v)), arb_radref(acb_imagref(v)));
      EXPECT_LE(mag_cmp(rad, var), 0) << "degree " << n << ", radius 2^-" << e << ", ball " << i;
      mag_clear(rad);
      mag_clear(rho);
      mag_clear(term);
      mag_clear(var);
      mag_clear(all);
      arb_clear(m);
      acb_clear(z);
      acb_clear(v);
    }
    arb_poly_clear(exact);
    arb_poly_clear(shifted);
  }
}

}  // namespace
}  // namespace uniparam

namespace uniparam {
namespace {

// Copies share one cache, and evaluations from several threads at once give
// exactly the enclosures a fresh LocalPoly gives on one thread (a cell
// depends only on its key, never on who built it or when).
TEST(LocalPoly, CopiesShareCellsAndThreadsGetTheSameEnclosures) {
  std::mt19937_64 rng(7121);
  for (long it = 0; it < iterations(4); ++it) {
    const Poly p = random_test_poly(rng);
    const LocalPoly shared(p);
    const LocalPoly copy = shared;  // NOLINT: the copy is the point
    constexpr int kBalls = 200;
    std::vector<acb_struct> balls(kBalls);
    for (auto& z : balls) {
      acb_init(&z);
      random_ball(&z, rng);
    }
    // the reference: a fresh LocalPoly, one thread, in order
    std::vector<acb_struct> ref(3 * kBalls);
    for (auto& v : ref) acb_init(&v);
    {
      const LocalPoly fresh(p);
      for (int b = 0; b < kBalls; ++b) fresh.eval(&ref[3 * b], &ref[3 * b + 1], &ref[3 * b + 2], &balls[b], 96);
    }
    // two threads on the shared cache (one through the copy), in opposite orders
    std::vector<acb_struct> got(6 * kBalls);
    for (auto& v : got) acb_init(&v);
    // thread t writes outputs t; `forward` is its order
    auto run_in = [&](const LocalPoly& lp, int t, bool forward) {
      for (int k = 0; k < kBalls; ++k) {
        const int b = forward ? k : kBalls - 1 - k;
        acb_ptr o = &got[static_cast<std::size_t>(3 * (t * kBalls + b))];
        lp.eval(o, o + 1, o + 2, &balls[b], 96);
      }
      flint_cleanup();  // this thread's FLINT caches (as parallel_for's workers do)
    };
    auto run = [&](const LocalPoly& lp, int t) { run_in(lp, t, t == 0); };
    std::thread a(run, std::cref(shared), 0), c(run, std::cref(copy), 1);
    a.join();
    c.join();
    EXPECT_GT(shared.cells(), 0u);
    EXPECT_EQ(shared.cells(), copy.cells());  // one cache
    const LocalPoly late = shared;             // NOLINT: a copy made after the work
    EXPECT_EQ(late.cells(), shared.cells());
    for (int t = 0; t < 2; ++t)
      for (int b = 0; b < 3 * kBalls; ++b)
        ASSERT_TRUE(acb_equal(&got[static_cast<std::size_t>(3 * t * kBalls + b)], &ref[static_cast<std::size_t>(b)]))
            << "thread " << t << ", output " << b % 3 << " of ball " << b / 3 << ", degree " << p.degree();
    EXPECT_EQ(shared.builds(), shared.cells());  // far below the cache's limit: nothing emptied
    // Two threads in the same order ask for the same cells at about the same
    // time: each is still built once (the second waits for the first).
    {
      const LocalPoly fresh(p);
      const LocalPoly fresh_copy = fresh;  // NOLINT: the copy is the point
      std::thread x(run_in, std::cref(fresh), 0, true), y(run_in, std::cref(fresh_copy), 1, true);
      x.join();
      y.join();
      EXPECT_EQ(fresh.builds(), fresh.cells()) << "degree " << p.degree();
      for (int t = 0; t < 2; ++t)
        for (int b = 0; b < 3 * kBalls; ++b)
          ASSERT_TRUE(acb_equal(&got[static_cast<std::size_t>(3 * t * kBalls + b)], &ref[static_cast<std::size_t>(b)]));
    }
    for (auto& v : got) acb_clear(&v);
    for (auto& v : ref) acb_clear(&v);
    for (auto& z : balls) acb_clear(&z);
  }
}

// A thread keeps the powers of the last w = z - c (the factors of a speed
// are evaluated at the same z, often on cells with the same centre): every
// evaluation must give what it gives alone on a fresh thread, whatever was
// evaluated before on its own thread (other polynomials, other balls,
// other precisions, fewer or more terms).
TEST(LocalPoly, SharedPowersGiveTheEnclosuresOfALoneEvaluation) {
  std::mt19937_64 rng(2311);
  for (long it = 0; it < iterations(3); ++it) {
    // p and q of the same degree share cell centres; r of another degree
    // has more or fewer terms on the same cells
    const long n = std::uniform_int_distribution<long>(20, 120)(rng);
    const LocalPoly p(random_poly(rng, n, 20)), q(random_poly(rng, n, 20)),
        r(random_poly(rng, std::uniform_int_distribution<long>(11, 160)(rng), 20));
    const LocalPoly* polys[3] = {&p, &q, &r};
    constexpr int kBalls = 40;
    const long precs[2] = {64, 200};
    // calls: (poly, ball, prec), in an order that reuses and invalidates the powers
    std::vector<std::array<int, 3>> calls;
    for (int b = 0; b < kBalls; ++b)
      for (int k : {0, 1, 2, 1})
        calls.push_back({k, b, static_cast<int>(std::uniform_int_distribution<int>(0, 1)(rng))});
    std::vector<acb_struct> balls(kBalls), got(3 * calls.size()), alone(3 * calls.size());
    for (auto& z : balls) {
      acb_init(&z);
      random_ball(&z, rng);
    }
    for (auto& v : got) acb_init(&v);
    for (auto& v : alone) acb_init(&v);
    auto call = [&](std::size_t i, acb_ptr o) {
      const auto& c = calls[i];
      polys[c[0]]->eval(o, o + 1, o + 2, &balls[static_cast<std::size_t>(c[1])], precs[c[2]]);
    };
    std::thread seq([&] {
      for (std::size_t i = 0; i < calls.size(); ++i) call(i, &got[3 * i]);
      flint_cleanup();
    });
    seq.join();
    for (std::size_t i = 0; i < calls.size(); ++i) {
      std::thread lone([&] {
        call(i, &alone[3 * i]);
        flint_cleanup();
      });
      lone.join();
      for (int j = 0; j < 3; ++j)
        ASSERT_TRUE(acb_equal(&got[3 * i + static_cast<std::size_t>(j)], &alone[3 * i + static_cast<std::size_t>(j)]))
            << "call " << i << " (polynomial " << calls[i][0] << ", ball " << calls[i][1] << ", precision "
            << precs[calls[i][2]] << "), output " << j;
    }
    for (auto& v : got) acb_clear(&v);
    for (auto& v : alone) acb_clear(&v);
    for (auto& z : balls) acb_clear(&z);
  }
}

// p has real coefficients: on a real ball its enclosures are real (an
// imaginary radius would make a square root of a positive quantity look as
// if it could cross its branch cut).
TEST(LocalPoly, RealBallsGiveRealEnclosures) {
  std::mt19937_64 rng(5);
  for (long it = 0; it < iterations(20); ++it) {
    const LocalPoly lp(random_test_poly(rng));
    for (int b = 0; b < 40; ++b) {
      acb_t z, v, d1, d2;
      for (acb_ptr x : {z, v, d1, d2}) acb_init(x);
      random_ball(z, rng);
      arb_zero(acb_imagref(z));
      lp.eval(v, d1, d2, z, 80);
      for (acb_srcptr x : {v, d1, d2}) ASSERT_TRUE(acb_is_real(x)) << "ball " << b << " of polynomial " << it;
      for (acb_ptr x : {z, v, d1, d2}) acb_clear(x);
    }
  }
}

// Wide balls with a real midpoint, of polynomials of degree <= 64 whose
// power basis loses few bits, are bounded by the centred form in double at
// their midpoint (DoubleCentredForm, tested on its own): on
// K (2^b t - a)^n around a 2^-b that bound is exact up to rounding, which
// the cells (a disc about twice the radius) are not. Balls where the form
// is refused (radius 2^-24 at the zero: rounding; radius up to 256:
// overflow) still get finite enclosures of the exact values.
TEST(LocalPoly, WideBallsOfLowDegreeGetTheCentredFormAtTheirMidpoint) {
  std::mt19937_64 rng(112327);
  std::uniform_real_distribution<double> unit(0, 1);
  for (long it = 0; it < iterations(60); ++it) {
    const test_support::PurePower c = test_support::random_pure_power(rng);
    const Poly& p = c.p;
    const LocalPoly lp(p);
    const double rx = c.m * (0.25 + 1.75 * unit(rng)), ry = rx * unit(rng);
    acb_t z, v, d1, d2;
    for (acb_ptr x : {z, v, d1, d2}) acb_init(x);
    acb_zero(z);
    arb_set_d(acb_realref(z), c.m);
    mag_set_d(arb_radref(acb_realref(z)), rx);
    mag_set_d(arb_radref(acb_imagref(z)), ry);
    const acb_struct* outs[3] = {v, d1, d2};
    lp.eval(v, d1, d2, z, 64);
    const std::string what = "of K (2^b t - a)^n, n = " + std::to_string(c.n);
    test_support::expect_pure_power_bounds(c, outs, z, rng, what);
    // refused: rounding near the zero, overflow at radius up to 256
    for (const double rr : {0x1p-24, 64 + 192 * unit(rng)}) {
      mag_set_d(arb_radref(acb_realref(z)), rr);
      mag_set_d(arb_radref(acb_imagref(z)), rr * unit(rng));
      lp.eval(v, d1, d2, z, 64);
      expect_encloses_at_points(p, outs, z, rng, "(refused) " + what);
      for (acb_srcptr o : {v, d1, d2}) EXPECT_TRUE(acb_is_finite(o)) << what;
    }
    for (acb_ptr x : {z, v, d1, d2}) acb_clear(x);
  }
}

}  // namespace
}  // namespace uniparam

namespace uniparam {
namespace {

/// The Taylor coefficients e_k of p at the double t (p(t + h) = sum e_k h^k),
/// exact (t is dyadic), then rounded to doubles.
std::vector<double> exact_taylor(const Poly& p, double t) {
  arb_poly_t e;
  arb_poly_init(e);
  arb_poly_set_fmpz_poly(e, p.get(), ARF_PREC_EXACT);
  arb_t tt;
  arb_init(tt);
  arb_set_d(tt, t);
  arb_poly_taylor_shift(e, e, tt, 4 * (p.degree() + 64) + p.max_bits());
  std::vector<double> out(static_cast<std::size_t>(arb_poly_length(e)));
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = arf_get_d(arb_midref(arb_poly_get_coeff_ptr(e, static_cast<slong>(k))), ARF_RND_NEAR);
  arb_clear(tt);
  arb_poly_clear(e);
  return out;
}

/// The scale of the j-th Taylor coefficient on a cell near t:
/// sum_{k >= j} C(k, j) |e_k| 2^-(k-j).
double local_scale(const std::vector<double>& e, int j) {
  double scale = 0, binom = 1;
  for (std::size_t k = static_cast<std::size_t>(j); k < e.size(); ++k) {
    scale += binom * std::fabs(e[k]) * std::ldexp(1.0, -static_cast<int>(k - static_cast<std::size_t>(j)));
    binom = binom * static_cast<double>(k + 1) / static_cast<double>(k + 1 - static_cast<std::size_t>(j));
  }
  return scale;
}

/// eval_double_taylor against the exact Taylor coefficients p^(j)(t) / j!
/// (p shifted to the double t exactly, then rounded): random polynomials
/// (Bernstein ones up to degree 160, whose power basis is useless in
/// double), t inside [0, 1] (local expansions) and outside (power basis).
/// The tolerance is 2^-40 of the coefficient's scale (inside: sum_k C(k, j)
/// |e_k| 2^-(k-j), which double arithmetic on a level-6 cell meets by far;
/// outside, that of the power basis' terms);
/// fails with an off-by-one in the passes or the shift's sign.
TEST(LocalPoly, DoubleTaylorCoefficientsMatchTheExactShift) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> in(0.0, 1.0), out(1.0, 1.25);
  for (long it = 0; it < iterations(30); ++it) {
    const Poly p = random_test_poly(rng);
    const LocalPoly lp(p);
    for (int k = 0; k < 6; ++k) {
      const double t = k < 5 ? in(rng) : out(rng);
      const int order = 1 + static_cast<int>(rng() % 8);
      std::vector<double> b(static_cast<std::size_t>(order + 1));
      lp.eval_double_taylor(t, order, b.data());
      // exact: p(t + h) = sum e_j h^j (t is a dyadic double)
      const std::vector<double> ex = exact_taylor(p, t);
      const long len = static_cast<long>(ex.size());
      auto ed = [&](long k) { return k < len ? ex[static_cast<std::size_t>(k)] : 0.0; };
      for (int j = 0; j <= order; ++j) {
        // Inside [0, 1]: the local expansion's scale near t. Outside: the
        // power basis is used (documented), so the scale of its terms,
        // sum_k C(k, j) |c_k| t^(k-j).
        double scale = 0, binom = 1;
        if (t <= 1) {
          scale = local_scale(ex, j);
        } else {
          for (long k = j; k <= p.degree(); ++k) {
            scale += binom * std::fabs(fmpz_get_d(p.get()->coeffs + k)) * std::pow(t, static_cast<double>(k - j));
            binom = binom * static_cast<double>(k + 1) / static_cast<double>(k + 1 - j);
          }
        }
        SCOPED_TRACE("degree " + std::to_string(p.degree()) + ", t = " + std::to_string(t) + ", j = " +
                     std::to_string(j));
        EXPECT_LE(std::fabs(b[static_cast<std::size_t>(j)] - ed(j)), std::ldexp(scale, -40) + 1e-300);
      }
    }
  }
  double b[17];
  EXPECT_THROW(LocalPoly(Poly(std::vector<long>{1, 2, 3})).eval_double_taylor(0.5, 16, b), InvalidArgument);
  EXPECT_THROW(LocalPoly(Poly(std::vector<long>{1, 2, 3})).eval_double_taylor(0.5, -1, b), InvalidArgument);
}

TEST(LocalPoly, DoubleValuesMatchTheExactValuesAtCellEndsAndInside) {
  // eval_double (uncertified, the optimisers' sigma^2) picks the cell of t
  // from t's double: at the ends k/64 of the point level's cells, one ulp
  // either side of them, and at random points, p, p', p'' agree with the
  // exact values to 2^-40 of the local expansion's scale.
  // Low degrees (3-16, small coefficients) too: there eval_double may take
  // Horner's rule on the power basis, whose error is bounded by the power
  // basis' scale sum_k C(k, j) |c_k| t^(k-j) instead.
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> in(0.0, 1.0);
  for (long it = 0; it < iterations(30); ++it) {
    const bool low = it % 3 == 2;
    const Poly p = low ? random_poly(rng, std::uniform_int_distribution<long>(3, 16)(rng), 20) : random_test_poly(rng);
    const LocalPoly lp(p);
    std::vector<double> ts{0.0, 1.0, in(rng), in(rng)};
    for (int k = 1; k < 64; k += 1 + static_cast<int>(rng() % 9)) {
      const double e = std::ldexp(static_cast<double>(k), -6);
      ts.insert(ts.end(), {e, std::nextafter(e, 0.0), std::nextafter(e, 1.0)});
    }
    for (double t : ts) {
      double v, d1, d2;
      lp.eval_double(t, &v, &d1, &d2);
      const std::vector<double> ex = exact_taylor(p, t);
      const double got[3] = {v, d1, d2 / 2};  // Taylor coefficients e_0, e_1, e_2
      for (int j = 0; j < 3; ++j) {
        const double want = static_cast<std::size_t>(j) < ex.size() ? ex[static_cast<std::size_t>(j)] : 0.0;
        SCOPED_TRACE("degree " + std::to_string(p.degree()) + ", t = " + std::to_string(t) + ", j = " +
                     std::to_string(j));
        double scale = local_scale(ex, j);
        if (low) {
          double power = 0, binom = 1;
          for (long k = j; k <= p.degree(); ++k) {
            power += binom * std::fabs(fmpz_get_d(p.get()->coeffs + k)) * std::pow(t, static_cast<double>(k - j));
            binom = binom * static_cast<double>(k + 1) / static_cast<double>(k + 1 - j);
          }
          scale = std::max(scale, power);
        }
        EXPECT_LE(std::fabs(got[j] - want), std::ldexp(scale, -40) + 1e-300);
      }
    }
  }
}

}  // namespace
}  // namespace uniparam
