// curve_model.cpp -- the power-basis and Bernstein-basis curve models
// (curve_model.hpp).
#include "curve_model.hpp"

#include <utility>

#include "speed_enclosure.hpp"
#include "uniparam/core/ball.hpp"

namespace uniparam {

namespace {

class PowerModel final : public CurveModel {
 public:
  explicit PowerModel(std::vector<PowerComponent> c) : c_(std::move(c)) {
    disks_ = true;
    for (const PowerComponent& k : c_) disks_ = disks_ && k.N.has_disk_form() && (k.unit_den || k.Q.has_disk_form());
  }
  std::size_t size() const override { return c_.size(); }
  bool unit_den(std::size_t i) const override { return c_[i].unit_den; }
  std::size_t den_index(std::size_t i) const override { return c_[i].q_index; }
  void eval_num(std::size_t i, acb_ptr v, acb_ptr d1, acb_ptr d2, const acb_t z, long prec) const override {
    c_[i].N.eval(v, d1, d2, z, prec);
  }
  void eval_den(std::size_t i, acb_ptr v, acb_ptr d1, acb_ptr d2, const acb_t z, long prec) const override {
    c_[i].Q.eval(v, d1, d2, z, prec);
  }
  bool has_disks() const override { return disks_; }
  void eval_num_disks(std::size_t i, CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, long prec) const override {
    c_[i].N.eval_disks(v, d1, d2, z, prec);
  }
  void eval_den_disks(std::size_t i, CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, long prec) const override {
    c_[i].Q.eval_disks(v, d1, d2, z, prec);
  }
  void eval_num_double(std::size_t i, double t, double* v, double* d1, double* d2) const override {
    c_[i].N.eval_double(t, v, d1, d2);
  }
  void eval_den_double(std::size_t i, double t, double* v, double* d1, double* d2) const override {
    c_[i].Q.eval_double(t, v, d1, d2);
  }

 private:
  std::vector<PowerComponent> c_;
  bool disks_ = false;
};

// One polynomial sum_k c_k B_k^n in the Bernstein basis: c[j] holds the
// coefficients of its j-th derivative, (n)_j Delta^j c (degree n - j; empty
// for j > n), j <= 3 (the third only bounds the second on wide balls).
struct BernsteinPoly {
  std::vector<Integer> c[4];
  std::vector<Integer> h[4];  // c[j]'s coefficients times binom(n - j, k) (bernstein_horner)
  std::vector<double> d[3];  // c[0..2] in double (UNCERTIFIED evaluation)
  bool constant = true;      // all coefficients equal: p = c_0 (an integral curve's Q)
  explicit BernsteinPoly(const std::vector<Integer>& coeffs) {
    c[0] = coeffs;
    for (const Integer& x : coeffs) constant = constant && x == coeffs.front();
    for (int j = 0; j < 3; ++j) {
      const long n = static_cast<long>(c[j].size()) - 1;  // degree of c[j]
      for (long k = 0; k < n; ++k) c[j + 1].push_back((c[j][static_cast<std::size_t>(k) + 1] - c[j][static_cast<std::size_t>(k)]) * Integer(n));
    }
    for (int j = 0; j < 4; ++j) {
      if (j < 3)
        for (const Integer& x : c[j]) d[j].push_back(fmpz_get_d(x.get()));
      const long n = static_cast<long>(c[j].size()) - 1;
      Integer b(1);  // binom(n, k)
      for (long k = 0; k <= n; ++k) {
        h[j].push_back(c[j][static_cast<std::size_t>(k)] * b);
        fmpz_mul_si(b.get(), b.get(), n - k);
        fmpz_divexact_si(b.get(), b.get(), k + 1);
      }
    }
  }
};

// out = sum_k c_k B_k^(len-1)(z) by de Casteljau's algorithm (omz = 1 - z);
// 0 for no coefficients.
void casteljau(acb_ptr out, const std::vector<Integer>& c, const acb_t z, const acb_t omz, long prec) {
  const std::size_t len = c.size();
  if (len == 0) {
    acb_zero(out);
    return;
  }
  AcbVec b(len);
  for (std::size_t k = 0; k < len; ++k) acb_set_fmpz(b + k, c[k].get());
  for (std::size_t r = 1; r < len; ++r)
    for (std::size_t k = 0; k + r < len; ++k) {
      acb_mul(b + k, b + k, omz, prec);
      acb_addmul(b + k, z, b + (k + 1), prec);
    }
  acb_set(out, b + 0);
}

// out = sum_k h_k t^k (1 - t)^(len-1-k) (h_k = c_k binom(n, k): the
// Bernstein sum) by Horner's rule in O(n): in s = z / (1 - z) times
// (1 - z)^n where Re(mid z) <= 1/2, else in s = (1 - z) / z times z^n. Each
// term is a Bernstein term c_k B_k(t), so no more is lost than the sum of
// |c_k| B_k(t) allows (no power basis's alternating coefficients).
void bernstein_horner(acb_ptr out, const std::vector<Integer>& h, const acb_t z, const acb_t omz, long prec) {
  const std::size_t len = h.size();
  if (len == 0) {
    acb_zero(out);
    return;
  }
  const bool left = arf_cmp_2exp_si(arb_midref(acb_realref(z)), -1) <= 0;
  if (acb_is_real(z)) {  // the same in real balls (the quadrature's nodes): about half the work
    Ball s, acc, p;
    const arb_srcptr t = acb_realref(z), omt = acb_realref(omz);
    if (left) arb_div(s.get(), t, omt, prec);
    else arb_div(s.get(), omt, t, prec);
    arb_set_fmpz(acc.get(), h[left ? len - 1 : 0].get());
    for (std::size_t j = 1; j < len; ++j) {
      arb_mul(acc.get(), acc.get(), s.get(), prec);
      arb_add_fmpz(acc.get(), acc.get(), h[left ? len - 1 - j : j].get(), prec);
    }
    arb_pow_ui(p.get(), left ? omt : t, len - 1, prec);
    arb_mul(acb_realref(out), acc.get(), p.get(), prec);
    arb_zero(acb_imagref(out));
    return;
  }
  AcbBox s, acc, p;
  if (left) acb_div(s, z, omz, prec);
  else acb_div(s, omz, z, prec);
  acb_set_fmpz(acc, h[left ? len - 1 : 0].get());
  for (std::size_t j = 1; j < len; ++j) {
    acb_mul(acc, acc, s, prec);
    acb_add_fmpz(acc, acc, h[left ? len - 1 - j : j].get(), prec);
  }
  acb_pow_ui(p, left ? omz : z, len - 1, prec);
  acb_mul(out, acc, p, prec);
}

double casteljau_double(const std::vector<double>& c, double t) {
  if (c.empty()) return 0;
  std::vector<double> b(c);
  for (std::size_t r = 1; r < b.size(); ++r)
    for (std::size_t k = 0; k + r < b.size(); ++k) b[k] = (1 - t) * b[k] + t * b[k + 1];
  return b[0];
}

// v, d1, d2 (nullable) = p, p', p'' at z: directly on a narrow ball
// (bernstein_horner); on a wide one p^(j)(m) + (z - m) p^(j+1)(z) about the
// midpoint m (the mean-value form: the enclosure of p^(j+1) on the wide
// ball, which may be much wider than the range, only multiplies z - m).
void eval_bernstein(const BernsteinPoly& p, acb_ptr v, acb_ptr d1, acb_ptr d2, const acb_t z, long prec) {
  acb_ptr out[3] = {v, d1, d2};
  if (p.constant) {
    acb_set_fmpz(v, p.c[0].front().get());
    if (d1) acb_zero(d1);
    if (d2) acb_zero(d2);
    return;
  }
  AcbBox omz, m, omm, w, t;
  acb_one(omz);
  acb_sub(omz, omz, z, prec);
  if (!is_wide_ball(z)) {
    for (int j = 0; j < 3; ++j)
      if (out[j]) bernstein_horner(out[j], p.h[j], z, omz, prec);
    return;
  }
  acb_get_mid(m, z);
  acb_one(omm);
  acb_sub(omm, omm, m, prec);
  acb_sub(w, z, m, prec);
  for (int j = 0; j < 3; ++j) {
    if (!out[j]) continue;
    // p^(j+1) on the wide ball: Horner's O(n) where finite (its divisor
    // z or 1 - z away from 0), else de Casteljau's O(n^2)
    bernstein_horner(t, p.h[j + 1], z, omz, prec);
    if (!acb_is_finite(t)) casteljau(t, p.c[j + 1], z, omz, prec);
    bernstein_horner(out[j], p.h[j], m, omm, prec);
    acb_addmul(out[j], w, t, prec);
  }
}

class BernsteinModel final : public CurveModel {
 public:
  explicit BernsteinModel(const BernsteinForm& b) : q_(b.den) {
    for (const auto& row : b.num) n_.emplace_back(row);
  }
  std::size_t size() const override { return n_.size(); }
  bool unit_den(std::size_t) const override { return false; }
  std::size_t den_index(std::size_t) const override { return 0; }
  void eval_num(std::size_t i, acb_ptr v, acb_ptr d1, acb_ptr d2, const acb_t z, long prec) const override {
    eval_bernstein(n_[i], v, d1, d2, z, prec);
  }
  void eval_den(std::size_t, acb_ptr v, acb_ptr d1, acb_ptr d2, const acb_t z, long prec) const override {
    eval_bernstein(q_, v, d1, d2, z, prec);
  }
  bool has_disks() const override { return false; }
  void eval_num_disks(std::size_t, CDisk*, CDisk*, CDisk*, const acb_t, long) const override {}
  void eval_den_disks(std::size_t, CDisk*, CDisk*, CDisk*, const acb_t, long) const override {}
  void eval_num_double(std::size_t i, double t, double* v, double* d1, double* d2) const override {
    eval_double(n_[i], t, v, d1, d2);
  }
  void eval_den_double(std::size_t, double t, double* v, double* d1, double* d2) const override {
    eval_double(q_, t, v, d1, d2);
  }

 private:
  static void eval_double(const BernsteinPoly& p, double t, double* v, double* d1, double* d2) {
    double* out[3] = {v, d1, d2};
    for (int j = 0; j < 3; ++j)
      if (out[j]) *out[j] = casteljau_double(p.d[j], t);
  }
  std::vector<BernsteinPoly> n_;
  BernsteinPoly q_;
};

}  // namespace

std::shared_ptr<const CurveModel> power_curve_model(std::vector<PowerComponent> comps) {
  return std::make_shared<const PowerModel>(std::move(comps));
}

std::shared_ptr<const CurveModel> bernstein_curve_model(const BernsteinForm& b) {
  return std::make_shared<const BernsteinModel>(b);
}

bool bernstein_model_serves(const BernsteinForm& b) {
  return !b.den.empty() && static_cast<long>(b.den.size()) - 1 <= kBernsteinMaxDegree;
}

}  // namespace uniparam
