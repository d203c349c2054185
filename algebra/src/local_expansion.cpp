// local_expansion.cpp -- truncated local Taylor expansions at dyadic cell
// centres (local_expansion.hpp): exact builds, child shifts, truncation with
// tail bounds, deflation by a root.
#include "uniparam/algebra/local_expansion.hpp"

#include <flint/fmpz_poly.h>

#include <string>

#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

LocalExpansion::LocalExpansion() {
  arf_init(centre);
  arb_poly_init(P);
  for (auto& t : tail) mag_init(&t);
}

LocalExpansion::~LocalExpansion() {
  arf_clear(centre);
  arb_poly_clear(P);
  for (auto& t : tail) mag_clear(&t);
}

namespace {

void check_cell(int level, unsigned long long j) {
  if (level < 0 || level > kMaxExpansionLevel || j >= (1ULL << level))
    throw InvalidArgument("local expansion: no dyadic cell (" + std::to_string(level) + ", " + std::to_string(j) +
                          ") of [0, 1]");
}

void set_cell(LocalExpansion& e, int level, unsigned long long j) {
  e.level = level;
  e.j = j;
  // centre = (2j + 1) 2^-(level+1)
  arf_set_ui(e.centre, 2 * j + 1);
  arf_mul_2exp_si(e.centre, e.centre, -(level + 1));
}

}  // namespace

Poly local_shift_exact(const Poly& G, int level, unsigned long long j) {
  check_cell(level, j);
  const long n = G.degree();
  Poly s;
  if (n < 0) return s;
  // q(x) = 2^(L n) G(x / 2^L), shifted by J = 2j + 1
  const long L = level + 1;
  Poly q(G);
  fmpz* c = q.get()->coeffs;
  for (long k = 0; k <= n; ++k) fmpz_mul_2exp(c + k, c + k, static_cast<ulong>(L * (n - k)));
  fmpz_t J;
  fmpz_init_set_ui(J, 2 * j + 1);
  fmpz_poly_taylor_shift(s.get(), q.get(), J);
  fmpz_clear(J);
  return s;
}

void set_local_expansion(LocalExpansion& e, const Poly& s, long n, int level, unsigned long long j, long wp) {
  check_cell(level, j);
  set_cell(e, level, j);
  for (auto& t : e.tail) mag_zero(&t);
  const long L = level + 1;
  const slong len = fmpz_poly_length(s.get());
  arb_poly_fit_length(e.P, len);
  for (slong k = 0; k < len; ++k) {
    arb_set_round_fmpz(e.P->coeffs + k, s.get()->coeffs + k, wp);
    arb_mul_2exp_si(e.P->coeffs + k, e.P->coeffs + k, L * (k - n));
  }
  _arb_poly_set_length(e.P, len);
  _arb_poly_normalise(e.P);
}

void local_expansion_exact(LocalExpansion& e, const Poly& G, int level, unsigned long long j, long wp) {
  set_local_expansion(e, local_shift_exact(G, level, j), G.degree(), level, j, wp);
}

void local_expansion_child(LocalExpansion& child, const LocalExpansion& parent, int side, long wp) {
  if (side != 1 && side != -1) throw InvalidArgument("local_expansion_child: the side must be +1 or -1");
  const int level = parent.level + 1;
  const unsigned long long j = 2 * parent.j + (side > 0 ? 1 : 0);
  check_cell(level, j);
  set_cell(child, level, j);
  arb_poly_set_round(child.P, parent.P, wp);
  taylor_shift_pow2(child.P, child.P, -(level + 1), side, wp);
  for (int t = 0; t < 3; ++t) mag_set(child.tail + t, parent.tail + t);
}

void truncate_local_expansion(LocalExpansion& e, long log2_rho, const mag_t eps, int orders) {
  if (orders != 2 && orders != 3) throw InvalidArgument("truncate_local_expansion: orders must be 2 or 3");
  const slong n = arb_poly_length(e.P);
  if (n <= orders) return;
  // Suffix sums from the top: t[i] = sum_{k >= K} k!/(k-i)! |c_k| rho^(k-i);
  // K is lowered while every t[i] rho^i stays at most eps. The powers of
  // rho are exact scalings.
  mag_t t[3], nt[3], a, m, c;
  for (int i = 0; i < 3; ++i) {
    mag_init(t[i]);
    mag_init(nt[i]);
  }
  mag_init(a);
  mag_init(m);
  mag_init(c);
  slong K = n;
  for (slong k = n - 1; k >= orders; --k) {
    arb_get_mag(a, e.P->coeffs + k);
    bool keep = false;
    for (int i = 0; i < orders && !keep; ++i) {
      mag_mul_2exp_si(m, a, log2_rho * (k - i));
      if (i > 0) mag_mul_ui(m, m, static_cast<ulong>(i == 1 ? k : k * (k - 1)));
      mag_add(nt[i], t[i], m);
      mag_mul_2exp_si(c, nt[i], log2_rho * i);
      keep = mag_cmp(c, eps) > 0;
    }
    if (keep) break;
    for (int i = 0; i < orders; ++i) mag_swap(t[i], nt[i]);
    K = k;
  }
  if (K < n) {
    arb_poly_truncate(e.P, K);
    for (int i = 0; i < orders; ++i) mag_add(e.tail + i, e.tail + i, t[i]);
  }
  for (int i = 0; i < 3; ++i) {
    mag_clear(t[i]);
    mag_clear(nt[i]);
  }
  mag_clear(a);
  mag_clear(m);
  mag_clear(c);
}

void local_expansion_variation(mag_t var0, mag_t var1, const LocalExpansion& e, long log2_r) {
  mag_zero(var0);
  if (var1) mag_zero(var1);
  mag_t a, b;
  mag_init(a);
  mag_init(b);
  const slong n = arb_poly_length(e.P);
  for (slong k = 1; k < n; ++k) {
    arb_get_mag(a, e.P->coeffs + k);
    mag_mul_2exp_si(a, a, log2_r * (k - 1));
    if (var1 && k >= 2) {
      mag_mul_ui(b, a, static_cast<ulong>(k));
      mag_add(var1, var1, b);
    }
    mag_mul_2exp_si(a, a, log2_r);
    mag_add(var0, var0, a);
  }
  mag_clear(a);
  mag_clear(b);
}

void deflate_local_expansion(LocalExpansion& e, const arb_t gamma, long wp) {
  const slong len = arb_poly_length(e.P);
  if (len == 0) return;
  // P(w) = (w - w_g) Q(w) with w_g = gamma - c: synthetic division from the
  // top; the remainder (exactly 0) is dropped.
  arb_t wg, acc;
  arb_init(wg);
  arb_init(acc);
  arb_sub_arf(wg, gamma, e.centre, wp + 32);
  arb_poly_t Q;
  arb_poly_init(Q);
  arb_poly_fit_length(Q, len - 1);
  arb_set(acc, e.P->coeffs + len - 1);
  for (slong k = len - 1; k >= 1; --k) {
    arb_set(Q->coeffs + k - 1, acc);
    arb_mul(acc, acc, wg, wp);
    arb_add(acc, acc, e.P->coeffs + k - 1, wp);
  }
  _arb_poly_set_length(Q, len - 1);
  _arb_poly_normalise(Q);
  arb_poly_swap(e.P, Q);
  arb_poly_clear(Q);
  arb_clear(wg);
  arb_clear(acc);
}

}  // namespace uniparam
