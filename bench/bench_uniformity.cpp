// Google Benchmark: certified uniformity and radical reparameterization on
// the running example and on deterministic polynomial plane curves of
// growing degree. Speed targets (docs/benchmarks.md) are tracked here, never in tests.
#include <benchmark/benchmark.h>

#include <string>

#include "uniparam/reparam/all.hpp"

namespace {

// A deterministic wavy polynomial plane curve of degree d: (t, sum c_k t^k)
// with small coefficients from a linear congruential sequence.
uniparam::Curve wavy_curve(long d) {
  std::string y;
  unsigned long s = 12345;
  for (long k = 1; k <= d; ++k) {
    s = s * 6364136223846793005UL + 1442695040888963407UL;
    long c = static_cast<long>((s >> 33) % 19) - 9;
    if (c == 0) c = 1;
    y += (c < 0 ? " - " : " + ") + std::to_string(c < 0 ? -c : c) + "*t^" + std::to_string(k);
  }
  return uniparam::parse_curve("(t, 0" + y + ")");
}

void BM_Uniformity_RunningExample(benchmark::State& st) {
  const auto c = uniparam::parse_curve("(t, t^3)");
  uniparam::Options o;
  o.digits = st.range(0);
  for (auto _ : st) benchmark::DoNotOptimize(uniparam::uniformity(c, uniparam::SpeedKind::Angular, o));
}
BENCHMARK(BM_Uniformity_RunningExample)->Arg(15)->Arg(50)->Unit(benchmark::kMillisecond);

void BM_Radical_RunningExample(benchmark::State& st) {
  const auto c = uniparam::parse_curve("(t, t^3)");
  uniparam::Options o;
  o.digits = st.range(0);
  for (auto _ : st) benchmark::DoNotOptimize(uniparam::radical(c, uniparam::SpeedKind::Angular, o));
}
BENCHMARK(BM_Radical_RunningExample)->Arg(15)->Arg(50)->Unit(benchmark::kMillisecond);

void BM_Uniformity_WavyDegree(benchmark::State& st) {
  const auto c = wavy_curve(st.range(0));
  for (auto _ : st) benchmark::DoNotOptimize(uniparam::uniformity(c, uniparam::SpeedKind::Angular));
}
BENCHMARK(BM_Uniformity_WavyDegree)->Arg(6)->Arg(12)->Arg(25)->Unit(benchmark::kMillisecond);

void BM_Radical_WavyDegree(benchmark::State& st) {
  const auto c = wavy_curve(st.range(0));
  for (auto _ : st) benchmark::DoNotOptimize(uniparam::radical(c, uniparam::SpeedKind::Angular));
}
BENCHMARK(BM_Radical_WavyDegree)->Arg(6)->Arg(12)->Arg(25)->Unit(benchmark::kMillisecond);

}  // namespace
