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

#include <atomic>
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
/// passed, and Interrupted (a TimeLimitExceeded) when a ScopedCancellation's
/// flag in force in the calling thread is set; otherwise does nothing.
void check_time_budget();

/// True when a TimeBudget is in force in the calling thread.
bool has_time_budget();

/// The calling thread's deadline (inactive when no budget is in force), to
/// hand to the worker threads it starts.
struct Deadline {
  bool active = false;
  std::chrono::steady_clock::time_point at{};
  double seconds = 0.0;  ///< length of the budget that set it (for messages)
  /// A ScopedCancellation's flag (null when none is in force): once it is
  /// set, check_time_budget() throws Interrupted.
  const std::atomic<bool>* cancel = nullptr;
};
/// The calling thread's Deadline (the budget and cancellation flag in force).
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

/// Makes `flag` the calling thread's cancellation flag for the scope's
/// lifetime (the previous one restored at destruction): from the moment
/// another thread sets it, every check_time_budget() of this thread, and of
/// the worker threads its parallel loops start (they inherit the Deadline),
/// throws Interrupted, so a computation ends at its next check (the same
/// places a TimeBudget is noticed) with nothing uncertified returned.
/// Used by callers that cancel from outside, e.g. the Python module on
/// Ctrl-C. \pre `flag` outlives the scope.
class ScopedCancellation {
 public:
  explicit ScopedCancellation(const std::atomic<bool>& flag);
  ~ScopedCancellation();
  ScopedCancellation(const ScopedCancellation&) = delete;
  ScopedCancellation& operator=(const ScopedCancellation&) = delete;

 private:
  const std::atomic<bool>* prev_;
};

}  // namespace uniparam
