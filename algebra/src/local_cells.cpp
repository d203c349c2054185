// local_cells.cpp -- the cache of local expansions behind LocalPoly
// (local_cells.hpp): cells built once, on demand, from an exact shift or
// their parent's expansion (local_expansion.hpp), and evaluation on balls.
#include "local_cells.hpp"

#include <arb_poly.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <future>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "uniparam/core/ball_regions.hpp"

namespace uniparam::detail {

namespace {

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
// Wide balls (is_wide_ball, radius >= 2^kCoarseBallLog2 = 2^-24: the
// quadrature's error bounds, whose enclosures are as wide as p's variation
// on them) use coarse cells, truncated at 2^-kCoarseBits of the cell's scale,
// the same 2^-24, instead of 2^-wp: far fewer
// terms, so far cheaper shifts and evaluations (rational space curves of
// degree 150: a quarter fewer instructions for the uniformity). Coarse cells of the
// exact levels are the fine ones truncated; deeper ones are ball shifts of
// their coarse parent, checked by accurate() as fine cells are.
constexpr long kCoarseBits = -kCoarseBallLog2;
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
// Distinct for every store ever made (point_cell's per-thread cache: a
// store's address may be reused by a later one).
std::atomic<std::uint64_t> g_next_store_uid{1};

struct CellStore {
  const std::uint64_t uid = g_next_store_uid.fetch_add(1, std::memory_order_relaxed);
  std::mutex mu;
  CellMap cells;
  std::unordered_map<CellKey, std::shared_future<CellPtr>, CellKeyHash> building;
  // variant i >= 0 expands p / (t - gamma_i), gamma_i enclosed by variants[i]
  std::vector<RootEnclosure> variants;
  std::size_t builds = 0;  // builds started (LocalCells::builds)
};

}  // namespace

struct LocalCells::Store : CellStore {};

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
      RootEnclosure enclosure;  // a copy, called outside the lock
      {
        std::lock_guard<std::mutex> lock(store.mu);
        enclosure = store.variants[static_cast<std::size_t>(variant)];
      }
      const Ball g = enclosure(wp + 32);
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

LocalCells::LocalCells() : store_(std::make_unique<Store>()) {}
LocalCells::~LocalCells() = default;

int LocalCells::add_variant(RootEnclosure enclosure) {
  std::lock_guard<std::mutex> lock(store_->mu);
  store_->variants.push_back(std::move(enclosure));
  return static_cast<int>(store_->variants.size()) - 1;
}

std::size_t LocalCells::cells() const {
  std::lock_guard<std::mutex> lock(store_->mu);
  return store_->cells.size();
}

std::size_t LocalCells::builds() const {
  std::lock_guard<std::mutex> lock(store_->mu);
  return store_->builds;
}

const Cell& LocalCells::point_cell(const Poly& p, double t) const {
  // 64 + guard bits: the same cells as a 64-bit certified evaluation.
  const long wp = (64 + kGuardBits + FLINT_BITS - 1) / FLINT_BITS * FLINT_BITS;
  const unsigned long long j = cell_index(t, kPointLevel);
  // The thread's recent cells, direct-mapped by store and index; each
  // entry holds its cell (a cell's content depends only on its key, so one
  // kept past the store's clearing is still right).
  struct Recent {
    std::uint64_t uid = 0;
    unsigned long long j = 0;
    CellPtr cell;
  };
  constexpr std::size_t kRecent = 32;
  thread_local std::array<Recent, kRecent> recent;
  Recent& r = recent[(j + store_->uid * 7) % kRecent];
  if (r.uid != store_->uid || r.j != j || !r.cell) {
    r.cell = get_cell(*store_, p, -1, wp, kPointLevel, j, false);
    r.uid = store_->uid;
    r.j = j;
  }
  return *r.cell;
}

bool LocalCells::eval(const Poly& p, int variant, acb_t v, acb_t d1, acb_t d2, const acb_t z, long prec) const {
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
      cell = get_cell(*store_, p, variant, wp, level, j, wide);
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

}  // namespace uniparam::detail
