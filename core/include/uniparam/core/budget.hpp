// uniparam/core/budget.hpp -- the wall-clock time budget, enforced
// cooperatively.
//
// A TimeBudget sets a deadline for the computations of the calling thread
// while it is alive; the long loops of the engine (quadrature integrand
// evaluations and precision doubling, real-root isolation and refinement,
// the precision loops of the reparameterizations) call check_time_budget(),
// which throws TimeLimitExceeded once the deadline has passed. Nothing
// uncertified is returned in place of a result. The check is cheap (one read
// of a monotonic clock), so it may be called per integrand evaluation.
// A single long FLINT/Arb call (one gcd of huge polynomials, ...) is not
// interrupted: the deadline is noticed at the next check.
//
// The CLI installs one budget per command (--timeout SECONDS, default 600);
// library callers install their own, or have none (no deadline at all).
#pragma once

#include <chrono>

namespace uniparam {

/// A deadline `seconds` from construction for the calling thread, removed
/// (the enclosing one restored) at destruction. Budgets nest: the earliest
/// deadline in force wins, so an inner budget can shorten but never extend
/// an outer one.
/// \pre seconds > 0 and finite (InvalidArgument otherwise).
class TimeBudget {
 public:
  explicit TimeBudget(double seconds);
  ~TimeBudget();
  TimeBudget(const TimeBudget&) = delete;
  TimeBudget& operator=(const TimeBudget&) = delete;

 private:
  bool prev_active_;
  std::chrono::steady_clock::time_point prev_deadline_;
  double prev_seconds_;
};

/// Throws TimeLimitExceeded (a BudgetExceeded) naming the time limit and
/// --timeout when the calling thread has a TimeBudget whose deadline has
/// passed; otherwise does nothing.
void check_time_budget();

/// True when a TimeBudget is in force in the calling thread.
bool has_time_budget();

/// The calling thread's deadline (inactive when no budget is in force), to
/// hand to the worker threads it starts.
struct Deadline {
  bool active = false;
  std::chrono::steady_clock::time_point at{};
  double seconds = 0.0;  ///< length of the budget that set it (for messages)
};
Deadline current_deadline();

/// Installs `d` as the calling thread's deadline for the scope's lifetime
/// (a worker thread inheriting its parent's budget); the previous one is
/// restored at destruction.
class ScopedDeadline {
 public:
  explicit ScopedDeadline(const Deadline& d);
  ~ScopedDeadline();
  ScopedDeadline(const ScopedDeadline&) = delete;
  ScopedDeadline& operator=(const ScopedDeadline&) = delete;

 private:
  Deadline prev_;
};

}  // namespace uniparam
