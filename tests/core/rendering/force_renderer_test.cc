// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/rendering/force_renderer.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hapticad/core/analysis/energy_observer.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

// A 100 mm box in mm; the top (+z, CAD face 5) is rubber-like, the rest untagged.
class RendererOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3);
    std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
    faces[5].friction.static_coefficient = 1.2;
    faces[5].friction.dynamic_coefficient = 1.0;
    faces[5].stiffness_n_per_m = 300.0;
    surfaces_ = std::make_shared<SurfaceTable>(faces);
    limits_.max_force_n = 8.0;
    limits_.max_stiffness_n_per_m = 3000.0;
  }
  RenderOutput Press(ForceRenderer& r, double depth_m, const Vec3& velocity = Vec3::Zero()) {
    RenderOutput out;
    r.Render({Vec3(0, 0, 0.06), Vec3::Zero()}, &out);
    r.Render({Vec3(0, 0, 0.05 - depth_m), velocity}, &out);
    return out;
  }
  std::shared_ptr<const HapticScene> scene_;
  std::shared_ptr<SurfaceTable> surfaces_;
  RenderLimits limits_;
};

TEST_F(RendererOnBox, NormalForceIsStiffnessTimesDepth) {
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out = Press(r, 0.002);
  EXPECT_TRUE(out.flags & kContact);
  EXPECT_EQ(out.cad_face, 5);
  EXPECT_NEAR(out.force_w.z(), 300.0 * 0.002, 1e-6);
  EXPECT_NEAR(out.normal_force_n, 0.6, 1e-6);
  EXPECT_NEAR(out.tangential_force_n, 0.0, 1e-12);
}

TEST_F(RendererOnBox, SlidingFrictionIsMuDynamicTimesNormal) {
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out = Press(r, 0.002, Vec3(0.05, 0.0, 0.0));
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 1.0, 1e-9);
  EXPECT_LT(out.force_w.x(), 0.0);  // opposes the motion
}

TEST_F(RendererOnBox, UsesEachFacesOwnProperties) {
  ForceRenderer r(scene_, surfaces_, limits_);
  RenderOutput out;
  r.Render({Vec3(0.06, 0, 0), Vec3::Zero()}, &out);
  r.Render({Vec3(0.049, 0, 0), Vec3(0, 0.05, 0)}, &out);
  EXPECT_EQ(out.cad_face, 1);
  EXPECT_NEAR(out.normal_force_n, 400.0 * 0.001, 1e-6);  // untagged: 0.4 N/mm
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 0.4, 1e-9);
}

TEST_F(RendererOnBox, ClampsForceToTheDeviceMaximum) {
  limits_.max_force_n = 1.0;
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out =
      Press(r, 0.010, Vec3(0.05, 0.0, 0.0));  // 3 N normal + 3 N friction asked
  EXPECT_TRUE(out.flags & kForceClamped);
  EXPECT_NEAR(out.force_w.norm(), 1.0, 1e-12);
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 1.0, 1e-9);  // direction kept
}

TEST_F(RendererOnBox, ClampsStiffnessToTheDeviceMaximum) {
  limits_.max_stiffness_n_per_m = 100.0;
  ForceRenderer r(scene_, surfaces_, limits_);
  const RenderOutput out = Press(r, 0.002);
  EXPECT_TRUE(out.flags & kStiffnessClamped);
  EXPECT_NEAR(out.normal_force_n, 0.2, 1e-6);
}

TEST_F(RendererOnBox, NonFiniteInputGivesZeroForceAndAFault) {
  ForceRenderer r(scene_, surfaces_, limits_);
  Press(r, 0.002);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  RenderOutput out;
  r.Render({Vec3(0, nan, 0.04), Vec3::Zero()}, &out);
  EXPECT_EQ(out.force_w, Vec3::Zero());
  EXPECT_TRUE(out.flags & kInputFault);
  r.Render({Vec3(0, 0, 0.048), Vec3(std::numeric_limits<double>::infinity(), 0, 0)}, &out);
  EXPECT_EQ(out.force_w, Vec3::Zero());
  // the proxy was not disturbed: the next good sample is felt normally
  r.Render({Vec3(0, 0, 0.048), Vec3::Zero()}, &out);
  EXPECT_NEAR(out.normal_force_n, 0.6, 1e-6);
}

TEST_F(RendererOnBox, FiniteButAbsurdInputGivesZeroForceAndAFaultNotNaN) {
  ForceRenderer r(scene_, surfaces_, limits_);
  Press(r, 0.002);
  RenderOutput pressed;
  r.Render({Vec3(0, 0, 0.048), Vec3::Zero()}, &pressed);
  ASSERT_GT(pressed.force_w.z(), 0.0);
  // 1e306 m and 1e5 m away, 1e306 m/s: the spring or the damper would overflow
  for (const RenderInput& input :
       {RenderInput{Vec3(0, 0, -1e306), Vec3::Zero()}, RenderInput{Vec3(1e5, 0, 0), Vec3::Zero()},
        RenderInput{Vec3(0, 0, 0.048), Vec3(0, 0, -1e306)}}) {
    RenderOutput out;
    r.Render(input, &out);
    EXPECT_EQ(out.force_w, Vec3::Zero()) << input.position_w.transpose();
    EXPECT_TRUE(out.flags & kInputFault);
    EXPECT_TRUE(out.proxy_w.allFinite());
  }
  // the proxy was not disturbed
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.048), Vec3::Zero()}, &out);
  EXPECT_EQ(out.force_w, pressed.force_w);
}

TEST_F(RendererOnBox, AForceTravelLawReplacesStiffnessTimesDepth) {
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  PushButtonParams button;                   // 1.47 N at 0.25 mm, snaps to 0.735 N
  button.bottom_stiffness_n_per_m = 4000.0;  // a housing the device renders as it is
  faces[5].force_travel = MakePushButton(button);
  limits_.max_stiffness_n_per_m = 10000.0;  // steeper than the snap: nothing clamped
  ForceRenderer r(scene_, std::make_shared<SurfaceTable>(faces), limits_);
  for (const auto& [depth, force] : {std::pair{0.1e-3, 0.588},
                                     {0.25e-3, 1.47},
                                     {0.35e-3, 0.735},
                                     {0.6e-3, 1.47},
                                     {0.8e-3, 2.27}}) {
    const RenderOutput out = Press(r, depth);
    // the proxy rests a fraction of a nanometre off the face: 1 nm of depth on the
    // steepest slope (7350 N/m) is 7e-6 N
    EXPECT_NEAR(out.normal_force_n, force, faces[5].force_travel->MaxSlope() * 1e-9) << depth;
    EXPECT_FALSE(out.flags & kStiffnessClamped) << depth;
  }
}

TEST_F(RendererOnBox, AForceTravelLawIsClampedToTheDeviceAndMakesNoEnergyThroughTheSnap) {
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  faces[5].force_travel = MakePushButton({});
  limits_.max_stiffness_n_per_m = 3000.0;
  ForceRenderer r(scene_, std::make_shared<SurfaceTable>(faces), limits_);
  EXPECT_TRUE(Press(r, 0.1e-3).flags & kStiffnessClamped);
  // stretched 2.45 x: the operating force 1.47 N comes at 0.61 mm instead of 0.25
  const double stretch = faces[5].force_travel->StretchSlope() / 3000.0;
  EXPECT_NEAR(Press(r, 0.25e-3 * stretch).normal_force_n, 1.47, 1e-4);
  // press through the snap to 0.8 mm and back at 1 kHz; the device damps as Colgate's
  // bound asks of the steepest slope rendered (b = K T / 2): the sampled law never
  // gives out more than it took
  const double period = 1e-3;
  EnergyObserver observer(limits_.max_stiffness_n_per_m * period / 2);
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.06), Vec3::Zero()}, &out);
  Vec3 x = Vec3(0, 0, 0.05);
  double previous_force = 0.0;
  for (int i = 1; i <= 2000; ++i) {
    const double depth = (i <= 1000 ? i : 2000 - i) * 0.8e-6;
    const Vec3 next(0, 0, 0.05 - depth);
    r.Render({x, Vec3::Zero()}, &out);
    EXPECT_LE(std::abs(out.normal_force_n - previous_force), 3000.0 * 0.8e-6 + 1e-9) << i;
    previous_force = out.normal_force_n;
    observer.Observe(out.force_w, x, next, period);
    x = next;
  }
  EXPECT_GE(observer.lowest_j(), -1e-12);
}

TEST_F(RendererOnBox, RenderDoesNotAllocate) {
  ForceRenderer r(scene_, surfaces_, limits_);
  Press(r, 0.002);
  RenderOutput out;
  testing::AllocationCounter counter;
  for (int i = 0; i < 1000; ++i) {
    r.Render({Vec3(-0.04 + 8e-5 * i, 0.01, 0.048), Vec3(0.08, 0, 0)}, &out);
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(out.flags & kContact);
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

// The 100 mm box with one tagged top face, configured per test, pressed 2 mm deep and
// stroked across at constant velocity.
class EffectsOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3);
    top_.friction.static_coefficient = 0.4;
    top_.friction.dynamic_coefficient = 0.3;
    top_.stiffness_n_per_m = 500.0;
    limits_.max_force_n = 8.0;
    limits_.max_stiffness_n_per_m = 3000.0;
  }
  ForceRenderer Make(std::vector<Vibration> vibrations = {}) {
    std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
    faces[5] = top_;
    return ForceRenderer(scene_, std::make_shared<SurfaceTable>(faces, std::move(vibrations)),
                         limits_);
  }
  // Strokes from x0 along `direction` at `speed` (m/s) for `ticks` at `rate` Hz, 2 mm deep.
  std::vector<RenderOutput> Stroke(ForceRenderer& r, const Vec3& direction, double speed, int ticks,
                                   double rate = 1000.0, double x0 = -0.03) {
    RenderOutput out;
    r.Render({Vec3(x0, 0.0, 0.06), Vec3::Zero(), 0.0}, &out);
    std::vector<RenderOutput> trace;
    for (int i = 0; i < ticks; ++i) {
      const double t = i / rate;
      const Vec3 p = Vec3(x0, 0.0, 0.048) + direction.normalized() * speed * t;
      r.Render({p, direction.normalized() * speed, t}, &out);
      trace.push_back(out);
    }
    return trace;
  }
  std::shared_ptr<const HapticScene> scene_;
  SurfaceProperties top_;
  RenderLimits limits_;
};

TEST_F(EffectsOnBox, LinearPatternGivesMuAlongAcrossAndEq3Between) {
  top_.pattern = LinearPattern{Vec3::UnitX()};
  top_.anisotropy.across_factor = 3.0;  // mu_n = 0.9
  auto r = Make();
  const struct {
    Vec3 direction;
    double mu;
  } cases[] = {
      {Vec3(1, 0, 0), 0.3}, {Vec3(0, 1, 0), 0.9}, {Vec3(1, 1, 0), 0.6}, {Vec3(-1, 1, 0), 0.6}};
  for (const auto& c : cases) {
    const RenderOutput out = Stroke(r, c.direction, 0.05, 100).back();
    EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, c.mu, 1e-9) << c.direction.transpose();
    EXPECT_NEAR(out.normal_force_n, 1.0, 1e-6);
  }
}

TEST_F(EffectsOnBox, CircularPatternIsIsotropicAtItsCentre) {
  top_.pattern = CircularPattern{Vec3(0, 0, 0.05), Vec3::UnitZ(), 1e-3};
  top_.anisotropy.across_factor = 3.0;
  auto r = Make();
  // crossing the centre along x: radial motion (across the circles) away from it,
  // isotropic mean right at it; never a jump or NaN
  const auto trace = Stroke(r, Vec3::UnitX(), 0.01, 6001, 1000.0, -0.03);
  double worst_step = 0.0;
  for (std::size_t i = 1; i < trace.size(); ++i) {
    ASSERT_TRUE(trace[i].force_w.allFinite());
    worst_step = std::max(worst_step, (trace[i].force_w - trace[i - 1].force_w).norm());
  }
  const RenderOutput& at_centre = trace[3000];  // x = 0
  EXPECT_NEAR(at_centre.tangential_force_n / at_centre.normal_force_n, 0.6, 1e-6);
  EXPECT_NEAR(trace[1000].tangential_force_n / trace[1000].normal_force_n, 0.9, 1e-9);
  EXPECT_LT(worst_step, 0.05);  // 10 um per tick: 0.3 N of friction change over 1 mm
}

TEST_F(EffectsOnBox, RoughnessShowsTheGridPeriodInTheForceSpectrum) {
  for (int category : {2, 4, 6}) {
    top_.roughness =
        MakeRoughnessGrid(category, SurfaceFrame{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()});
    auto r = Make();
    const auto trace = Stroke(r, Vec3::UnitX(), 0.05, 1200, 5000.0);  // 12 mm at 5 kHz
    const double g = top_.roughness->spacing_m;
    // amplitude of the normal force at spatial frequency f (1/m): detrended and
    // Hann-windowed projection, as seed 001 analyses its traces
    double mean = 0.0;
    for (const auto& o : trace) mean += o.normal_force_n / trace.size();
    auto amplitude = [&](double f) {
      double c = 0.0, s = 0.0, weight = 0.0;
      for (std::size_t i = 0; i < trace.size(); ++i) {
        const double x = -0.03 + 0.05 * i / 5000.0;
        const double w = 0.5 - 0.5 * std::cos(2 * M_PI * i / (trace.size() - 1));
        c += w * (trace[i].normal_force_n - mean) * std::cos(2 * M_PI * f * x);
        s += w * (trace[i].normal_force_n - mean) * std::sin(2 * M_PI * f * x);
        weight += w;
      }
      return std::hypot(c, s) * 2.0 / weight;
    };
    const double at_grid = amplitude(1.0 / g);
    EXPECT_NEAR(at_grid, 500.0 * top_.roughness->amplitude_m / 2.0, 0.2 * at_grid) << category;
    EXPECT_GT(at_grid, 10.0 * amplitude(1.37 / g)) << category;
    EXPECT_GT(at_grid, 10.0 * amplitude(0.61 / g)) << category;
  }
}

TEST_F(EffectsOnBox, ViscousGratingReplacesFrictionWithEq2InNewtons) {
  ViscousGrating grating{PaperPreset(1, 2),
                         SurfaceFrame{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()}};
  top_.texture = grating;
  auto r = Make();
  // across the ridges (along e2 = y) at 80 mm/s
  const auto trace = Stroke(r, Vec3::UnitY(), 0.08, 200, 1000.0, 0.0);
  for (std::size_t i = 50; i < trace.size(); i += 37) {
    const double y = 0.08 * i / 1000.0;
    const double level = ViscousTextureLevel(grating.params, y, 0.08);
    EXPECT_NEAR(trace[i].texture_force_n, level * 8.0, 1e-9) << i;
    EXPECT_NEAR(trace[i].tangential_force_n, level * 8.0 > 8.0 ? 0 : trace[i].texture_force_n,
                trace[i].normal_force_n + 1e-6);
    EXPECT_EQ(trace[i].friction_force_n, 0.0);
  }
  // a texture with its own full range: level 1 is 2 N whatever the device
  top_.texture->full_range_n = 2.0;
  auto own = Make();
  const RenderOutput out = Stroke(own, Vec3::UnitY(), 0.08, 120, 1000.0, 0.0).back();
  EXPECT_NEAR(out.texture_force_n,
              ViscousTextureLevel(grating.params, 0.08 * 119 / 1000.0, 0.08) * 2.0, 1e-9);
}

TEST_F(EffectsOnBox, AViscousGratingAsAFrictionLevelDragsInProportionToThePress) {
  ViscousGrating grating{PaperPreset(1, 1),
                         SurfaceFrame{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()}};
  grating.scale = TextureScale::kFrictionLevel;
  top_.texture = grating;
  // across the ridges at 80 mm/s, pressed 1 and 3 mm deep: level * mu_s * F_n, so the
  // deeper stroke drags three times as hard (as a force, both dragged the same 8 N * f)
  for (const double depth : {0.001, 0.003}) {
    auto r = Make();
    RenderOutput out;
    r.Render({Vec3(0, -0.03, 0.06), Vec3::Zero(), 0.0}, &out);
    for (int i = 0; i < 200; ++i) {
      const double y = -0.03 + 0.08 * i / 1000.0;
      r.Render({Vec3(0, y, 0.05 - depth), Vec3(0, 0.08, 0), i / 1000.0}, &out);
      if (i < 20) continue;
      const double level = std::clamp(ViscousTextureLevel(grating.params, y, 0.08), 0.0, 1.0);
      ASSERT_NEAR(out.normal_force_n, 500.0 * depth, 1e-6) << i;
      ASSERT_NEAR(out.texture_force_n, level * 0.4 * out.normal_force_n, 1e-12)
          << depth << " " << i;
      ASSERT_LT(out.texture_force_n, 0.4 * out.normal_force_n + 1e-12) << i;
    }
  }
}

TEST_F(EffectsOnBox, APatternScalesAViscousGratingAsItScalesFriction) {
  // stripes along x with twice the friction across them, and a grating stroked across its
  // bars along x, then (turned) along y: across the stripes it drags twice as hard as
  // along them, as a force and as a friction level alike (it ignored the pattern)
  top_.pattern = LinearPattern{Vec3::UnitX()};
  top_.anisotropy.across_factor = 2.0;
  for (const TextureScale scale : {TextureScale::kDeviceForce, TextureScale::kFrictionLevel}) {
    double drag[2] = {};
    for (int across = 0; across < 2; ++across) {
      const Vec3 direction = across ? Vec3::UnitY() : Vec3::UnitX();
      // the grating's coordinate (its frame's e2) along the stroke, the frame's normal +z
      ViscousGrating grating{
          PaperPreset(1, 1),
          SurfaceFrame{Vec3(0, 0, 0.05), direction.cross(Vec3::UnitZ()), direction}};
      grating.scale = scale;
      grating.full_range_n = 2.0;
      top_.texture = grating;
      auto r = Make();
      const auto trace = Stroke(r, direction, 0.08, 200, 1000.0, 0.0);
      for (int i = 20; i < 200; ++i) drag[across] += trace[i].texture_force_n;
    }
    ASSERT_GT(drag[0], 0.0);
    EXPECT_NEAR(drag[1] / drag[0], 2.0, 1e-9) << static_cast<int>(scale);
  }
}

TEST_F(EffectsOnBox, VibrationShakesOnlyWhileTouched) {
  top_.vibration = 0;
  auto r = Make({Vibration{100.0, 0.25, Vec3::UnitZ(), true}});
  const auto trace = Stroke(r, Vec3::UnitX(), 0.0, 40, 1000.0);
  EXPECT_NEAR(trace[2].vibration_force_n, 0.25 * std::sin(2 * M_PI * 100 * 0.002),
              1e-9);  // t = 2 ms
  EXPECT_NEAR(trace[2].force_w.z(), 1.0 + 0.25 * std::sin(2 * M_PI * 100 * 0.002), 1e-6);
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.07), Vec3::Zero(), 0.0025}, &out);  // lifted off
  EXPECT_EQ(out.force_w, Vec3::Zero());
}

TEST_F(EffectsOnBox, FrictionConeSticksThenSlips) {
  top_.friction_mode = FrictionMode::kCone;
  auto r = Make();
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.06), Vec3::Zero(), 0}, &out);
  r.Render({Vec3(0, 0, 0.048), Vec3::Zero(), 0}, &out);  // 2 mm deep: F_n = 1 N
  ASSERT_TRUE(out.flags & kSticking);
  // drag 0.5 mm: still inside the static cone (0.4 * 2 mm = 0.8 mm): spring k dx
  r.Render({Vec3(0.0005, 0, 0.048), Vec3(0.01, 0, 0), 0}, &out);
  EXPECT_TRUE(out.flags & kSticking);
  EXPECT_NEAR(out.force_w.x(), -500.0 * 0.0005, 1e-9);
  // past 0.8 mm it slips and the friction drops to mu_d F_n
  for (int i = 1; i <= 20; ++i)
    r.Render({Vec3(0.0005 + 0.0002 * i, 0, 0.048), Vec3(0.2, 0, 0), 0}, &out);
  EXPECT_FALSE(out.flags & kSticking);
  EXPECT_NEAR(-out.force_w.x() / out.force_w.z(), 0.3, 1e-6);
  // stopping: the device falls back inside the cone and sticks again
  for (int i = 0; i < 3; ++i)
    r.Render({Vec3(0.0045 - 0.0003 * i, 0, 0.048), Vec3(-0.3, 0, 0), 0}, &out);
  EXPECT_TRUE(out.flags & kSticking);
}

TEST_F(EffectsOnBox, AFrictionConeSlideThatStopsSticksAndBreaksAwayAgainAtMuS) {
  top_.friction_mode = FrictionMode::kCone;
  auto r = Make();
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.06), Vec3::Zero(), 0}, &out);
  double t = 0.0;
  // slides 5 mm along +x at 20 mm/s, 2 mm deep (F_n = 1 N; cones 0.8 and 0.6 mm)
  double x = 0.0;
  const auto move = [&](double speed, int ticks, double* peak) {
    for (int i = 0; i < ticks; ++i) {
      x += speed * 1e-3;
      t += 1e-3;
      r.Render({Vec3(x, 0, 0.048), Vec3(speed, 0, 0), t}, &out);
      if (peak) *peak = std::max(*peak, -out.force_w.x() / out.force_w.z());
    }
  };
  double first = 0.0;
  move(0.02, 250, &first);
  EXPECT_NEAR(first, 0.4, 1e-3);  // broke away at mu_s
  EXPECT_FALSE(out.flags & kSticking);
  EXPECT_NEAR(-out.force_w.x() / out.force_w.z(), 0.3, 1e-6);
  // the hand stops where it is, still pulled back at mu_d: it sticks there
  move(0.0, 100, nullptr);
  EXPECT_TRUE(out.flags & kSticking);
  EXPECT_NEAR(-out.force_w.x() / out.force_w.z(), 0.3, 1e-6);
  // and setting off again in the same direction breaks away at mu_s again, not mu_d
  double second = 0.0;
  move(0.02, 250, &second);
  EXPECT_NEAR(second, 0.4, 1e-3);
  EXPECT_FALSE(out.flags & kSticking);
  EXPECT_NEAR(-out.force_w.x() / out.force_w.z(), 0.3, 1e-6);
  // a hand that only slows (above the stick speed) slides on
  move(0.004, 100, nullptr);
  EXPECT_FALSE(out.flags & kSticking);
}

TEST_F(EffectsOnBox, VelocitySignFlipsEveryTickStayBoundedAndFinite) {
  auto r = Make();
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.06), Vec3::Zero(), 0}, &out);
  for (int i = 0; i < 2000; ++i) {
    const double v =
        (i % 2 ? 1.0 : -1.0) * (i % 7 == 0 ? 1e-300 : 0.002);  // exactly eps, then tiny
    r.Render({Vec3(1e-9 * (i % 2), 0, 0.048), Vec3(v, 0, 0), i * 1e-3}, &out);
    ASSERT_TRUE(out.force_w.allFinite());
    ASSERT_LE(out.tangential_force_n, 0.4 * out.normal_force_n * (1 + 1e-9));
  }
}

TEST_F(EffectsOnBox, ExtremeCoefficientsAreClampedNotNaN) {
  top_.friction.static_coefficient = 1e3;
  top_.friction.dynamic_coefficient = 2e3;  // mu_d > mu_s
  top_.pattern = LinearPattern{Vec3::UnitX()};
  auto r = Make();
  const RenderOutput out = Stroke(r, Vec3(1, 1, 0), 0.05, 50).back();
  EXPECT_TRUE(out.force_w.allFinite());
  EXPECT_NEAR(out.force_w.norm(), 8.0, 1e-9);
  EXPECT_TRUE(out.flags & kForceClamped);
  top_.friction.static_coefficient = 0.0;
  top_.friction.dynamic_coefficient = 0.0;
  auto frictionless = Make();
  EXPECT_NEAR(Stroke(frictionless, Vec3(1, 1, 0), 0.05, 50).back().tangential_force_n, 0.0, 1e-12);
}

TEST_F(EffectsOnBox, NonFiniteInputWithEveryEffectGivesZeroForceAndAFault) {
  top_.pattern = CircularPattern{Vec3(0, 0, 0.05), Vec3::UnitZ(), 1e-3};
  top_.roughness =
      MakeRoughnessGrid(5, SurfaceFrame{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()});
  top_.vibration = 0;
  top_.force_travel = MakePushButton({});
  auto r = Make({Vibration{150.0, 0.3, Vec3::UnitX(), true}});
  Stroke(r, Vec3::UnitX(), 0.05, 10);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const RenderInput& bad : {RenderInput{Vec3(nan, 0, 0.048), Vec3::Zero(), 0.01},
                                 RenderInput{Vec3(0, 0, 0.048), Vec3(0, inf, 0), 0.01},
                                 RenderInput{Vec3(0, 0, 0.048), Vec3::Zero(), nan}}) {
    RenderOutput out;
    r.Render(bad, &out);
    EXPECT_EQ(out.force_w, Vec3::Zero());
    EXPECT_TRUE(out.flags & kInputFault);
  }
}

TEST_F(EffectsOnBox, EveryEffectRendersWithoutAllocating) {
  std::vector<Vec2> poles = {Vec2(0, -0.05), Vec2(0.01, 0.0), Vec2(0.0, 0.05)};
  top_.pattern = std::make_shared<const CurvePattern>(CurvePattern::Build(
      PatternPlane{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()},
      NurbsCurve2(2, {0, 0, 0, 1, 1, 1}, poles, {}), 64, CurvePattern::Evaluation::kExact));
  top_.roughness =
      MakeRoughnessGrid(5, SurfaceFrame{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()});
  top_.texture = ViscousGrating{PaperPreset(2, 0),
                                SurfaceFrame{Vec3(0, 0, 0.05), Vec3::UnitX(), Vec3::UnitY()}};
  top_.vibration = 0;
  top_.force_travel = MakePushButton({});
  auto r = Make({Vibration{150.0, 0.3, Vec3::UnitX(), true}});
  Stroke(r, Vec3::UnitX(), 0.05, 5);
  testing::AllocationCounter counter;
  const auto before = counter.count();
  RenderOutput out;
  for (int i = 0; i < 1000; ++i)
    r.Render({Vec3(-0.02 + 4e-5 * i, 0.001, 0.048), Vec3(0.04, 0.01, 0), i * 1e-3}, &out);
  EXPECT_EQ(counter.count(), before);
  EXPECT_TRUE(out.flags & kContact);
  top_.texture.reset();
  top_.friction_mode = FrictionMode::kCone;
  auto cone = Make({Vibration{150.0, 0.3, Vec3::UnitX(), true}});
  Stroke(cone, Vec3::UnitX(), 0.05, 5);
  testing::AllocationCounter cone_counter;
  for (int i = 0; i < 1000; ++i)
    cone.Render({Vec3(-0.02 + 4e-5 * i, 0.001, 0.048), Vec3(0.04, 0.01, 0), i * 1e-3}, &out);
  EXPECT_EQ(cone_counter.count(), 0u);
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

TEST_F(RendererOnBox, APropertyEditIsInEffectAtTheNextTickWithoutARebuild) {
  ForceRenderer r(scene_, surfaces_, limits_);
  const HapticScene* scene_before = &r.scene();
  RenderOutput out = Press(r, 0.002, Vec3(0.05, 0.0, 0.0));
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 1.0, 1e-9);  // rubber, mu_d 1
  const Vec3 proxy = out.proxy_w;
  // the designer makes the top slippery while sliding
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  faces[5].friction.static_coefficient = 0.3;
  faces[5].friction.dynamic_coefficient = 0.2;
  faces[5].stiffness_n_per_m = 300.0;
  r.SetSurfaces(std::make_shared<SurfaceTable>(faces));
  {
    testing::AllocationCounter counter;
    r.Render({Vec3(0.00005, 0, 0.048), Vec3(0.05, 0.0, 0.0), 0.002}, &out);
    EXPECT_EQ(counter.count(), 0u);  // taking the new table allocates nothing
  }
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 0.2, 1e-9);  // the very next tick
  EXPECT_EQ(&r.scene(), scene_before);                                  // no new scene
  EXPECT_NEAR((out.proxy_w - proxy).norm(), 0.00005, 1e-12);            // the proxy went on
  EXPECT_THROW(r.SetSurfaces(nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

TEST_F(RendererOnBox, DampingResistsPressingAndSpringingBackButNeverPulls) {
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  faces[5].stiffness_n_per_m = 300.0;
  faces[5].friction.static_coefficient = 0.0;
  faces[5].friction.dynamic_coefficient = 0.0;
  faces[5].damping_n_s_per_m = 0.4;
  ForceRenderer r(scene_, std::make_shared<SurfaceTable>(faces), limits_);
  // pressing in at 0.1 m/s, 2 mm deep: k d + B v
  RenderOutput out = Press(r, 0.002, Vec3(0, 0, -0.1));
  EXPECT_NEAR(out.force_w.z(), 300.0 * 0.002 + 0.4 * 0.1, 1e-6);  // (the proxy's offset: 5e-8 N)
  // springing back out at 0.1 m/s: k d - B v
  r.Render({Vec3(0, 0, 0.048), Vec3(0, 0, 0.1)}, &out);
  EXPECT_NEAR(out.force_w.z(), 300.0 * 0.002 - 0.4 * 0.1, 1e-6);
  // out fast, barely in: the damper would pull; the force stays zero instead
  r.Render({Vec3(0, 0, 0.0499), Vec3(0, 0, 1.0)}, &out);
  EXPECT_TRUE(out.flags & kContact);
  EXPECT_EQ(out.force_w.z(), 0.0);
  // more damping than the device allows is capped, and said so
  faces[5].damping_n_s_per_m = 5.0;
  r.SetSurfaces(std::make_shared<SurfaceTable>(faces));
  r.Render({Vec3(0, 0, 0.048), Vec3(0, 0, -0.1)}, &out);
  EXPECT_TRUE(out.flags & kDampingClamped);
  EXPECT_NEAR(out.force_w.z(), 300.0 * 0.002 + limits_.max_damping_n_s_per_m * 0.1, 1e-6);
  faces[5].damping_n_s_per_m = -1.0;
  EXPECT_THROW(SurfaceTable{faces}, std::invalid_argument);
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

TEST_F(RendererOnBox, APartWoundInsideOutPushesOutADeviceThatStartsInIt) {
  // the same box as a file that lists its triangles clockwise hands it over; alone, and
  // with a sheet beside it (where inside is known piece by piece, from how each winds)
  for (const bool sheet : {false, true}) {
    TriangleSoup inside_out = testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50));
    for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
    if (sheet) {
      const TriangleSoup beside = testing::MakeSheetSoup(40.0, 0.0);
      const auto base = static_cast<std::int32_t>(inside_out.vertices.size());
      for (const Vec3& v : beside.vertices) inside_out.vertices.push_back(v + Vec3(200, 0, 0));
      for (const auto& t : beside.triangles) {
        inside_out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
        inside_out.cad_faces.push_back(0);
      }
    }
    scene_ = HapticScene::Build(inside_out, 1e-3);
    EXPECT_EQ(scene_->repair_report().inside_out_shells, 1u);
    ForceRenderer r(scene_, surfaces_, limits_);
    // the device starts 5 mm under the rubber top, or on it: the proxy goes out through it
    for (const double depth : {0.005, 0.0}) {
      const Vec3 device(0.01, 0.02, 0.05 - depth);
      r.Reset(device);
      RenderOutput out;
      r.Render({device, Vec3::Zero()}, &out);
      const std::string where = (sheet ? "with a sheet, " : "alone, ") + std::to_string(depth);
      EXPECT_GT(out.proxy_w.z(), 0.05) << where;
      EXPECT_NEAR(out.proxy_w.z(), 0.05, 1e-6) << where;
      EXPECT_NEAR(out.force_w.z(), 300.0 * depth, 1e-5) << where;
      EXPECT_NEAR(out.force_w.head<2>().norm(), 0.0, 1e-9) << where;
    }
  }
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

// A property edit under the hand: the top's push blends from what was felt to the
// edited face's over ContactOptions::edit_ramp_s, and never steps.
class EditUnderTheHand : public RendererOnBox {
 protected:
  std::shared_ptr<SurfaceTable> Top(double stiffness_n_per_m) {
    std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
    faces[5].stiffness_n_per_m = stiffness_n_per_m;
    return std::make_shared<SurfaceTable>(faces);
  }
  // Holds the device `depth_m` into the top from tick `first` to `last` (1 kHz),
  // returning the normal forces.
  std::vector<double> Hold(ForceRenderer& r, int first, int last, double depth_m,
                           std::uint32_t* flags = nullptr) {
    std::vector<double> forces;
    RenderOutput out;
    for (int i = first; i <= last; ++i) {
      r.Render({Vec3(0, 0, 0.05 - depth_m), Vec3::Zero(), i * 1e-3}, &out);
      EXPECT_TRUE(out.flags & kContact) << i;
      forces.push_back(out.normal_force_n);
      if (flags != nullptr) *flags |= out.flags;
    }
    return forces;
  }
};

TEST_F(EditUnderTheHand, AStiffnessEditBlendsOverTheRampInsteadOfSteppingInOneTick) {
  for (const auto& [before, after] : {std::pair{300.0, 3000.0}, {3000.0, 300.0}}) {
    ForceRenderer r(scene_, Top(before), limits_);
    RenderOutput out;
    r.Render({Vec3(0, 0, 0.06), Vec3::Zero(), 0.0}, &out);
    const double felt = Hold(r, 1, 50, 0.002).back();
    EXPECT_NEAR(felt, before * 0.002, 1e-6);
    r.SetSurfaces(Top(after));
    const std::vector<double> forces = Hold(r, 51, 400, 0.002);
    // the tick that takes the edit feels what was felt; each tick after moves a
    // 200th of the way (0.2 s at 1 kHz), always the same way
    EXPECT_NEAR(forces.front(), felt, 1e-9);
    const double step = std::abs(after - before) * 0.002 / 200.0;
    double previous = felt;
    for (std::size_t i = 0; i < forces.size(); ++i) {
      EXPECT_LE(std::abs(forces[i] - previous), step + 1e-6) << i;  // (the proxy's offset)
      EXPECT_GE((forces[i] - previous) * (after - before), 0.0) << i;
      previous = forces[i];
    }
    // halfway through, halfway there; at the ramp's end, the edited face's
    EXPECT_NEAR(forces[100], 0.5 * (before + after) * 0.002, 1e-6);
    EXPECT_NEAR(forces[200], after * 0.002, 1e-6);
    EXPECT_NEAR(forces.back(), after * 0.002, 1e-6);
  }
}

TEST_F(EditUnderTheHand, TheBlendSaysSoAndEndsAfterTheRamp) {
  ForceRenderer r(scene_, Top(300.0), limits_);
  Hold(r, 0, 10, 0.002);
  r.SetSurfaces(Top(600.0));
  RenderOutput out;
  std::uint32_t during = 0;
  {
    testing::AllocationCounter counter;
    for (int i = 11; i <= 100; ++i) {
      r.Render({Vec3(0, 0, 0.048), Vec3::Zero(), i * 1e-3}, &out);
      during |= out.flags;
    }
    EXPECT_EQ(counter.count(), 0u);  // taking the edit and blending allocate nothing
  }
  EXPECT_TRUE(during & kEditBlending);
  std::uint32_t after = 0;
  Hold(r, 212, 300, 0.002, &after);
  EXPECT_FALSE(after & kEditBlending);
}

TEST_F(EditUnderTheHand, AnEditThatLeavesTheTouchedFaceAloneChangesNothingFelt) {
  ForceRenderer r(scene_, Top(300.0), limits_);
  const double felt = Hold(r, 0, 10, 0.002).back();
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  faces[5].stiffness_n_per_m = 300.0;
  faces[0].stiffness_n_per_m = 50.0;  // the bottom, away from the hand
  r.SetSurfaces(std::make_shared<SurfaceTable>(faces));
  std::uint32_t flags = 0;
  for (const double f : Hold(r, 11, 30, 0.002, &flags)) EXPECT_EQ(f, felt);
  EXPECT_FALSE(flags & kEditBlending);
}

TEST_F(EditUnderTheHand, AnEditMidRampBlendsOnFromWhatWasFelt) {
  ForceRenderer r(scene_, Top(300.0), limits_);
  Hold(r, 0, 10, 0.002);
  r.SetSurfaces(Top(3000.0));
  const double felt = Hold(r, 11, 60, 0.002).back();  // a quarter of the way up
  EXPECT_GT(felt, 0.6 + 1.0);
  r.SetSurfaces(Top(100.0));  // the designer drags the slider back down
  const std::vector<double> forces = Hold(r, 61, 300, 0.002);
  EXPECT_NEAR(forces.front(), felt, 1e-9);
  EXPECT_NEAR(forces.back(), 100.0 * 0.002, 1e-6);
}

TEST_F(EditUnderTheHand, AnEditMadeAwayFromThePartIsFeltAtOnceOnTheNextTouch) {
  ForceRenderer r(scene_, Top(300.0), limits_);
  Hold(r, 0, 10, 0.002);
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.06), Vec3::Zero(), 0.011}, &out);  // lifted off
  r.SetSurfaces(Top(1000.0));
  std::uint32_t flags = 0;
  EXPECT_NEAR(Hold(r, 12, 12, 0.002, &flags).front(), 2.0, 1e-6);
  EXPECT_FALSE(flags & kEditBlending);
}

TEST_F(EditUnderTheHand, APushButtonLawBlendsIntoASpringFromWhereTheLawWas) {
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  faces[5].force_travel = MakePushButton({});  // 0.735 N past the snap, at 0.35 mm
  limits_.max_stiffness_n_per_m = 10000.0;
  ForceRenderer r(scene_, std::make_shared<SurfaceTable>(faces), limits_);
  const double felt = Hold(r, 0, 10, 0.35e-3).back();
  EXPECT_NEAR(felt, 0.735, 1e-3);
  r.SetSurfaces(Top(5000.0));  // 1.75 N there
  const std::vector<double> forces = Hold(r, 11, 300, 0.35e-3);
  EXPECT_NEAR(forces.front(), felt, 1e-9);
  EXPECT_NEAR(forces.back(), 5000.0 * 0.35e-3, 1e-6);
}

// A law nearly flat where the hand is and steep beyond: (1 mm, 3 mN), (2 mm, 3 N).
std::shared_ptr<SurfaceTable> FlatThenSteep() {
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  ForceTravel law;
  law.points = 2;
  law.travel_m = {1e-3, 2e-3};
  law.force_n = {0.003, 3.0};
  faces[5].force_travel = law;
  return std::make_shared<SurfaceTable>(faces);
}

TEST_F(EditUnderTheHand, BlendingDownIsNeverSteeperThanTheDeviceRendersStably) {
  // from the device's stiffest spring (3 N at 1 mm) to a law that pushes 3 mN there:
  // scaling that law up to 3 N would make its steep part 1000 times too stiff. The
  // scale is held to k_max over the law's steepest slope, so the push steps down
  // (no energy added) and the hand pressing on feels no more than k_max
  ForceRenderer r(scene_, Top(3000.0), limits_);
  EXPECT_NEAR(Hold(r, 0, 10, 0.001).back(), 3.0, 1e-6);
  r.SetSurfaces(FlatThenSteep());
  RenderOutput out;
  for (int i = 11; i <= 250; ++i) {
    // presses on to 1.8 mm and back; at each tick the push's slope there, probed 10 um
    // deeper at the same moment
    const double depth = 0.001 + 0.0008 * std::pow(std::sin(0.05 * (i - 11)), 2);
    r.Render({Vec3(0, 0, 0.05 - depth), Vec3::Zero(), i * 1e-3}, &out);
    const double push = out.normal_force_n;
    EXPECT_LE(push, 3000.0 * depth * (1.0 + 1e-6)) << i;
    r.Render({Vec3(0, 0, 0.05 - depth - 1e-5), Vec3::Zero(), i * 1e-3}, &out);
    EXPECT_LE((out.normal_force_n - push) / 1e-5, 3000.0 * (1.0 + 1e-6)) << i;
    if (i == 11) {
      EXPECT_LT(push, 0.01);  // stepped down from 3 N, not held there
      EXPECT_TRUE(out.flags & kEditBlending);
    }
  }
}

TEST_F(EditUnderTheHand, WhereTheEditedFacePushesNothingItsPushIsFeltAtOnce) {
  std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
  ForceTravel law;  // a free stretch to 1 mm, then 400 N/m
  law.points = 2;
  law.travel_m = {1e-3, 2e-3};
  law.force_n = {0.0, 0.4};
  faces[5].force_travel = law;
  ForceRenderer r(scene_, Top(400.0), limits_);
  EXPECT_NEAR(Hold(r, 0, 10, 0.0009).back(), 0.36, 1e-6);
  r.SetSurfaces(std::make_shared<SurfaceTable>(faces));
  std::uint32_t flags = 0;
  EXPECT_NEAR(Hold(r, 11, 11, 0.0009, &flags).front(), 0.0, 1e-9);  // a step down: no energy added
  EXPECT_FALSE(flags & kEditBlending);
  EXPECT_NEAR(Hold(r, 12, 12, 0.0015).front(), 0.2, 1e-6);  // the law, unscaled
}

TEST_F(EditUnderTheHand, SlidingOntoAnotherFaceEndsTheBlend) {
  // the box's top made of two CAD faces, one triangle each (5 and a new 6), both
  // 3000 N/m; face 5 is made soft while pressed, and the hand slides onto face 6,
  // which was not edited: it pushes its own 3000 N/m, not face 5's blend
  TriangleSoup soup = testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50));
  std::vector<Vec3> centres;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    if (soup.cad_faces[t] != 5) continue;
    if (!centres.empty()) soup.cad_faces[t] = 6;
    const auto& tri = soup.triangles[t];
    centres.push_back((soup.vertices[tri[0]] + soup.vertices[tri[1]] + soup.vertices[tri[2]]) *
                      (1e-3 / 3));
  }
  ASSERT_EQ(centres.size(), 2u);
  const auto scene = HapticScene::Build(soup, 1e-3);
  const auto table = [](double top) {
    std::vector<SurfaceProperties> faces(7, kUntaggedSurface);
    faces[5].stiffness_n_per_m = top;
    faces[6].stiffness_n_per_m = 3000.0;
    return std::make_shared<SurfaceTable>(faces);
  };
  ForceRenderer r(scene, table(3000.0), limits_);
  const Vec3 down(0, 0, -0.001);  // 1 mm into the top
  RenderOutput out;
  r.Render({centres[0] + Vec3(0, 0, 0.01), Vec3::Zero(), 0.0}, &out);
  r.Render({centres[0] + down, Vec3::Zero(), 0.001}, &out);
  ASSERT_EQ(out.cad_face, 5);
  r.SetSurfaces(table(30.0));
  r.Render({centres[0] + down, Vec3::Zero(), 0.002}, &out);
  EXPECT_TRUE(out.flags & kEditBlending);
  for (int i = 3; i <= 40; ++i) {
    const double t = (i - 3) / 37.0;
    r.Render({centres[0] + t * (centres[1] - centres[0]) + down, Vec3::Zero(), i * 1e-3}, &out);
  }
  ASSERT_EQ(out.cad_face, 6);
  EXPECT_FALSE(out.flags & kEditBlending);
  EXPECT_NEAR(out.normal_force_n, 3.0, 1e-5);
}

TEST_F(EditUnderTheHand, AClockThatGoesBackRestartsTheBlendFromThere) {
  ForceRenderer r(scene_, Top(300.0), limits_);
  Hold(r, 100, 110, 0.002);
  r.SetSurfaces(Top(600.0));
  Hold(r, 111, 150, 0.002);
  // the clock restarts at 0 (a caller's new run): the blend goes on from there, and ends
  const std::vector<double> forces = Hold(r, 0, 300, 0.002);
  EXPECT_NEAR(forces.back(), 1.2, 1e-6);
}

TEST_F(EditUnderTheHand, ANoughtRampStepsAtOnceAndABadOneIsRefused) {
  ContactOptions options;
  options.edit_ramp_s = 0.0;
  ForceRenderer r(scene_, Top(300.0), limits_, options);
  Hold(r, 0, 10, 0.002);
  r.SetSurfaces(Top(1000.0));
  EXPECT_NEAR(Hold(r, 11, 11, 0.002).front(), 2.0, 1e-6);
  for (const double bad :
       {-0.1, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    options.edit_ramp_s = bad;
    EXPECT_THROW(ForceRenderer(scene_, Top(300.0), limits_, options), std::invalid_argument);
  }
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

// A workspace scaled into the world (RenderLimits::workspace_scale = 2: a handle's 1 mm
// is 2 mm of the part): what a face is given to feel is felt at the handle.
class ScaledWorkspace : public RendererOnBox {
 protected:
  static constexpr double kScale = 2.0;
  void SetUp() override {
    RendererOnBox::SetUp();
    limits_.workspace_scale = kScale;
  }
  std::shared_ptr<SurfaceTable> Top(const SurfaceProperties& top) {
    std::vector<SurfaceProperties> faces(6, kUntaggedSurface);
    faces[5] = top;
    return std::make_shared<SurfaceTable>(faces);
  }
  // Pressed `handle_depth_m` into the top as the handle moves (kScale times that in the
  // world), at `handle_velocity` (m/s of the handle).
  RenderOutput PressHandle(ForceRenderer& r, double handle_depth_m,
                           const Vec3& handle_velocity = Vec3::Zero()) {
    return Press(r, kScale * handle_depth_m, kScale * handle_velocity);
  }
};

TEST_F(ScaledWorkspace, AFacesStiffnessIsFeltAtTheHandleNotInTheWorld) {
  // the top's 300 N/m: 0.3 N for the handle's 1 mm, though it went 2 mm into the part
  ForceRenderer r(scene_, surfaces_, limits_);
  RenderOutput out = PressHandle(r, 0.001);
  EXPECT_FALSE(out.flags & kStiffnessClamped);
  EXPECT_NEAR(out.normal_force_n, 300.0 * 0.001, 1e-6);  // (the proxy's offset: 3e-8 N)
  // past the device's stable stiffness, felt at that limit at the handle, and said so
  limits_.max_stiffness_n_per_m = 200.0;
  ForceRenderer clamped(scene_, surfaces_, limits_);
  out = PressHandle(clamped, 0.001);
  EXPECT_TRUE(out.flags & kStiffnessClamped);
  EXPECT_NEAR(out.normal_force_n, 200.0 * 0.001, 1e-6);
  // friction is mu times that push, in newtons as at scale 1
  out = PressHandle(r, 0.001, Vec3(0.05, 0, 0));
  EXPECT_NEAR(out.tangential_force_n / out.normal_force_n, 1.0, 1e-9);
}

TEST_F(ScaledWorkspace, AFacesDampingIsFeltAgainstTheHandlesSpeed) {
  SurfaceProperties top = kUntaggedSurface;
  top.stiffness_n_per_m = 300.0;
  top.friction.static_coefficient = 0.0;
  top.friction.dynamic_coefficient = 0.0;
  top.damping_n_s_per_m = 0.4;
  ForceRenderer r(scene_, Top(top), limits_);
  // pressing in at 0.1 m/s of the handle (0.2 m/s in the world), 1 mm deep: k d + B v
  const RenderOutput out = PressHandle(r, 0.001, Vec3(0, 0, -0.1));
  EXPECT_NEAR(out.normal_force_n, 300.0 * 0.001 + 0.4 * 0.1, 1e-6);
}

TEST_F(ScaledWorkspace, AForceTravelLawIsPressedByTheHandlesDepth) {
  SurfaceProperties top = kUntaggedSurface;
  PushButtonParams button;                   // 1.47 N at 0.25 mm, snaps to 0.735 N
  button.bottom_stiffness_n_per_m = 4000.0;  // a housing the device renders as it is
  top.force_travel = MakePushButton(button);
  limits_.max_stiffness_n_per_m = 10000.0;  // steeper than the snap: nothing clamped
  ForceRenderer r(scene_, Top(top), limits_);
  for (const auto& [depth, force] : {std::pair{0.1e-3, 0.588},
                                     {0.25e-3, 1.47},
                                     {0.35e-3, 0.735},
                                     {0.6e-3, 1.47},
                                     {0.8e-3, 2.27}}) {
    const RenderOutput out = PressHandle(r, depth);
    // the proxy's offset, 1e-10 m in the world, is 5e-11 m of the handle on 7350 N/m
    EXPECT_NEAR(out.normal_force_n, force, top.force_travel->MaxSlope() * 1e-9) << depth;
    EXPECT_FALSE(out.flags & kStiffnessClamped) << depth;
  }
  // the device's 3 N/mm at the handle stretches the handle's travel, not the world's:
  // the operating force comes at 0.25 mm x 2.45 of the handle
  limits_.max_stiffness_n_per_m = 3000.0;
  ForceRenderer clamped(scene_, Top(top), limits_);
  const double stretch = top.force_travel->StretchSlope() / 3000.0;
  const RenderOutput out = PressHandle(clamped, 0.25e-3 * stretch);
  EXPECT_TRUE(out.flags & kStiffnessClamped);
  EXPECT_NEAR(out.normal_force_n, 1.47, 1e-4);
}

TEST_F(ScaledWorkspace, ANonPositiveOrNonFiniteScaleIsRefused) {
  for (const double bad : {0.0, -2.0, std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    limits_.workspace_scale = bad;
    EXPECT_THROW(ForceRenderer(scene_, surfaces_, limits_), std::invalid_argument) << bad;
  }
}

// Stroked 2 mm deep (1 N) at 50 mm/s with mu_d 0.3: a 1.5 N vibration along the normal
// loads and unloads the contact, and the friction follows the load it leaves: never a drag
// without a push (it was 0.3 N of drag with no push at all, where the shake took it away).
TEST_F(EffectsOnBox, FrictionFollowsTheLoadAVibrationLeaves) {
  top_.vibration = 0;
  auto r = Make({Vibration{100.0, 1.5, Vec3::UnitZ(), true}});
  int unloaded = 0, loaded = 0;
  for (const RenderOutput& out : Stroke(r, Vec3::UnitX(), 0.05, 200)) {
    if (!(out.flags & kContact)) continue;
    EXPECT_LE(out.tangential_force_n, 0.3 * out.normal_force_n + 1e-9);
    if (out.normal_force_n == 0.0) {
      ++unloaded;
      EXPECT_EQ(out.tangential_force_n, 0.0);
    } else if (out.normal_force_n > 1.2) {  // pushed harder: the drag grows with it
      ++loaded;
      EXPECT_NEAR(out.tangential_force_n, 0.3 * out.normal_force_n, 1e-6);
    }
  }
  EXPECT_GT(unloaded, 20);
  EXPECT_GT(loaded, 20);
}

// The top's 500 N/m pressed 0.2 mm pushes 0.1 N; a 0.3 N vibration rides on it.
TEST_F(EffectsOnBox, AVibrationStrongerThanThePushIsFeltAsItsHalfWaveNeverPullingIn) {
  top_.vibration = 0;
  for (const Vec3& axis : {Vec3(Vec3::UnitZ()), Vec3(Vec3(1, 0, 1).normalized())}) {
    auto r = Make({Vibration{100.0, 0.3, axis, true}});
    RenderOutput out;
    r.Render({Vec3(0, 0, 0.06), Vec3::Zero(), 0.0}, &out);
    double lowest = 1.0;
    for (int i = 1; i <= 40; ++i) {  // four periods at 1 kHz
      const double t = i * 1e-3;
      r.Render({Vec3(0, 0, 0.0498), Vec3::Zero(), t}, &out);
      const double shake = 0.3 * std::sin(2 * M_PI * 100.0 * t);
      // along the normal: the push and the vibration where they push, nothing where the
      // vibration would pull; across the face the vibration as it is
      EXPECT_NEAR(out.normal_force_n, std::max(0.1 + shake * axis.z(), 0.0), 1e-6) << i;
      EXPECT_GE(out.force_w.z(), 0.0) << i;
      EXPECT_NEAR(out.force_w.x(), shake * axis.x(), 1e-9) << i;
      lowest = std::min(lowest, out.force_w.z());
    }
    EXPECT_EQ(lowest, 0.0) << axis.transpose();  // the half-wave: it does let go
  }
  // 10 N under a 3 N force limit: cut at the limit, and still never a pull
  limits_.max_force_n = 3.0;
  auto r = Make({Vibration{100.0, 10.0, Vec3::UnitZ(), true}});
  RenderOutput out;
  r.Render({Vec3(0, 0, 0.06), Vec3::Zero(), 0.0}, &out);
  for (int i = 1; i <= 20; ++i) {
    r.Render({Vec3(0, 0, 0.0498), Vec3::Zero(), i * 1e-3}, &out);
    EXPECT_GE(out.force_w.z(), 0.0) << i;
    EXPECT_LE(out.force_w.norm(), 3.0 + 1e-12) << i;
  }
}

}  // namespace
}  // namespace hapticad
