#include "uniparam/algebra/local_poly.hpp"

#include <arb_poly.h>
#include <flint/fmpz_poly.h>

#include <algorithm>
#include <cmath>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "uniparam/algebra/deflation.hpp"
#include "uniparam/algebra/double_centred.hpp"
#include "uniparam/algebra/local_expansion.hpp"
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

// Radius of a complex ball: an upper bound of |t - mid z| over z.
void ball_radius(mag_t r, const acb_t z) { mag_hypot(r, arb_radref(acb_realref(z)), arb_radref(acb_imagref(z))); }

// Polynomials of at most this length are evaluated in the power basis: the
// cells cost more than they save (and low degrees lose little to
// cancellation).
constexpr long kMinLength = 3;
// Cells up to this level are computed by an exact integer Taylor shift;
// deeper ones from their parent's (truncated) expansion by a ball shift,
// O(K^2) at the working precision instead of O(n^2) on integers of about
// (level + 1) n bits. Up to kMaxExactLevel a ball-shifted cell that lost
// accuracy (accurate() below) is rebuilt exactly.
constexpr int kExactLevel = 3;
constexpr int kMaxExactLevel = 6;
// Finest level (cells of width 2^-40).
constexpr int kMaxLevel = 40;
// Level of the cells for narrow balls (quadrature nodes): 64 cells on [0, 1].
constexpr int kPointLevel = 6;
// Wide balls (radius >= 2^-24: the quadrature's error bounds, whose
// enclosures are as wide as p's variation on them) use coarse cells,
// truncated at 2^-kCoarseBits of the cell's scale instead of 2^-wp: far fewer
// terms, so far cheaper shifts and evaluations (rational space curves of
// degree 150: a quarter fewer instructions for the uniformity). Coarse cells of the
// exact levels are the fine ones truncated; deeper ones are ball shifts of
// their coarse parent, checked by accurate() as fine cells are.
constexpr long kCoarseBits = 24;
// Working precision of the coarse cells' shifts (one limb): their rounding
// must stay below 2^-kCoarseBits of the cell's scale after the bits a shift
// loses, which accurate() checks.
constexpr long kCoarsePrec = 64;
// The level that surely holds a wide ball assumes its midpoint anywhere in
// the cell; one level deeper is tried first (it holds a ball centred near
// its cell's centre, e.g. an ellipse around a dyadic subinterval): a disc
// about two thirds as large, so tighter bounds and fewer failed ellipses
// (bez-rat-space 150 uniformity: 266 quadrature steps instead of 328).
constexpr int kWideDeeper = 1;
// Extra bits of the cells' working precision over the caller's: deep cells
// are shifted from their parents, which costs a few bits per level.
constexpr long kGuardBits = 12;
// Bounded memory: the cache is emptied when it holds more cells.
constexpr std::size_t kMaxCells = 20000;

// Enclosures of p(z), and p'(z), p''(z) where d1, d2 are non-null, for a
// polynomial with ball coefficients p and its derivatives p1 = p', p2 = p''
// (the power-basis fallback). Narrow balls (radius < 2^-24) and lengths <= 2:
// Horner. Wide balls: the centred form at the exact midpoint m of z,
//     p^(j)(z) in j! c_j + sum_{k > j} k!/(k-j)! |c_k| r^(k-j) (unit disc),
// c_k = p^(k)(m)/k! by one Taylor shift (centred_shift).
void centred_eval(acb_t v, acb_t d1, acb_t d2, const BallPoly& p, const BallPoly& p1, const BallPoly& p2,
                  const acb_t z, long prec) {
  mag_t r;
  mag_init(r);
  ball_radius(r, z);
  // Narrow balls (the quadrature's nodes) and low degrees: Horner is tight.
  if (p.length() <= 2 || mag_cmp_2exp_si(r, -24) < 0) {
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

bool is_wide_ball(const acb_t z) {
  return mag_cmp_2exp_si(arb_radref(acb_realref(z)), -24) >= 0 || mag_cmp_2exp_si(arb_radref(acb_imagref(z)), -24) >= 0;
}

// ---------------------------------------------------------------------------

namespace {

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

struct CellKey {
  long prec;
  int level;
  int variant;
  unsigned long long j;
  bool coarse;
  bool operator==(const CellKey& o) const {
    return prec == o.prec && level == o.level && variant == o.variant && j == o.j && coarse == o.coarse;
  }
};
struct CellKeyHash {
  std::size_t operator()(const CellKey& k) const {
    return std::hash<unsigned long long>()(k.j * 1000003ULL ^ static_cast<unsigned long long>(k.level) * 7919ULL ^
                                           static_cast<unsigned long long>(k.prec) * 104729ULL ^
                                           static_cast<unsigned long long>(k.variant + 1) * 15485863ULL ^
                                           static_cast<unsigned long long>(k.coarse));
  }
};

// Drops the high terms of the cell's expansion whose contribution to p,
// p', p'' on |w| <= 2h is below 2^-wp times the scale sum |c_k| h^k of p
// on the cell (truncate_local_expansion), adding their bound to the tails.
void truncate(LocalExpansion& e, long wp) {
  if (arb_poly_length(e.P) <= 3) return;
  const long log2h = -(e.level + 1);
  mag_t scale, eps;
  mag_init(scale);
  mag_init(eps);
  local_expansion_variation(scale, nullptr, e, log2h);
  arb_get_mag(eps, e.P->coeffs);
  mag_add(scale, scale, eps);
  mag_mul_2exp_si(eps, scale, -wp);
  truncate_local_expansion(e, log2h + 1, eps, 3);
  mag_clear(scale);
  mag_clear(eps);
}

// True when a ball-shifted cell kept its accuracy: the error of its
// expansion on the disc |w| <= 2h, sum rad(c_k) (2h)^k + tail, is at most
// 2^-(wp - kGuardBits) times its scale sum |c_k| h^k (wp - kGuardBits is at
// least the caller's precision). It fails where p is much larger on the
// parent's disc than on this cell (near a cluster of p's zeros).
bool accurate(const LocalExpansion& cell, long wp) {
  const slong n = arb_poly_length(cell.P);
  mag_t h, rho, hk, rk, a, scale, err;
  for (mag_struct* m : {h, rho, hk, rk, a, scale, err}) mag_init(m);
  mag_one(h);
  mag_mul_2exp_si(h, h, -(cell.level + 1));
  mag_mul_2exp_si(rho, h, 1);
  mag_one(hk);
  mag_one(rk);
  mag_set(err, cell.tail + 0);
  for (slong k = 0; k < n; ++k) {
    arf_get_mag(a, arb_midref(cell.P->coeffs + k));
    mag_mul(a, a, hk);
    mag_add(scale, scale, a);
    mag_mul(a, arb_radref(cell.P->coeffs + k), rk);
    mag_add(err, err, a);
    mag_mul(hk, hk, h);
    mag_mul(rk, rk, rho);
  }
  mag_mul_2exp_si(scale, scale, -(wp - kGuardBits));
  const bool ok = !mag_is_zero(scale) && mag_cmp(err, scale) <= 0;
  for (mag_struct* m : {h, rho, hk, rk, a, scale, err}) mag_clear(m);
  return ok;
}

using CellPtr = std::shared_ptr<const Cell>;
using CellMap = std::unordered_map<CellKey, CellPtr, CellKeyHash>;

// A vector of Arb balls that only grows (no allocation per evaluation).
template <typename Ptr, Ptr (*Init)(slong), void (*Clear)(Ptr, slong)>
struct Growing {
  Ptr v = nullptr;
  slong cap = 0;
  Growing() = default;
  Growing(const Growing&) = delete;
  Growing& operator=(const Growing&) = delete;
  ~Growing() {
    if (v) Clear(v, cap);
  }
  Ptr at_least(slong n) {
    if (n > cap) {
      if (v) Clear(v, cap);
      cap = std::max(n, 2 * cap);
      v = Init(cap);
    }
    return v;
  }
};

// Scratch for the powers of w, one per thread. The powers of the last w
// (and precision) are kept: a speed evaluates all its factors at the same
// z, and factors of similar degree use cells with the same centre at the
// same level (the level depends on z alone), so they share w = z - c and
// its powers (7.5% of a degree-150 rational space curve's radical,
// one thread). Reused powers are the ones recomputing would give (the same
// products of the same balls at the same precision), so results do not
// change.
template <typename Ptr, Ptr (*Init)(slong), void (*Clear)(Ptr, slong), typename Ball, void (*BallInit)(Ball*),
          void (*BallClear)(Ball*), int (*Equal)(const Ball*, const Ball*), void (*Set)(Ball*, const Ball*),
          void (*One)(Ball*), void (*Mul)(Ball*, const Ball*, const Ball*, slong)>
struct PowerMemo {
  Growing<Ptr, Init, Clear> pw;
  Ball w;           // the ball whose powers pw holds
  long prec = 0;    // their precision
  slong valid = 0;  // pw[0..valid) = w^0..w^(valid-1)
  PowerMemo() { BallInit(&w); }
  PowerMemo(const PowerMemo&) = delete;
  PowerMemo& operator=(const PowerMemo&) = delete;
  ~PowerMemo() { BallClear(&w); }
  /// w^0, ..., w^(n-1) at precision p (n >= 1).
  Ptr powers(const Ball* x, slong n, long p) {
    if (n > pw.cap) valid = 0;  // at_least reallocates
    Ptr v = pw.at_least(n);
    if (valid == 0 || p != prec || !Equal(&w, x)) {
      Set(&w, x);
      prec = p;
      One(v);
      valid = 1;
    }
    for (; valid < n; ++valid) Mul(v + valid, v + valid - 1, &w, p);
    return v;
  }
};

struct Scratch {
  PowerMemo<arb_ptr, _arb_vec_init, _arb_vec_clear, arb_struct, arb_init, arb_clear, arb_equal, arb_set, arb_one,
            arb_mul>
      real;
  PowerMemo<acb_ptr, _acb_vec_init, _acb_vec_clear, acb_struct, acb_init, acb_clear, acb_equal, acb_set, acb_one,
            acb_mul>
      complex;
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// The cells of one polynomial, shared by a LocalPoly and its copies (threads
// included). `mu` guards every member. A cell is built outside the lock by
// the first thread that asks for it, once: its key is in `building` until it
// is in `cells`, and other threads asking for it wait for that build (in
// parallel phases, two workers often need the same cell at once; building it
// twice repeated its exact shift). Waiting cannot deadlock: a build waits
// only on cells of a lower level or, for a coarse cell, the fine cell of the
// same key, so the waits follow a well-founded order.
struct CellStore {
  std::mutex mu;
  CellMap cells;
  std::unordered_map<CellKey, std::shared_future<CellPtr>, CellKeyHash> building;
  // variant i >= 0 expands p / (t - roots[i].value); value lies in
  // [mid - rad, mid + rad] (doubles, for DoubleCentredForm::eval_deflated)
  struct Root {
    RealAlgebraic value;
    double mid, rad;
  };
  std::vector<Root> roots;
  std::size_t builds = 0;            // builds started (LocalPoly::builds)
};

}  // namespace

struct LocalPoly::Cache {
  CellStore store;  // store.mu also guards `deflated`
  // fallback for p / (t - roots[i]): the deflated power basis, per (i, prec)
  std::map<std::pair<int, long>, std::shared_ptr<const BallPoly>> deflated;
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

LocalPoly::LocalPoly() : cache_(std::make_shared<Cache>()) {}
LocalPoly::LocalPoly(const Poly& p)
    : p_(p), b_(p), b1_(p.derivative()), b2_(p.derivative().derivative()), cache_(std::make_shared<Cache>()) {
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

std::size_t LocalPoly::cells() const {
  if (!cache_) return 0;  // moved from
  std::lock_guard<std::mutex> lock(cache_->store.mu);
  return cache_->store.cells.size();
}

std::size_t LocalPoly::builds() const {
  if (!cache_) return 0;  // moved from
  std::lock_guard<std::mutex> lock(cache_->store.mu);
  return cache_->store.builds;
}

namespace {

// A cell's centre is its parent's plus child_side(j) 2^-(level+1): the odd
// index is the right half.
int child_side(unsigned long long j) { return (j & 1) ? 1 : -1; }

CellPtr get_cell(CellStore& store, const Poly& p, int variant, long wp, int level, unsigned long long j, bool coarse);

// Builds the cell `key` of p (see get_cell); does not store it.
CellPtr build_cell(CellStore& store, const Poly& p, const CellKey& key) {
  const int variant = key.variant;
  const long wp = key.prec;
  const int level = key.level;
  const unsigned long long j = key.j;
  const bool coarse = key.coarse;
  auto cell = std::make_shared<Cell>();
  LocalExpansion& e = cell->e;
  if (coarse) {
    // Truncated at kCoarseBits: a ball shift of the coarse parent (few
    // terms), or, at the exact levels and where that shift lost accuracy
    // (checked up to kMaxExactLevel, as for fine cells: deeper, the
    // rebuild costs more than the looser bounds), the fine cell truncated.
    bool built = false;
    if (level > kExactLevel) {
      const CellPtr parent = get_cell(store, p, variant, wp, level - 1, j >> 1, true);
      local_expansion_child(e, parent->e, child_side(j), kCoarsePrec);
      truncate(e, kCoarseBits);
      built = level > kMaxExactLevel || accurate(e, kCoarseBits + kGuardBits);
    }
    if (!built) {
      const CellPtr fine = get_cell(store, p, variant, wp, level, j, false);
      e.level = level;
      e.j = j;
      arf_set(e.centre, fine->e.centre);
      arb_poly_set_round(e.P, fine->e.P, kCoarsePrec);
      for (int t = 0; t < 3; ++t) mag_set(e.tail + t, fine->e.tail + t);
      truncate(e, kCoarseBits);
    }
    arb_poly_derivative(cell->P1, e.P, kCoarsePrec);
    arb_poly_derivative(cell->P2, cell->P1, kCoarsePrec);
    return cell;
  }
  bool built = false;
  if (level > kExactLevel) {
    // From the parent: its disc |t - c_p| <= 2 h_p holds this cell's disc
    // |t - c| <= 2h = h_p (|c - c_p| = h_p / 2), so its tail bounds hold here.
    const CellPtr parent = get_cell(store, p, variant, wp, level - 1, j >> 1, false);
    local_expansion_child(e, parent->e, child_side(j), wp);
    truncate(e, wp);
    // p may be far larger on the parent's disc than on this cell's: then the
    // parent's rounding and tail swamp p here, and up to kMaxExactLevel the
    // cell is rebuilt by an exact shift instead.
    built = level > kMaxExactLevel || accurate(e, wp);
  }
  if (!built) {
    // An exact integer Taylor shift; for p / (t - gamma), deflated in the
    // local basis by an enclosure of gamma.
    local_expansion_exact(e, p, level, j, wp);
    if (variant >= 0) {
      std::unique_ptr<RealAlgebraic> root;
      {
        std::lock_guard<std::mutex> lock(store.mu);
        root = std::make_unique<RealAlgebraic>(store.roots[static_cast<std::size_t>(variant)].value);
      }
      const Ball g = root->to_ball(wp + 32);
      deflate_local_expansion(e, g.get(), wp);
    }
    truncate(e, wp);
  }
  arb_poly_derivative(cell->P1, e.P, wp);
  arb_poly_derivative(cell->P2, cell->P1, wp);
  const slong len = arb_poly_length(e.P);
  cell->mid.resize(static_cast<std::size_t>(len));
  for (slong k = 0; k < len; ++k)
    cell->mid[static_cast<std::size_t>(k)] = arf_get_d(arb_midref(e.P->coeffs + k), ARF_RND_NEAR);
  return cell;
}

// The cell (level, j) of variant `variant` (-1: p; i >= 0: p / (t - roots[i]))
// at working precision wp, built on demand, once (see CellStore).
// Thread-safe. An exception in the build reaches every thread waiting for it
// and the key is freed, so a later call tries again.
CellPtr get_cell(CellStore& store, const Poly& p, int variant, long wp, int level, unsigned long long j, bool coarse) {
  const CellKey key{wp, level, variant, j, coarse};
  // Made only when this thread builds the cell: a promise allocates its
  // shared state, and most calls find the cell stored.
  std::optional<std::promise<CellPtr>> promise;
  {
    std::unique_lock<std::mutex> lock(store.mu);
    auto it = store.cells.find(key);
    if (it != store.cells.end()) return it->second;
    auto b = store.building.find(key);
    if (b != store.building.end()) {
      const std::shared_future<CellPtr> pending = b->second;
      lock.unlock();
      return pending.get();
    }
    promise.emplace();
    store.building.emplace(key, promise->get_future().share());
    ++store.builds;
  }
  CellPtr cell;
  try {
    cell = build_cell(store, p, key);
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(store.mu);
      store.building.erase(key);
    }
    promise->set_exception(std::current_exception());
    throw;
  }
  {
    std::lock_guard<std::mutex> lock(store.mu);
    if (store.cells.size() >= kMaxCells) store.cells.clear();  // bounded memory: start again (holders keep theirs)
    store.cells.emplace(key, cell);
    store.building.erase(key);
  }
  promise->set_value(cell);
  return cell;
}

// True when the ball z lies in the disc |t - c| <= 2h of the cell of level
// `level` centred at c; w = z - c.
bool in_disc(acb_t w, const arf_t centre, int level, const acb_t z, long prec) {
  acb_set(w, z);
  arb_sub_arf(acb_realref(w), acb_realref(z), centre, prec);
  mag_t m;
  mag_init(m);
  acb_get_mag(m, w);
  const bool ok = mag_is_finite(m) && mag_cmp_2exp_si(m, -level) <= 0;
  mag_clear(m);
  return ok;
}

// Index of the level-l cell whose closure holds x (clamped to [0, 1]).
// Exact from x rounded down to a double d: every cell end k 2^-l <= x
// (k < 2^53) is a double, so d >= k 2^-l too and floor(d 2^l) = floor(x 2^l).
unsigned long long cell_index(double d, int level) {
  const unsigned long long cells = 1ULL << level;
  if (!(d > 0)) return 0;
  const double y = std::floor(std::ldexp(d, level));
  return y < static_cast<double>(cells - 1) ? static_cast<unsigned long long>(y) : cells - 1;
}

unsigned long long cell_index(const arf_t x, int level) { return cell_index(arf_get_d(x, ARF_RND_FLOOR), level); }

}  // namespace

bool LocalPoly::eval_cells(int variant, acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const {
  Cache& cache = *cache_;
  // Cells are shared by every caller whose precision rounds to the same
  // number of limbs (the quadrature's attempts, the optimiser, ...).
  const long wp = (prec + kGuardBits + FLINT_BITS - 1) / FLINT_BITS * FLINT_BITS;
  acb_t w;
  acb_init(w);
  const bool wide = is_wide_ball(z);
  CellPtr cell;
  // The cell depends on z alone (never on what was evaluated before), so
  // results do not depend on the order of evaluations or on threads.
  int level = kPointLevel;
  if (wide) {
    // The deepest level whose disc |t - c| <= 2h holds z for any c within h
    // of Re(mid z): h = 2^-(level+1) >= rad(z) + |Im(mid z)| =: s; as
    // s < 2^e with e = MAG_EXP(s), level = -e - 1 will do.
    mag_t s;
    mag_init(s);
    ball_radius(s, z);
    mag_t im;
    mag_init(im);
    arf_get_mag(im, arb_midref(acb_imagref(z)));
    mag_add(s, s, im);
    mag_clear(im);
    const long lv = mag_is_zero(s) ? kMaxLevel : -fmpz_get_si(MAG_EXPREF(s)) - 1;
    mag_clear(s);
    level = static_cast<int>(std::min<long>(std::max<long>(lv, 0), kMaxLevel));
  }
  arf_t centre;
  arf_init(centre);
  for (level = wide ? std::min(level + kWideDeeper, kMaxLevel) : level; level >= 0 && !cell; --level) {
    const unsigned long long j = cell_index(arb_midref(acb_realref(z)), level);
    arf_set_ui(centre, 2 * j + 1);
    arf_mul_2exp_si(centre, centre, -(level + 1));
    if (in_disc(w, centre, level, z, prec))
      cell = get_cell(cache.store, p_, variant, wp, level, j, wide);
  }
  arf_clear(centre);
  if (!cell) {
    acb_clear(w);
    return false;
  }
  // sum c_k w^k with w = z - c, plus the tails: the powers of w once, then
  // one dot product per output (Arb's arb_dot: no intermediate rounding).
  // On a wide ball this bounds p by its expansion on the disc
  // |t - c| <= |mid z - c| + rad z, at most twice z's radius: a little
  // looser than a centred form at mid z, and O(K) instead of an O(K^2) shift.
  const arb_poly_struct* polys[3] = {cell->e.P, cell->P1, cell->P2};
  acb_ptr outs[3] = {v, d1, d2};
  const slong K = std::max<slong>(arb_poly_length(cell->e.P), 1);
  if (acb_is_real(w)) {
    arb_srcptr pw = scratch().real.powers(acb_realref(w), K, prec);
    for (int j = 0; j <= 2; ++j) {
      if (!outs[j]) continue;
      arb_dot(acb_realref(outs[j]), nullptr, 0, polys[j]->coeffs, 1, pw, 1, arb_poly_length(polys[j]), prec);
      arb_zero(acb_imagref(outs[j]));
      // p is real on real balls: the tail widens the real part only
      arb_add_error_mag(acb_realref(outs[j]), cell->e.tail + j);
    }
  } else {
    acb_srcptr pw = scratch().complex.powers(w, K, prec);
    // real coefficients: real and imaginary parts are two real dot products
    // over the interleaved parts of the powers (stride 2)
    arb_srcptr parts = reinterpret_cast<arb_srcptr>(pw);
    for (int j = 0; j <= 2; ++j) {
      if (!outs[j]) continue;
      const slong len = arb_poly_length(polys[j]);
      arb_dot(acb_realref(outs[j]), nullptr, 0, polys[j]->coeffs, 1, parts, 2, len, prec);
      arb_dot(acb_imagref(outs[j]), nullptr, 0, polys[j]->coeffs, 1, parts + 1, 2, len, prec);
      acb_add_error_mag(outs[j], cell->e.tail + j);
    }
  }
  acb_clear(w);
  return true;
}

void LocalPoly::eval_double(double t, double* v, double* d1, double* d2) const {
  double c[3] = {0, 0, 0};
  const long n = p_.degree();
  if (n + 1 <= kMinLength || cache_->double_horner || !(t >= 0 && t <= 1)) {
    for (long k = n; k >= 0; --k) {  // Horner with two derivatives
      c[2] = c[2] * t + c[1];
      c[1] = c[1] * t + c[0];
      c[0] = c[0] * t + fmpz_get_d(p_.get()->coeffs + k);
    }
    c[2] *= 2;
  } else {
    Cache& cache = *cache_;
    // 64 + guard bits: the same cells as a 64-bit certified evaluation.
    const long wp = (64 + kGuardBits + FLINT_BITS - 1) / FLINT_BITS * FLINT_BITS;
    const CellPtr cp = get_cell(cache.store, p_, -1, wp, kPointLevel, cell_index(t, kPointLevel), false);
    const Cell& cell = *cp;
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
  std::vector<double> a;  // coefficients in w around a centre, then shifted by w
  double w = t;
  const long n = p_.degree();
  if (n + 1 <= kMinLength || !(t >= 0 && t <= 1)) {
    for (long k = 0; k <= n; ++k) a.push_back(fmpz_get_d(p_.get()->coeffs + k));
  } else {
    Cache& cache = *cache_;
    const long wp = (64 + kGuardBits + FLINT_BITS - 1) / FLINT_BITS * FLINT_BITS;  // eval_double's cells
    arf_t x;
    arf_init(x);
    arf_set_d(x, t);
    const CellPtr cp = get_cell(cache.store, p_, -1, wp, kPointLevel, cell_index(x, kPointLevel), false);
    arf_clear(x);
    a = cp->mid;
    w = t - arf_get_d(cp->e.centre, ARF_RND_NEAR);
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

void LocalPoly::eval(acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const {
  if (p_.degree() + 1 <= kMinLength || !acb_is_finite(z)) {
    centred_eval(v, d1, d2, b_, b1_, b2_, z, prec);
    return;
  }
  // Wide balls of low degree: the centred form in double, cheaper than a
  // cell's build and centred at the ball's own midpoint.
  if (cache_->centred.usable() && is_wide_ball(z) && cache_->centred.eval(v, d1, d2, z, kDoubleCentredMaxError))
    return;
  if (!eval_cells(-1, v, d1, d2, z, prec)) centred_eval(v, d1, d2, b_, b1_, b2_, z, prec);
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
    std::lock_guard<std::mutex> lock(cache.store.mu);
    for (std::size_t i = 0; i < cache.store.roots.size(); ++i)
      if (cache.store.roots[i].value == gamma) variant = static_cast<int>(i);
    if (variant >= 0) {
      g_mid = cache.store.roots[static_cast<std::size_t>(variant)].mid;
      g_rad = cache.store.roots[static_cast<std::size_t>(variant)].rad;
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
    std::lock_guard<std::mutex> lock(cache.store.mu);
    for (std::size_t i = 0; i < cache.store.roots.size() && variant < 0; ++i)  // another thread may have added it
      if (cache.store.roots[i].value == gamma) variant = static_cast<int>(i);
    if (variant < 0) {
      cache.store.roots.push_back({gamma, g_mid, g_rad});
      variant = static_cast<int>(cache.store.roots.size()) - 1;
    }
  }
  // Wide balls of low degree: the centred form of the quotient in double.
  if (cache.centred.usable() && is_wide_ball(z) && acb_is_finite(z) &&
      cache.centred.eval_deflated(v, z, g_mid, g_rad, kDoubleCentredMaxError))
    return;
  if (p_.degree() + 1 > kMinLength && acb_is_finite(z) && eval_cells(variant, v, nullptr, nullptr, z, prec)) return;
  // Low degree, or far from [0, 1]: the deflated power basis (exact
  // synthetic division in Z[gamma], see deflate), centred form.
  const auto key = std::make_pair(variant, prec);
  std::shared_ptr<const BallPoly> q;
  {
    std::lock_guard<std::mutex> lock(cache.store.mu);
    auto it = cache.deflated.find(key);
    if (it != cache.deflated.end()) q = it->second;
  }
  if (!q) {
    q = std::make_shared<const BallPoly>(deflate(p_, gamma, 1, prec + 16));
    std::lock_guard<std::mutex> lock(cache.store.mu);
    if (cache.deflated.size() > 64) cache.deflated.clear();
    cache.deflated.emplace(key, q);
  }
  centred_eval(v, nullptr, nullptr, *q, *q, *q, z, prec);
}

}  // namespace uniparam
