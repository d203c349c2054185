// The pieces of uniformity, radical and reparam --pieces run on worker
// threads (core/parallel.hpp). With UNIPARAM_THREADS=1 and 3 the results
// must be the same numbers: every pair of balls overlaps and both meet the
// requested digits, on random curves of degree 8 to 24 (a race between
// workers would corrupt a value). Bit-for-bit equality is not promised:
// Arb caches its Gauss-Legendre nodes per thread at the highest precision
// asked so far, so the last bits of a radius depend on the thread's history.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

namespace uniparam {
namespace {

using test_support::iterations;
using test_support::random_poly;

bool same(const Ball& a, const Ball& b) {
  return arb_overlaps(a.get(), b.get()) && a.meets_digits(20) && b.meets_digits(20);
}

struct ThreadsEnv {
  explicit ThreadsEnv(const char* n) { setenv("UNIPARAM_THREADS", n, 1); }
  ~ThreadsEnv() { unsetenv("UNIPARAM_THREADS"); }
};

TEST(Threads, ResultsAgreeForAnyNumberOfThreads) {
  std::mt19937_64 rng(314);
  Options o;
  o.digits = 20;
  for (long it = 0; it < iterations(4); ++it) {
    const long d = std::uniform_int_distribution<long>(8, 24)(rng);
    const Curve c({RatFunc(random_poly(rng, d, 30)), RatFunc(random_poly(rng, d, 30))});
    UniformityResult u1, u3;
    RadicalResult r1, r3;
    MoebiusResult m1, m3;
    {
      ThreadsEnv env("1");
      u1 = uniformity(c, SpeedKind::Angular, o);
      r1 = radical(c, SpeedKind::Angular, o);
      m1 = reparam_c0(c, SpeedKind::Parametric, 4, o);
    }
    {
      ThreadsEnv env("3");
      u3 = uniformity(c, SpeedKind::Angular, o);
      r3 = radical(c, SpeedKind::Angular, o);
      m3 = reparam_c0(c, SpeedKind::Parametric, 4, o);
    }
    EXPECT_TRUE(same(u1.mu, u3.mu) && same(u1.mean_square, u3.mean_square) && same(u1.u, u3.u)) << c.str();
    ASSERT_EQ(r1.integrals.size(), r3.integrals.size());
    for (std::size_t i = 0; i < r1.integrals.size(); ++i)
      EXPECT_TRUE(same(r1.integrals[i].A, r3.integrals[i].A) && same(r1.integrals[i].B, r3.integrals[i].B) &&
                  same(r1.integrals[i].C, r3.integrals[i].C))
          << "piece " << i << " of " << c.str();
    EXPECT_TRUE(same(r1.u_after, r3.u_after));
    EXPECT_TRUE(same(m1.u_after, m3.u_after)) << c.str();
  }
}

TEST(Threads, BatchedPieceIntegralsAreThoseOfEachListAlone) {
  // all_piece_integrals over two lists at once (one parallel loop over every
  // piece, 2 workers) against each piece computed alone on one thread: a
  // task mapped to the wrong list or piece, or a race, gives balls that do
  // not overlap (the lists differ, so do their pieces).
  std::mt19937_64 rng(2718);
  for (long it = 0; it < iterations(3); ++it) {
    const long d = std::uniform_int_distribution<long>(6, 14)(rng);
    const Curve c({RatFunc(random_poly(rng, d, 30)), RatFunc(random_poly(rng, d, 30))});
    const Speed s(c, SpeedKind::Parametric);
    auto random_list = [&](int n) {
      std::vector<Breakpoint> T{Breakpoint{RealAlgebraic(0)}};
      long num = 0;
      const long den = 97;
      for (int i = 1; i < n; ++i) {
        num = std::uniform_int_distribution<long>(num + 1, den - (n - i))(rng);
        T.push_back(Breakpoint{RealAlgebraic(Rational(num, den))});
      }
      T.push_back(Breakpoint{RealAlgebraic(1)});
      return T;
    };
    const std::vector<PieceJob> jobs{PieceJob{random_list(3), 70}, PieceJob{random_list(4), 40}};
    std::vector<std::vector<PieceIntegrals>> batch;
    {
      ThreadsEnv env("2");
      batch = all_piece_integrals(s, jobs, 4096);
    }
    ThreadsEnv env("1");
    ASSERT_EQ(batch.size(), 2u);
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      ASSERT_EQ(batch[k].size(), jobs[k].T.size() - 1);
      const long digits = jobs[k].rel_goal_bits * 3 / 10 - 2;  // what the goal in bits gives, in digits
      for (std::size_t i = 0; i + 1 < jobs[k].T.size(); ++i) {
        const PieceIntegrals alone = piece_integrals(s, jobs[k].T[i], jobs[k].T[i + 1], jobs[k].rel_goal_bits, 4096);
        const PieceIntegrals& b = batch[k][i];
        for (const auto& [x, y] : {std::pair<const Ball*, const Ball*>{&b.A, &alone.A}, {&b.B, &alone.B},
                                   {&b.C, &alone.C}, {&b.M, &alone.M}}) {
          EXPECT_TRUE(arb_overlaps(x->get(), y->get())) << "list " << k << " piece " << i << ": " << x->str(20)
                                                         << " vs " << y->str(20) << " on " << c.str();
          EXPECT_TRUE(x->meets_digits(digits)) << x->str(30);
        }
      }
    }
  }
}

}  // namespace
}  // namespace uniparam
