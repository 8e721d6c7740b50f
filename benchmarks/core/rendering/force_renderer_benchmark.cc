// SPDX-License-Identifier: GPL-3.0-or-later
// One servo tick of the renderer in sliding contact on a box face: a plain face
// against one with each effect and one with every effect ("model only what the scene
// requires": a plain face must not pay for effects it does not use). And what a reset
// costs (ForceRenderer::Reset: a swap, a fault, the clutch), where the device may be
// inside a part and the proxy is moved out.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/rendering/force_renderer.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

// a generated soup is clean: no repair
SceneOptions NoRepair() {
  SceneOptions options;
  options.repair = false;
  return options;
}

enum Setup { kPlain, kPattern, kCurve, kRoughness, kTexture, kVibration, kCone, kEverything };
const char* kNames[] = {"plain",         "linear pattern",  "curve pattern (exact)",
                        "roughness",     "viscous texture", "vibration",
                        "friction cone", "every effect"};

SurfaceProperties Make(int setup) {
  SurfaceProperties s;
  const SurfaceFrame frame{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()};
  if (setup == kPattern || setup == kEverything) s.pattern = LinearPattern{Vec3::UnitX()};
  if (setup == kCurve) {
    s.pattern = std::make_shared<const CurvePattern>(CurvePattern::Build(
        PatternPlane{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()},
        NurbsCurve2(2, {0, 0, 0, 1, 1, 1}, {Vec2(0, -0.05), Vec2(0.01, 0.0), Vec2(0.0, 0.05)}, {}),
        256, CurvePattern::Evaluation::kExact));
  }
  if (setup == kRoughness || setup == kEverything) s.roughness = MakeRoughnessGrid(4, frame);
  if (setup == kTexture || setup == kEverything)
    s.texture = ViscousGrating{PaperPreset(1, 2), frame};
  if (setup == kVibration || setup == kEverything) s.vibration = 0;
  if (setup == kCone) s.friction_mode = FrictionMode::kCone;
  return s;
}

void BM_RenderTick(benchmark::State& state) {
  const int setup = static_cast<int>(state.range(0));
  const auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3);
  std::vector<SurfaceProperties> faces(6);
  faces[5] = Make(setup);
  const auto table = std::make_shared<SurfaceTable>(
      faces, std::vector<Vibration>{{120.0, 0.3, Vec3::UnitZ(), true}});
  ForceRenderer renderer(scene, table, RenderLimits{8.9, 3000.0});
  // a circle of radius 20 mm, 2 mm below the top face, at 50 mm/s, 1 kHz: precomputed
  constexpr int kTicks = 2513;  // one lap
  std::vector<RenderInput> inputs(kTicks);
  for (int k = 0; k < kTicks; ++k) {
    const double t = 1e-3 * k;
    inputs[k] = {Vec3(0.02 * std::cos(2.5 * t), 0.02 * std::sin(2.5 * t), 0.048),
                 Vec3(-0.05 * std::sin(2.5 * t), 0.05 * std::cos(2.5 * t), 0.0), t};
  }
  RenderOutput out;
  renderer.Render({Vec3(0.02, 0.0, 0.06), Vec3::Zero(), 0.0}, &out);
  int i = 0;
  for (auto _ : state) {
    renderer.Render(inputs[i], &out);
    i = i + 1 == kTicks ? 0 : i + 1;
    benchmark::DoNotOptimize(out);
  }
  if (!(out.flags & kContact)) state.SkipWithError("lost contact");
  state.SetLabel(kNames[setup]);
}
BENCHMARK(BM_RenderTick)->DenseRange(kPlain, kEverything);

// A reset 2 mm inside an icosphere of radius 50 mm, moved out: the six rays' sweeps
// through the grid (point) or the tree (1 mm sphere). (A point outside every vertex's
// distance from the centre returns at once.)
void BM_ResetInside(benchmark::State& state) {
  const int frequency = static_cast<int>(state.range(0));
  const bool sphere = state.range(1) != 0;
  const auto scene = HapticScene::Build(MakeIcosphere(frequency, 50.0), 1e-3, NoRepair());
  ContactOptions options;
  options.proxy_radius_m = sphere ? 0.001 : 0.0;
  ForceRenderer renderer(scene, std::make_shared<SurfaceTable>(), RenderLimits{8.9, 3000.0},
                         options);
  const Vec3 at = Vec3(0.3, 0.5, 0.8).normalized() * 0.048;
  for (auto _ : state) {
    renderer.Reset(at);
    benchmark::DoNotOptimize(renderer.proxy().position());
  }
  if (renderer.proxy().position() == at) state.SkipWithError("not moved out");
  state.SetLabel(std::to_string(scene->mesh().num_triangles()) + (sphere ? " sphere:1" : " point"));
}
BENCHMARK(BM_ResetInside)->ArgsProduct({{22, 71, 224}, {0, 1}})->Unit(benchmark::kMicrosecond);

// Two icospheres of 100,820 triangles and radius `radius_mm`, centred at x = -half and
// x = +half (mm), in one soup.
TriangleSoup TwoIcospheres(double radius_mm, double half_mm) {
  TriangleSoup soup = MakeIcosphere(71, radius_mm, Vec3(-half_mm, 0.0, 0.0));
  const TriangleSoup other = MakeIcosphere(71, radius_mm, Vec3(half_mm, 0.0, 0.0));
  const auto base = static_cast<std::int32_t>(soup.vertices.size());
  soup.vertices.insert(soup.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& t : other.triangles)
    soup.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  soup.cad_faces.resize(soup.triangles.size(), 0);
  return soup;
}

// The worst case known for the grid: small dense parts far apart (one grid level of
// tiny cells, whose rays walk the empty cells between the parts). Two icospheres of
// radius 5 mm, 100,820 triangles each, 500 mm apart; a point proxy reset 0.5 mm inside
// one of them.
void BM_ResetInsideOneOfTwoFarApart(benchmark::State& state) {
  const auto scene = HapticScene::Build(TwoIcospheres(5.0, 250.0), 1e-3, NoRepair());
  ForceRenderer renderer(scene, std::make_shared<SurfaceTable>(), RenderLimits{8.9, 3000.0});
  const Vec3 at = Vec3(-0.25, 0.0, 0.0) + Vec3(0.3, 0.5, 0.8).normalized() * 0.0045;
  for (auto _ : state) {
    renderer.Reset(at);
    benchmark::DoNotOptimize(renderer.proxy().position());
  }
  if (renderer.proxy().position() == at) state.SkipWithError("not moved out");
}
BENCHMARK(BM_ResetInsideOneOfTwoFarApart)->Unit(benchmark::kMicrosecond);

// Parts that overlap (their surface crosses itself; each piece is a solid): two
// icospheres of radius 50 mm and 100,820 triangles each, centres 80 mm apart; the point
// 1.2 mm inside both, 2 mm under the ridge where they cross, so a ray's exit is where
// the pieces stop winding round it.
void BM_ResetInsideOverlappingParts(benchmark::State& state) {
  const bool sphere = state.range(0) != 0;
  const auto scene = HapticScene::Build(TwoIcospheres(50.0, 40.0), 1e-3, NoRepair());
  if (scene->BuildSolids().bounds_solids || !scene->BuildSolids().pieces_bound_solids) {
    state.SkipWithError("the scene is not two overlapping solids");
    return;
  }
  ContactOptions options;
  options.proxy_radius_m = sphere ? 0.001 : 0.0;
  ForceRenderer renderer(scene, std::make_shared<SurfaceTable>(), RenderLimits{8.9, 3000.0},
                         options);
  const Vec3 at(0.0, 0.0, 0.028);
  for (auto _ : state) {
    renderer.Reset(at);
    benchmark::DoNotOptimize(renderer.proxy().position());
  }
  if (renderer.proxy().position() == at) state.SkipWithError("not moved out");
  state.SetLabel(sphere ? "sphere:1" : "point");
}
BENCHMARK(BM_ResetInsideOverlappingParts)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace hapticad

BENCHMARK_MAIN();
