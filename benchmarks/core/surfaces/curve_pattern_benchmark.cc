// SPDX-License-Identifier: GPL-3.0-or-later
// The curve pattern's trade: lookup-table size against angle error and time, for two
// sketch-like curves. Counters: max_err_deg and mean_err_deg over 20,000 heights
// against the exact evaluation; the time is one Evaluate() per iteration.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "hapticad/core/surfaces/curve_pattern.h"

namespace hapticad {
namespace {

constexpr double kPi = 3.14159265358979323846;

// 0: a gentle S over 90 mm (the figure in docs/traces/pattern_curve.png);
// 1: a tight wave, 5 mm amplitude every 10 mm, over 40 mm.
NurbsCurve2 Curve(int which) {
  if (which == 0) {
    return NurbsCurve2(
        3, {0, 0, 0, 0, 1, 1, 1, 1},
        {Vec2(0.040, 0.005), Vec2(0.070, 0.035), Vec2(0.030, 0.065), Vec2(0.060, 0.095)}, {});
  }
  std::vector<Vec2> poles;
  for (int i = 0; i <= 80; ++i) poles.emplace_back(5e-3 * std::sin(2 * kPi * i / 20.0), 0.5e-3 * i);
  std::vector<double> knots(4, 0.0);
  for (int i = 1; i < 78; ++i) knots.push_back(i / 78.0);
  knots.insert(knots.end(), 4, 1.0);
  return NurbsCurve2(3, knots, poles, {});
}

void BM_CurveLookupTable(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const int size = static_cast<int>(state.range(1));
  const PatternPlane plane{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};
  const CurvePattern table =
      CurvePattern::Build(plane, Curve(which), size, CurvePattern::Evaluation::kLookupTable);
  double worst = 0.0, sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double y = table.y_min() + (table.y_max() - table.y_min()) * (i + 0.5) / n;
    const double error = std::abs(table.LookupAngle(y) - table.ExactAngle(y));
    worst = std::max(worst, error);
    sum += error;
  }
  int i = 0;
  const double span = table.y_max() - table.y_min();
  for (auto _ : state) {
    benchmark::DoNotOptimize(table.Evaluate(
        Vec3(0.0, table.y_min() + span * ((++i % 997) / 997.0), 0.0), Vec3::UnitZ()));
  }
  state.counters["max_err_deg"] = worst * 180.0 / kPi;
  state.counters["mean_err_deg"] = sum / n * 180.0 / kPi;
  state.counters["table_bytes"] = size * sizeof(double);
  state.SetLabel(which == 0 ? "gentle S" : "tight wave");
}
BENCHMARK(BM_CurveLookupTable)->ArgsProduct({{0, 1}, {8, 16, 32, 64, 128, 256, 1024, 4096}});

void BM_CurveExact(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const PatternPlane plane{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};
  const CurvePattern exact =
      CurvePattern::Build(plane, Curve(which), 2, CurvePattern::Evaluation::kExact);
  int i = 0;
  const double span = exact.y_max() - exact.y_min();
  for (auto _ : state) {
    benchmark::DoNotOptimize(exact.Evaluate(
        Vec3(0.0, exact.y_min() + span * ((++i % 997) / 997.0), 0.0), Vec3::UnitZ()));
  }
  state.SetLabel(which == 0 ? "gentle S" : "tight wave");
}
BENCHMARK(BM_CurveExact)->Arg(0)->Arg(1);

}  // namespace
}  // namespace hapticad

BENCHMARK_MAIN();
