// reparam/src/api_impl.hpp -- the state behind the facade's types
// (uniparam/uniparam.hpp) and the conversions between them and the engine's.
// Private to reparam/src/api*.cpp.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/all.hpp"
#include "uniparam/uniparam.hpp"

namespace uniparam {
namespace api {

struct Rational::Impl {
  uniparam::Rational v;
};

struct Ball::Impl {
  uniparam::Ball v;
};

struct Curve::Impl {
  CompositeCurve cc;                   ///< one segment for a single curve
  std::optional<BezierCurve> bezier;   ///< set when given as one Bezier curve
  explicit Impl(CompositeCurve c) : cc(std::move(c)) {}
};

struct Nurbs::Impl {
  uniparam::Nurbs n;
};

struct Reparameterization::Impl {
  Curve curve;
  Options opt;
  uniparam::Options iopt;
  std::vector<Speed> speeds;  ///< one per segment
  // A single curve: the map; for bezier_bilinear also the Bezier result.
  std::optional<uniparam::Reparameterization> map;
  std::optional<BezierResult> bezier;
  // A composite curve: the map and the method that made it.
  std::optional<CompositeMap> cmap;
  std::optional<CompositeMethod> cmethod;
  Impl(Curve c, const Options& o, uniparam::Options io) : curve(std::move(c)), opt(o), iopt(io) {}
};

namespace detail {

uniparam::SpeedKind kind_of(const Options& o);
/// The engine's options for o, every field of o checked (InvalidArgument
/// naming the field).
uniparam::Options engine_options(const Options& o);
/// The engine's messages name CLI options; the facade's name Options fields.
std::string facade_message(std::string m);

/// Runs f() with o's thread count and time limit in force, the engine's
/// exceptions rethrown as the same types with facade messages.
template <class F>
auto guarded(const Options& o, F f) -> decltype(f()) {
  try {
    engine_options(o);
    const ScopedWorkerCount workers(o.threads);
    std::optional<TimeBudget> budget;
    if (o.time_limit > 0) budget.emplace(o.time_limit);
    return f();
  } catch (const ParseError&) {
    throw;
  } catch (const Interrupted& e) {
    throw Interrupted(facade_message(e.what()));
  } catch (const TimeLimitExceeded& e) {
    throw TimeLimitExceeded(facade_message(e.what()));
  } catch (const BudgetExceeded& e) {
    throw BudgetExceeded(facade_message(e.what()));
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(facade_message(e.what()));
  } catch (const DomainError& e) {
    throw DomainError(facade_message(e.what()));
  }
}

inline api::Rational wrap(const uniparam::Rational& q) {
  return api::Rational(std::make_shared<const api::Rational::Impl>(api::Rational::Impl{q}));
}
inline api::Ball wrap(const uniparam::Ball& b) {
  return api::Ball(std::make_shared<const api::Ball::Impl>(api::Ball::Impl{b}));
}
inline std::vector<api::Ball> wrap(const std::vector<uniparam::Ball>& v) {
  std::vector<api::Ball> out;
  out.reserve(v.size());
  for (const auto& b : v) out.push_back(wrap(b));
  return out;
}
inline const uniparam::Rational& unwrap(const api::Rational& q) { return q.impl().v; }
inline const uniparam::Ball& unwrap(const api::Ball& b) { return b.impl().v; }

}  // namespace detail
}  // namespace api
}  // namespace uniparam
