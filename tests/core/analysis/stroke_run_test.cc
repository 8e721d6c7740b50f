// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/analysis/stroke_run.h"

#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "test_meshes.h"

namespace hapticad {
namespace {

// A 100 mm box in mm, scaled to metres; its top (CAD face 5) at z = 0.05 m.
std::unique_ptr<ForceRenderer> BoxRenderer() {
  auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3);
  return std::make_unique<ForceRenderer>(scene, std::make_shared<SurfaceTable>(),
                                         RenderLimits{8.0, 3000.0});
}

// Down onto the top, 1 mm in, a 20 mm slide along x, and up: 400 ticks of 1 ms.
std::vector<RenderInput> Stroke() {
  std::vector<RenderInput> inputs;
  for (int k = 0; k < 400; ++k) {
    const double t = k * 1e-3;
    RenderInput in;
    in.time_s = t;
    if (k < 100) {
      in.position_w = Vec3(0, 0, 0.06 - 0.011 * k / 100.0);
      in.velocity_w = Vec3(0, 0, -0.11);
    } else if (k < 300) {
      in.position_w = Vec3(0.02 * (k - 100) / 200.0, 0, 0.049);
      in.velocity_w = Vec3(0.1, 0, 0);
    } else {
      in.position_w = Vec3(0.02, 0, 0.049 + 0.011 * (k - 300) / 100.0);
      in.velocity_w = Vec3(0, 0, 0.11);
    }
    inputs.push_back(in);
  }
  return inputs;
}

void ExpectSame(const RenderOutput& a, const RenderOutput& b, int k) {
  EXPECT_EQ(a.force_w, b.force_w) << k;
  EXPECT_EQ(a.proxy_w, b.proxy_w) << k;
  EXPECT_EQ(a.normal_force_n, b.normal_force_n) << k;
  EXPECT_EQ(a.tangential_force_n, b.tangential_force_n) << k;
  EXPECT_EQ(a.cad_face, b.cad_face) << k;
  EXPECT_EQ(a.flags, b.flags) << k;
}

TEST(RunStroke, RendersEveryInputInOrderAsTickByTickRenderingDoes) {
  const std::vector<RenderInput> inputs = Stroke();
  auto run_renderer = BoxRenderer();
  const StrokeRun run = RunStroke(*run_renderer, inputs);
  ASSERT_EQ(run.outputs.size(), inputs.size());
  // the same stroke rendered by hand on a renderer of its own: the god-object proxy
  // carries state from tick to tick, so only the same inputs in the same order agree
  auto reference = BoxRenderer();
  int contact = 0;
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    RenderOutput expected;
    reference->Render(inputs[k], &expected);
    ExpectSame(run.outputs[k], expected, static_cast<int>(k));
    if (expected.flags & kContact) ++contact;
  }
  // the stroke pressed on the top face: the comparison is not between two idle renderers
  EXPECT_GT(contact, 200);  // ticks 91 to 309 are under the face
  EXPECT_EQ(run.outputs[200].cad_face, 5);
  EXPECT_NEAR(run.outputs[200].normal_force_n, 0.4, 1e-6);  // 0.4 N/mm untagged, 1 mm
  // the renderer is left where the stroke ended: both render the next input alike
  RenderInput after = inputs.back();
  after.time_s += 1e-3;
  RenderOutput a, b;
  run_renderer->Render(after, &a);
  reference->Render(after, &b);
  ExpectSame(a, b, -1);
}

TEST(RunStroke, TimesEachTickItRenders) {
  const std::vector<RenderInput> inputs = Stroke();
  auto renderer = BoxRenderer();
  const StrokeRun run = RunStroke(*renderer, inputs);
  // one time per input; what they are is the host's (only that they are durations)
  ASSERT_EQ(run.tick_us.size(), inputs.size());
  for (const double us : run.tick_us) {
    EXPECT_TRUE(std::isfinite(us));
    EXPECT_GE(us, 0.0);
  }
  const StrokeRun none = RunStroke(*renderer, {});
  EXPECT_TRUE(none.outputs.empty());
  EXPECT_TRUE(none.tick_us.empty());
}

}  // namespace
}  // namespace hapticad
