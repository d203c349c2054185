// Google Benchmark: font-like inputs. Arc length of single TrueType-like
// quadratic segments (integer font units), and of a glyph-like closed path
// of quadratic segments as one composite curve. The targets of
// docs/benchmarks.md: >= 5000 quadratic segments per second on 2 cores
// (through `uniparam batch`, scripts/bench.sh), a glyph in < 5 ms.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "uniparam/reparam/all.hpp"

namespace {

// Deterministic quadratic segments with coordinates in [0, 2048) (font units).
std::vector<uniparam::BezierCurve> font_like_quadratics(std::size_t n) {
  std::vector<uniparam::BezierCurve> out;
  unsigned long s = 99;
  auto next = [&]() {
    s = s * 6364136223846793005UL + 1442695040888963407UL;
    return static_cast<long>((s >> 33) % 2048);
  };
  while (out.size() < n) {
    std::vector<std::vector<uniparam::Rational>> p;
    for (int i = 0; i < 3; ++i) p.push_back({uniparam::Rational(next()), uniparam::Rational(next())});
    if (p[0] == p[2]) continue;
    out.emplace_back(p);
  }
  return out;
}

void BM_ArcLength_FontQuadratic(benchmark::State& st) {
  const auto segs = font_like_quadratics(64);
  std::vector<uniparam::Curve> curves;
  for (const auto& b : segs) curves.push_back(b.to_curve());
  std::size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(uniparam::uniformity(curves[i], uniparam::SpeedKind::Parametric));
    i = (i + 1) % curves.size();
  }
  st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_ArcLength_FontQuadratic)->Unit(benchmark::kMicrosecond);

// A closed glyph-like outline of 17 segments (16 quadratic, one line), as
// TrueType draws an "S": integer on-curve and off-curve points.
const char* kGlyph =
    "M 520 1460 Q 520 1700 760 1700 Q 1000 1700 1000 1460 Q 1000 1300 860 1220 Q 700 1130 620 1060 "
    "Q 480 930 480 720 Q 480 440 760 440 Q 1060 440 1060 720 L 940 720 Q 940 560 760 560 Q 600 560 600 720 "
    "Q 600 860 720 960 Q 800 1030 920 1110 Q 1120 1240 1120 1460 Q 1120 1820 760 1820 Q 400 1820 400 1460 Z";

void BM_ArcLength_GlyphComposite(benchmark::State& st) {
  const auto paths = uniparam::parse_svg_path(kGlyph);
  std::vector<uniparam::Curve> segs;
  for (const auto& b : paths.front().segments) segs.push_back(b.to_curve());
  const uniparam::CompositeCurve c(segs, paths.front().knots, paths.front().labels);
  for (auto _ : st) benchmark::DoNotOptimize(uniparam::uniformity(c, uniparam::SpeedKind::Parametric));
  st.counters["segments"] = static_cast<double>(c.size());
}
BENCHMARK(BM_ArcLength_GlyphComposite)->Unit(benchmark::kMillisecond);

}  // namespace
