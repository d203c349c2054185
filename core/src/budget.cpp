// budget.cpp -- the thread's deadline (see budget.hpp).
#include "uniparam/core/budget.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using Clock = std::chrono::steady_clock;

/// The deadline in force in this thread, and the length of the budget that
/// set it (for the message).
thread_local Deadline g_deadline;

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

}  // namespace

TimeBudget::TimeBudget(double seconds)
    : prev_active_(g_deadline.active), prev_deadline_(g_deadline.at), prev_seconds_(g_deadline.seconds) {
  // 1e9 s (about 31 years) keeps the duration arithmetic far from overflow.
  if (!(seconds > 0.0) || !std::isfinite(seconds) || seconds > 1e9)
    throw InvalidArgument("a time budget must be a positive number of seconds up to 1e9, got " +
                          seconds_text(seconds));
  const auto at = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  if (!g_deadline.active || at < g_deadline.at) {
    g_deadline.active = true;
    g_deadline.at = at;
    g_deadline.seconds = seconds;
  }
}

TimeBudget::~TimeBudget() {
  g_deadline.active = prev_active_;
  g_deadline.at = prev_deadline_;
  g_deadline.seconds = prev_seconds_;
}

void check_time_budget() {
  if (g_deadline.cancel && g_deadline.cancel->load(std::memory_order_relaxed))
    throw Interrupted("interrupted: the computation was cancelled");
  if (g_deadline.active && Clock::now() >= g_deadline.at)
    throw TimeLimitExceeded("time limit exceeded: the computation did not finish within " +
                         seconds_text(g_deadline.seconds) + " s (raise it with --timeout SECONDS)");
}

bool has_time_budget() { return g_deadline.active; }

Deadline current_deadline() { return g_deadline; }

ScopedDeadline::ScopedDeadline(const Deadline& d) : prev_(g_deadline) { g_deadline = d; }

ScopedDeadline::~ScopedDeadline() { g_deadline = prev_; }

ScopedCancellation::ScopedCancellation(const std::atomic<bool>& flag) : prev_(g_deadline.cancel) {
  g_deadline.cancel = &flag;
}

ScopedCancellation::~ScopedCancellation() { g_deadline.cancel = prev_; }

}  // namespace uniparam
