// SPDX-License-Identifier: GPL-3.0-or-later
// The contact engine at the extremes (issue 4): units and far origins, thin plates and
// sheets at 2 m/s, concave corners, convex edges and vertices, dirty input meshes.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/rendering/force_renderer.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

constexpr double kK = 400.0;  // N/m

// Every face of the scene at 0.4 N/mm with friction mu_s / mu_d.
std::shared_ptr<SurfaceTable> Uniform(const HapticScene& scene, double mu_s, double mu_d) {
  SurfaceProperties s;
  s.stiffness_n_per_m = kK;
  s.friction.static_coefficient = mu_s;
  s.friction.dynamic_coefficient = mu_d;
  return std::make_shared<SurfaceTable>(
      std::vector<SurfaceProperties>(static_cast<std::size_t>(scene.mesh().num_cad_faces()), s));
}
std::shared_ptr<SurfaceTable> Frictionless(const HapticScene& scene) {
  return Uniform(scene, 0.0, 0.0);
}
std::shared_ptr<SurfaceTable> Rubbery(const HapticScene& scene) { return Uniform(scene, 1.2, 1.0); }

RenderLimits Unclamped() { return RenderLimits{1e6, 1e6}; }

// A seeded stroke over the surface of a scene in world metres: positions and
// velocities, pressing 0.5-2 mm below, with a lift-off and a re-touch.
std::vector<RenderInput> Stroke(const HapticScene& scene, int ticks, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  SurfaceSample here = scene.CalcClosestPoint(scene.origin_w() + Vec3(0.0, 0.0, 1.0));
  Vec3 heading = here.normal_w.cross(Vec3(1.0, 0.3, 0.2)).normalized();
  std::vector<RenderInput> path;
  Vec3 previous = here.point_w + 0.01 * here.normal_w;
  for (int k = 0; k < ticks; ++k) {
    heading = (heading + 0.1 * gauss(rng) * here.normal_w.cross(heading)).normalized();
    here = scene.CalcClosestPoint(here.point_w + 0.00007 * heading);
    heading = (heading - heading.dot(here.normal_w) * here.normal_w).normalized();
    const double depth = k % 500 < 40 ? -0.002 : 0.0005 + 0.0015 * (0.5 + 0.5 * std::sin(k * 0.01));
    RenderInput in;
    in.position_w = here.point_w - depth * here.normal_w;
    in.velocity_w = (in.position_w - previous) / 1e-3;
    in.time_s = k * 1e-3;
    previous = in.position_w;
    path.push_back(in);
  }
  return path;
}

std::vector<Vec3> Forces(ForceRenderer& renderer, const std::vector<RenderInput>& path,
                         const Vec3& shift_w) {
  std::vector<Vec3> forces;
  RenderOutput out;
  for (const RenderInput& p : path) {
    RenderInput in = p;
    in.position_w = p.position_w + shift_w;
    renderer.Render(in, &out);
    forces.push_back(out.force_w);
  }
  return forces;
}

TEST(ContactExtremes, TheSameSceneInMmMAndFarAwayGivesTheSameForces) {
  // an icosphere of radius 50 mm (curved: every tick touches a different triangle), as
  // modelled in mm, in m, and translated, with no friction and with a rubbery one
  // (velocity-dependent)
  for (const bool rubbery : {false, true}) {
    for (double radius_proxy : {0.0, 0.001}) {
      ContactOptions options;
      options.proxy_radius_m = radius_proxy;
      const auto surfaces = [&](const HapticScene& s) {
        return rubbery ? Rubbery(s) : Frictionless(s);
      };
      const TriangleSoup mm = MakeIcosphere(30, 50.0);
      const auto reference = HapticScene::Build(mm, 1e-3);
      const std::vector<RenderInput> path = Stroke(*reference, 3000, 11);
      ForceRenderer base(reference, surfaces(*reference), Unclamped(), options);
      const std::vector<Vec3> expected = Forces(base, path, Vec3::Zero());
      double largest = 0.0;
      for (const Vec3& f : expected) largest = std::max(largest, f.norm());
      ASSERT_GT(largest, 0.3);

      struct Variant {
        const char* name;
        double metres_per_unit;
        double shift_units;
      };
      for (const Variant v :
           {Variant{"m", 1.0, 0.0}, Variant{"mm + 1e3", 1e-3, 1e3}, Variant{"mm + 1e6", 1e-3, 1e6},
            Variant{"m + 1e3", 1.0, 1e3}, Variant{"m + 1e6", 1.0, 1e6}}) {
        TriangleSoup soup = mm;
        const double scale = 1e-3 / v.metres_per_unit;  // model units per mm
        for (Vec3& p : soup.vertices) p = p * scale + Vec3::Constant(v.shift_units);
        const auto scene = HapticScene::Build(soup, v.metres_per_unit);
        ForceRenderer r(scene, surfaces(*scene), Unclamped(), options);
        const Vec3 shift_w = Vec3::Constant(v.shift_units * v.metres_per_unit);
        const std::vector<Vec3> forces = Forces(r, path, shift_w);
        // The world coordinates themselves may be coarser than 1e-9: 1e6 m from the
        // origin a position (the device's, a vertex's) is only known to an ulp of
        // 1.2e-10 m. Without friction the engine adds a few ulps to that (4.6 measured):
        // 8 are allowed, through a 0.4 N/mm spring. With friction, the scene's own rounding
        // reaches the friction's direction where the device lands on the part (k % 500 ==
        // 40): it arrives at 4 m/s, 57 times its speed along the surface, so the 2e-11 rad
        // by which the rounded vertices tilt a 2 mm triangle at 1e3 m turns v_t by 1e-9 rad
        // and the 0.8 N of friction by 1e-9 N (measured 1.07e-9 N at "m + 1e3", 23 ulps
        // of spring): 32 ulps are allowed, or 1e-9 of the largest force if that is more.
        const double ulp = std::nextafter(shift_w.x() + 0.1, 1e300) - (shift_w.x() + 0.1);
        const double tolerance =
            rubbery ? std::max(1e-9 * largest, 16.0 * ulp * kK * 2.0) : 8.0 * ulp * kK;
        for (std::size_t k = 0; k < forces.size(); ++k) {
          ASSERT_LE((forces[k] - expected[k]).norm(), tolerance)
              << v.name << (rubbery ? " rubbery" : " frictionless") << " radius " << radius_proxy
              << " tick " << k;
        }
      }
    }
  }
}

TEST(ContactExtremes, ConvexPiecesChangeNoContactAndSettleTheStroke) {
  // The ball is one convex piece: its sweeps are settled from the last contact, and every
  // tick has the proxy and the constraint planes the walk through the tree or the grid
  // gives, and so the force. A contact on an edge or at a vertex is made by every
  // triangle there at once, and the two searches may name different ones: then only the
  // force shading, which blends the named triangle's corner normals, may differ.
  const auto scene = HapticScene::Build(MakeIcosphere(30, 50.0, Vec3::Zero(), true), 1e-3);
  const std::vector<RenderInput> path = Stroke(*scene, 3000, 13);
  for (double radius : {0.0, 0.001}) {
    ContactOptions options;
    options.proxy_radius_m = radius;
    ForceRenderer settled(scene, Rubbery(*scene), Unclamped(), options);
    options.convex_pieces = false;
    ForceRenderer walked(scene, Rubbery(*scene), Unclamped(), options);
    RenderOutput a, b;
    int named_alike = 0;
    for (std::size_t k = 0; k < path.size(); ++k) {
      settled.Render(path[k], &a);
      walked.Render(path[k], &b);
      ASSERT_LE((a.proxy_w - b.proxy_w).norm(), 1e-15) << "radius " << radius << " tick " << k;
      const ConstraintSet& ca = settled.proxy().constraints();
      const ConstraintSet& cb = walked.proxy().constraints();
      ASSERT_EQ(ca.count(), cb.count()) << k;
      bool alike = true;
      for (int i = 0; i < ca.count(); ++i) {
        ASSERT_LE((ca.plane(i).normal - cb.plane(i).normal).norm(), 1e-12) << k;
        ASSERT_NEAR(ca.plane(i).offset, cb.plane(i).offset, 1e-15) << k;
        alike = alike && ca.plane(i).triangle == cb.plane(i).triangle;
      }
      if (!alike) continue;
      ++named_alike;
      ASSERT_LE((a.force_w - b.force_w).norm(), 1e-12) << "radius " << radius << " tick " << k;
    }
    EXPECT_GT(named_alike, 2950) << radius;
    EXPECT_EQ(walked.proxy().settled_sweeps(), 0u);
    EXPECT_GT(settled.proxy().settled_sweeps(), 0.99 * settled.proxy().sweeps()) << radius;
  }
}

// Thin things at 2 m/s: the device moves 2 mm per tick straight through them.
void ExpectNoPopThrough(const TriangleSoup& soup, double thickness_m, double radius) {
  const auto scene = HapticScene::Build(soup, 1e-3);
  ContactOptions options;
  options.proxy_radius_m = radius;
  ForceRenderer r(scene, Frictionless(*scene), Unclamped(), options);
  RenderOutput out;
  // start above, then sweep down and up through the plate, drifting sideways
  double z = 0.01;
  double direction = -1.0;
  int contacts = 0;
  for (int k = 0; k < 4000; ++k) {
    z += direction * 0.002;
    if (z < -0.01) direction = 1.0;
    if (z > 0.01) direction = -1.0;
    const Vec3 device(0.02 * std::sin(k * 0.013), 0.02 * std::cos(k * 0.017), z);
    r.Render({device, Vec3(0, 0, direction * 2.0), k * 1e-3}, &out);
    ASSERT_TRUE(out.force_w.allFinite());
    // the proxy's centre never goes below the plate's top (less its radius)
    ASSERT_GE(out.proxy_w.z(), thickness_m + radius - 1e-12) << "tick " << k;
    if (out.flags & kContact) ++contacts;
  }
  EXPECT_GT(contacts, 1000);
}

TEST(ContactExtremes, PointAndSphereProxiesRenderWithoutAllocatingOnACurvedShadedMesh) {
  const auto scene = HapticScene::Build(MakeIcosphere(40, 50.0, Vec3::Zero(), true), 1e-3);
  const std::vector<RenderInput> path = Stroke(*scene, 3000, 5);
  for (double radius : {0.0, 0.002}) {
    ContactOptions options;
    options.proxy_radius_m = radius;
    ForceRenderer r(scene, Rubbery(*scene), Unclamped(), options);
    RenderOutput out;
    r.Render(path[0], &out);
    int contacts = 0;
    testing::AllocationCounter counter;
    for (const RenderInput& in : path) {
      r.Render(in, &out);
      contacts += (out.flags & kContact) != 0;
    }
    EXPECT_EQ(counter.count(), 0u) << radius;
    EXPECT_GT(contacts, 2000) << radius;
  }
}

TEST(ContactExtremes, AHundredthOfAMillimetrePlateAt2MetresPerSecondIsNeverPoppedThrough) {
  // a 60 x 60 x 0.01 mm plate, its top at z = 0.01 mm
  const TriangleSoup plate = testing::MakeBoxSoup(Vec3(-30, -30, 0), Vec3(30, 30, 0.01));
  for (double radius : {0.0, 0.0005}) ExpectNoPopThrough(plate, 1e-5, radius);
}

TEST(ContactExtremes, AZeroThicknessSheetAt2MetresPerSecondIsNeverPoppedThrough) {
  const TriangleSoup sheet = testing::MakeSheetSoup(30.0, 0.0);
  for (double radius : {0.0, 0.0005}) ExpectNoPopThrough(sheet, 0.0, radius);
}

// The god-object in a concave corner is the projection onto a convex set (for a sphere
// of radius r, the corner's walls moved in by r): the force k (proxy - device) can
// change by at most k times the device's step.
void ExpectLipschitzInCorner(const TriangleSoup& soup, const Vec3& corner_w, int planes,
                             double radius = 0.0) {
  const auto scene = HapticScene::Build(soup, 1e-3);
  ContactOptions options;
  options.proxy_radius_m = radius;
  ForceRenderer r(scene, Frictionless(*scene), Unclamped(), options);
  std::mt19937 rng(planes);
  std::normal_distribution<double> step(0.0, 0.0002);
  RenderOutput out;
  Vec3 device = corner_w + Vec3(0.005, 0.005, 0.005);
  r.Render({device, Vec3::Zero(), 0.0}, &out);
  Vec3 previous_force = out.force_w;
  Vec3 previous_device = device;
  int bound = 0;
  for (int k = 0; k < 20000; ++k) {
    device += Vec3(step(rng), step(rng), step(rng));
    device = device.cwiseMax(corner_w - Vec3::Constant(0.004))
                 .cwiseMin(corner_w + Vec3::Constant(0.006));
    r.Render({device, Vec3::Zero(), k * 1e-3}, &out);
    // outside: no coordinate of the proxy below the corner's walls
    for (int axis = 0; axis < planes; ++axis) {
      ASSERT_GE(out.proxy_w[2 - axis], corner_w[2 - axis] + radius - 1e-12) << k;
    }
    ASSERT_LE((out.force_w - previous_force).norm(),
              kK * (device - previous_device).norm() * (1 + 1e-9) + 1e-9)
        << "tick " << k;
    if (out.proxy_w.z() < corner_w.z() + radius + 1e-6 && planes > 1 &&
        out.proxy_w.y() < corner_w.y() + radius + 1e-6)
      ++bound;
    previous_force = out.force_w;
    previous_device = device;
  }
  if (planes > 1) {
    EXPECT_GT(bound, 100);  // the walk did reach the corner's line
  }
}

// The inside of a box seen from within: its walls, edges and corners are concave. The
// box has no lid: the inside of a closed surface is the inside of a solid, where a
// proxy does not start (ForceRenderer::Reset).
TEST(ContactExtremes, ConcaveTwoAndThreePlaneCornersKeepTheProxyOutAndTheForceContinuous) {
  // inside a 40 mm box: the floor alone, the floor-wall edge, and the floor-wall-wall
  // corner at (-20, -20, -20) mm
  TriangleSoup room = testing::MakeBoxSoup(Vec3(-20, -20, -20), Vec3(20, 20, 20));
  for (std::size_t t = room.triangles.size(); t-- > 0;) {
    if (room.cad_faces[t] != 5) continue;  // the top
    room.triangles.erase(room.triangles.begin() + static_cast<std::ptrdiff_t>(t));
    room.cad_faces.erase(room.cad_faces.begin() + static_cast<std::ptrdiff_t>(t));
  }
  ASSERT_EQ(room.triangles.size(), 10u);
  const Vec3 corner(-0.02, -0.02, -0.02);
  for (double radius : {0.0, 0.001}) {  // the point and the 1 mm sphere
    ExpectLipschitzInCorner(room, Vec3(0.0, 0.0, -0.02), 1, radius);
    ExpectLipschitzInCorner(room, Vec3(0.0, -0.02, -0.02), 2, radius);
    ExpectLipschitzInCorner(room, corner, 3, radius);
  }
}

TEST(ContactExtremes, SlidingOverConvexEdgesAndVerticesStaysOutsideAndContinuous) {
  // device 1 mm inside a box, circling round the top edge y = 20 and over the corner
  // (20, 20, 20) along the inner offset of the surface: the proxy stays on the
  // surface, the force changes by no more than k times the device's step
  const auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-20, -20, -20), Vec3(20, 20, 20)), 1e-3);
  for (double radius : {0.0, 0.001}) {
    ContactOptions options;
    options.proxy_radius_m = radius;
    ForceRenderer r(scene, Frictionless(*scene), Unclamped(), options);
    RenderOutput out;
    r.Render({Vec3(0, 0, 0.03), Vec3::Zero(), 0.0}, &out);
    Vec3 previous_force = out.force_w, previous = Vec3(0, 0, 0.03);
    const double d = 0.001;
    std::vector<Vec3> path;
    for (int i = 0; i <= 200; ++i) path.push_back(Vec3(0, 0, 0.03 - (0.01 + d) * i / 200.0));
    for (int i = 0; i <= 2000; ++i)
      path.push_back(Vec3(0.019 * i / 2000.0, 0.019 * i / 2000.0, 0.02 - d));
    for (int i = 0; i <= 2000; ++i)
      path.push_back(Vec3(0.019, 0.019, 0.02 - d - 0.019 * i / 2000.0));
    int contacts = 0;
    for (std::size_t k = 0; k < path.size(); ++k) {
      r.Render({path[k], Vec3::Zero(), k * 1e-3}, &out);
      const Vec3 c = scene->ToLocal(out.proxy_w);
      const Vec3 outside = (c.cwiseAbs() - Vec3::Constant(0.02)).cwiseMax(0.0);
      ASSERT_GE(outside.norm(), radius - 1e-12) << "radius " << radius << " tick " << k;
      ASSERT_LE((out.force_w - previous_force).norm(),
                kK * (path[k] - previous).norm() * (1 + 1e-9) + 1e-9)
          << "radius " << radius << " tick " << k;
      if (out.flags & kContact) ++contacts;
      previous_force = out.force_w;
      previous = path[k];
    }
    EXPECT_GT(contacts, 4000);
  }
}

TEST(ContactExtremes, ADirtyMeshIsRepairedAndNeverGivesANaNForce) {
  // a box with a duplicate, a needle, a repeated vertex, a non-manifold fin and a NaN
  TriangleSoup s = testing::MakeBoxSoup(Vec3(-20, -20, -20), Vec3(20, 20, 20));
  s.vertices.push_back(Vec3(0, -20, -20));                                     // 8
  s.vertices.push_back(Vec3(0, 0, 40));                                        // 9: a fin
  s.vertices.push_back(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));  // 10
  s.vertices.push_back(Vec3(std::numeric_limits<double>::infinity(), 0, 0));   // 11
  s.triangles.push_back(s.triangles[0]);                                       // duplicate
  s.triangles.push_back({0, 8, 1});                                            // collinear
  s.triangles.push_back({2, 2, 3});                                            // repeated vertex
  s.triangles.push_back({6, 7, 9});   // a fin on the top's edge 6-7 (non-manifold)
  s.triangles.push_back({0, 1, 10});  // NaN
  s.triangles.push_back({0, 11, 1});  // Inf
  for (int i = 0; i < 6; ++i) s.cad_faces.push_back(0);
  const auto scene = HapticScene::Build(s, 1e-3);
  const RepairReport& report = scene->repair_report();
  EXPECT_EQ(report.removed_nonfinite, 2u);
  EXPECT_EQ(report.removed_duplicates, 1u);
  EXPECT_EQ(report.removed_degenerate, 2u);
  EXPECT_EQ(report.non_manifold_edges, 1u);
  for (double radius : {0.0, 0.001}) {
    ContactOptions options;
    options.proxy_radius_m = radius;
    ForceRenderer r(scene, Rubbery(*scene), Unclamped(), options);
    std::mt19937 rng(3);
    std::normal_distribution<double> step(0.0, 0.003);
    Vec3 device(0, 0, 0.05);
    RenderOutput out;
    int contacts = 0;
    for (int k = 0; k < 20000; ++k) {
      device = (device + Vec3(step(rng), step(rng), step(rng))).cwiseMax(-0.05).cwiseMin(0.05);
      r.Render({device, Vec3(step(rng), step(rng), step(rng)) * 100.0, k * 1e-3}, &out);
      ASSERT_TRUE(out.force_w.allFinite() && out.proxy_w.allFinite()) << k;
      if (out.flags & kContact) ++contacts;
    }
    EXPECT_GT(contacts, 1000);
  }
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

// A shallow valley of two triangles meeting along x = 0 (each tilted 5 degrees up
// away from it), in mm. `smooth`: every corner carries +z, as the tessellation of one
// smooth CAD face would; otherwise each triangle carries its own facet normal (a crease).
TriangleSoup Valley(bool smooth) {
  const double rise = 20.0 * std::tan(5.0 * M_PI / 180.0);
  TriangleSoup s;
  s.vertices = {Vec3(0, -20, 0), Vec3(0, 20, 0), Vec3(-20, 0, rise), Vec3(20, 0, rise)};
  s.triangles = {{0, 1, 2}, {1, 0, 3}};
  s.cad_faces = smooth ? std::vector<std::int32_t>{0, 0} : std::vector<std::int32_t>{0, 1};
  for (int t = 0; t < 2; ++t) {
    const Vec3 a = s.vertices[s.triangles[t][0]], b = s.vertices[s.triangles[t][1]],
               c = s.vertices[s.triangles[t][2]];
    Vec3 n = (b - a).cross(c - a).normalized();
    if (n.z() < 0) n = -n;
    const Vec3 corner = smooth ? Vec3::UnitZ() : n;
    s.corner_normals.push_back({corner, corner, corner});
  }
  return s;
}

TEST(ForceShading, ShadesAcrossTessellationValleysButNotAcrossCadCreases) {
  for (bool smooth : {true, false}) {
    const auto scene = HapticScene::Build(Valley(smooth), 1e-3);
    ForceRenderer r(scene, Frictionless(*scene), Unclamped());
    RenderOutput out;
    r.Render({Vec3(0.0, 0.0, 0.01), Vec3::Zero(), 0.0}, &out);
    // pressed 5 mm deep, 0.1 mm right of the fold: the goal's projection on either
    // slope lies past the fold, so the proxy rests on the fold, held by both
    const Vec3 goal(0.0001, 0.0, -0.005);
    r.Render({goal, Vec3::Zero(), 0.001}, &out);
    ASSERT_EQ(out.constraints, 2) << smooth;
    const Vec3 proxy = out.proxy_w;
    EXPECT_NEAR(proxy.x(), 0.0, 1e-9);
    const Vec3 direction = out.force_w.normalized();
    if (smooth) {
      // shaded: along the smooth face's normal, the depth measured along it
      EXPECT_NEAR((direction - Vec3::UnitZ()).norm(), 0.0, 1e-9);
      EXPECT_NEAR(out.force_w.z(), kK * (proxy.z() - goal.z()), 1e-9);
    } else {
      // a crease: the plain spring from the device to the fold, 1.1 degrees off +z
      EXPECT_NEAR((out.force_w - kK * (proxy - goal)).norm(), 0.0, 1e-9);
      EXPECT_GT(std::acos(direction.z()), 1.0 * M_PI / 180.0);
    }
  }
}

}  // namespace
}  // namespace hapticad
