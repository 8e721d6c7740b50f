// SPDX-License-Identifier: GPL-3.0-or-later
// Cost of one evaluation of each surface effect (core/surfaces), on varying inputs so
// the compiler cannot hoist the work out of the loop.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "hapticad/core/surfaces/anisotropy.h"
#include "hapticad/core/surfaces/curve_pattern.h"
#include "hapticad/core/surfaces/friction.h"
#include "hapticad/core/surfaces/roughness_texture.h"
#include "hapticad/core/surfaces/stripe_pattern.h"
#include "hapticad/core/surfaces/vibration.h"
#include "hapticad/core/surfaces/viscous_texture.h"

namespace hapticad {
namespace {

// precomputed inputs, so the loops time the effect and not their generation: a walk of
// velocities at 50 mm/s in every direction and points over a few millimetres
struct Inputs {
  static constexpr int kCount = 1024;
  Vec3 velocity[kCount];
  Vec3 point[kCount];
  Vec3 normal[kCount];
  Inputs() {
    for (int i = 0; i < kCount; ++i) {
      velocity[i] = 0.05 * Vec3(std::cos(0.37 * i), std::sin(0.37 * i), 0.0);
      point[i] = Vec3(1e-5 * ((i * 37) % 1024), 2e-5 * ((i * 11) % 512), 0.0);
      normal[i] = Vec3(0.001 * (i % 100), 0.0, 1.0).normalized();
    }
  }
};
const Inputs kInputs;
Vec3 Velocity(int i) { return kInputs.velocity[i & (Inputs::kCount - 1)]; }
Vec3 Point(int i) { return kInputs.point[i & (Inputs::kCount - 1)]; }
Vec3 Normal(int i) { return kInputs.normal[i & (Inputs::kCount - 1)]; }

void BM_EquivalentFriction(benchmark::State& state) {
  FrictionParams p;
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(EquivalentFriction(p, Point(++i).y()));
}
BENCHMARK(BM_EquivalentFriction);

void BM_CalcFrictionForce(benchmark::State& state) {
  FrictionParams p;
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(CalcFrictionForce(p, 1.0, Velocity(++i)));
}
BENCHMARK(BM_CalcFrictionForce);

void BM_DirectionalFriction(benchmark::State& state) {
  FrictionParams p;
  AnisotropicFriction a;
  a.interpolation =
      state.range(0) ? AnisotropyInterpolation::kEllipse : AnisotropyInterpolation::kLinear;
  int i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(DirectionalFriction(p, a, Vec3::UnitX(), 1.0, Velocity(++i)));
  state.SetLabel(state.range(0) ? "ellipse" : "eq. 3");
}
BENCHMARK(BM_DirectionalFriction)->Arg(0)->Arg(1);

void BM_EvaluateLinear(benchmark::State& state) {
  const LinearPattern p{Vec3(1, 0, 0)};
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(EvaluateLinear(p, Vec3::Zero(), Normal(++i)));
}
BENCHMARK(BM_EvaluateLinear);

void BM_EvaluateLinearOnACylinder(benchmark::State& state) {
  // round a 20 mm handle: the points made before the loop, so only the pattern is timed
  const LinearPattern p{Vec3(0, 1, 0), 0.02, Vec3(0.02, 0, 0), Vec3::Zero(), Vec3::UnitZ()};
  std::vector<Vec3> points;
  for (int k = 0; k < 1024; ++k) {
    const double a = 2 * M_PI * k / 1024;
    points.emplace_back(0.02 * std::cos(a), 0.02 * std::sin(a), 0.01);
  }
  int i = 0;
  for (auto _ : state) {
    const Vec3& point = points[++i & 1023];
    benchmark::DoNotOptimize(EvaluateLinear(p, point, Vec3(point.x(), point.y(), 0) / 0.02));
  }
}
BENCHMARK(BM_EvaluateLinearOnACylinder);

void BM_EvaluateCircular(benchmark::State& state) {
  const CircularPattern p{Vec3::Zero(), Vec3::UnitZ(), 1e-3};
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(EvaluateCircular(p, Point(++i), Vec3::UnitZ()));
}
BENCHMARK(BM_EvaluateCircular);

void BM_CurvePattern(benchmark::State& state) {
  std::vector<Vec2> poles;
  for (int k = 0; k <= 20; ++k) poles.emplace_back(5e-3 * std::sin(0.3 * k), 2e-3 * k);
  std::vector<double> knots(4, 0.0);
  for (int k = 1; k < 18; ++k) knots.push_back(k / 18.0);
  knots.insert(knots.end(), 4, 1.0);
  const auto evaluation =
      state.range(0) ? CurvePattern::Evaluation::kExact : CurvePattern::Evaluation::kLookupTable;
  const CurvePattern pattern =
      CurvePattern::Build({Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()},
                          NurbsCurve2(3, knots, poles, {}), 256, evaluation);
  int i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(pattern.Evaluate(Vec3(0, 2 * Point(++i).y(), 0), Vec3::UnitZ()));
  state.SetLabel(state.range(0) ? "exact" : "lookup table, 256");
}
BENCHMARK(BM_CurvePattern)->Arg(0)->Arg(1);

void BM_SampleRoughness(benchmark::State& state) {
  const RoughnessGrid g = MakeRoughnessGrid(4, SurfaceFrame{});
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(SampleRoughness(g, Point(++i)));
}
BENCHMARK(BM_SampleRoughness);

void BM_ViscousTextureForce(benchmark::State& state) {
  const ViscousTextureParams p = PaperPreset(1, 2);
  int i = 0;
  for (auto _ : state) {
    ++i;
    benchmark::DoNotOptimize(CalcViscousTextureForce(p, 3.3, Point(i).x(), Velocity(i), 0.002));
  }
}
BENCHMARK(BM_ViscousTextureForce);

void BM_VibrationForce(benchmark::State& state) {
  const Vibration v{120.0, 0.3, Vec3::UnitZ(), true};
  double t = 0.0;
  for (auto _ : state) benchmark::DoNotOptimize(CalcVibrationForce(v, t += 1e-3));
}
BENCHMARK(BM_VibrationForce);

}  // namespace
}  // namespace hapticad

BENCHMARK_MAIN();
