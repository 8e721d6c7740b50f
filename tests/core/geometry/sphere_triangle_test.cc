// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/sphere_triangle.h"

#include <random>

#include <gtest/gtest.h>

#include "closest_on_triangle.h"

namespace hapticad {
namespace {

// the triangle (0,0,0), (1,0,0), (0,1,0), normal +z
const Vec3 kV0(0, 0, 0), kV1(1, 0, 0), kV2(0, 1, 0), kN(0, 0, 1);

bool Sweep(const Vec3& a, const Vec3& b, double r, SphereTriangleHit* hit) {
  return SweepSphereTriangle(a, b - a, 1.0, r, kV0, kV1, kV2, kN, 1e-12, hit);
}

// distance from p to the triangle, by an independent reference
double DistanceToTriangle(const Vec3& p) {
  return (p - testing::ClosestOnTriangle(p, kV0, kV1, kV2)).norm();
}

TEST(SweepSphereTriangle, TouchesTheFaceOneRadiusAbove) {
  SphereTriangleHit hit;
  ASSERT_TRUE(Sweep(Vec3(0.2, 0.2, 1.0), Vec3(0.2, 0.2, -1.0), 0.25, &hit));
  EXPECT_NEAR(hit.s, 0.375, 1e-15);  // centre at z = 0.25
  EXPECT_NEAR((hit.normal - kN).norm(), 0.0, 1e-15);
  // from below: the other side
  ASSERT_TRUE(Sweep(Vec3(0.2, 0.2, -1.0), Vec3(0.2, 0.2, 1.0), 0.25, &hit));
  EXPECT_NEAR(hit.s, 0.375, 1e-15);
  EXPECT_NEAR((hit.normal + kN).norm(), 0.0, 1e-15);
}

TEST(SweepSphereTriangle, TouchesAnEdgeAndAVertexBesideTheFace) {
  SphereTriangleHit hit;
  // straight down beside the edge y = 0, 0.1 away: touches the edge when z = sqrt(r^2 - 0.01)
  ASSERT_TRUE(Sweep(Vec3(0.5, -0.1, 1.0), Vec3(0.5, -0.1, -1.0), 0.25, &hit));
  const double z = std::sqrt(0.25 * 0.25 - 0.01);
  EXPECT_NEAR(hit.s, (1.0 - z) / 2.0, 1e-14);
  EXPECT_NEAR((hit.normal - Vec3(0, -0.1, z) / 0.25).norm(), 0.0, 1e-13);
  // beside the vertex (0,0,0), diagonally out
  ASSERT_TRUE(Sweep(Vec3(-0.1, -0.1, 1.0), Vec3(-0.1, -0.1, -1.0), 0.25, &hit));
  const double zv = std::sqrt(0.25 * 0.25 - 0.02);
  EXPECT_NEAR(hit.s, (1.0 - zv) / 2.0, 1e-14);
  // far beside: nothing
  EXPECT_FALSE(Sweep(Vec3(-0.3, -0.3, 1.0), Vec3(-0.3, -0.3, -1.0), 0.25, &hit));
}

TEST(SweepSphereTriangle, ALateralSweepAlongThePlaneHitsTheEdgeItRunsInto) {
  SphereTriangleHit hit;
  // centre 0.1 above the plane, moving in +x from x = -1 toward the triangle
  ASSERT_TRUE(Sweep(Vec3(-1.0, 0.3, 0.1), Vec3(1.0, 0.3, 0.1), 0.25, &hit));
  const double dx = std::sqrt(0.25 * 0.25 - 0.01);  // to the edge x = 0 at height 0.1
  EXPECT_NEAR(hit.s, (1.0 - dx) / 2.0, 1e-14);
  EXPECT_NEAR((hit.normal - Vec3(-dx, 0, 0.1) / 0.25).norm(), 0.0, 1e-13);
}

TEST(SweepSphereTriangle, AnOverlappingSphereMayLeaveButNotGoDeeper) {
  SphereTriangleHit hit;
  EXPECT_FALSE(Sweep(Vec3(0.2, 0.2, 0.1), Vec3(0.2, 0.2, 0.5), 0.25, &hit));
  ASSERT_TRUE(Sweep(Vec3(0.2, 0.2, 0.1), Vec3(0.2, 0.2, 0.0), 0.25, &hit));
  EXPECT_EQ(hit.s, 0.0);
  EXPECT_FALSE(Sweep(Vec3(0.5, -0.1, 0.0), Vec3(0.5, -0.4, 0.0), 0.25, &hit));  // off an edge
}

TEST(SweepSphereTriangle, AgreesWithBruteForceDistancesOnRandomSweeps) {
  // the reported contact is at distance r, and no earlier point of the sweep is closer
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  const double r = 0.2;
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    const Vec3 b(u(rng), u(rng), u(rng));
    if (DistanceToTriangle(a) <= r + 1e-6) continue;  // start clearly outside
    SphereTriangleHit hit;
    const bool found = Sweep(a, b, r, &hit);
    double first = 2.0;  // brute force: first sample closer than r
    for (int k = 0; k <= 2000; ++k) {
      if (DistanceToTriangle(a + (b - a) * (k / 2000.0)) < r - 1e-9) {
        first = k / 2000.0;
        break;
      }
    }
    if (first <= 1.0) {
      ASSERT_TRUE(found) << i;
      EXPECT_LE(hit.s, first + 1e-12) << i;
    }
    if (found) {
      ++hits;
      EXPECT_NEAR(DistanceToTriangle(a + hit.s * (b - a)), r, 1e-9) << i;
    }
  }
  EXPECT_GT(hits, 300);
}

TEST(SweepSphereTriangle, ASliverTouchesOnlyWhereItIs) {
  // A sliver a million times longer than it is wide, away from the origin (a side
  // triangle of a 0.01 mm plate 10 mm across): a sphere coming down just beyond its long
  // edge, clear of it by a millionth of its width (a thousand times the test's
  // tolerance), must not land on its face. Barycentrics from the sides' dot products
  // lose 1e-4 here; from cross products, 1e-10.
  const Vec3 v0(5.0 / 3.0, -5, 1e-5), v1(5, -5, 1e-5 * 2.0 / 3.0), v2(5, -5, 1e-5);
  const Vec3 n = (v1 - v0).cross(v2 - v0).normalized();
  const double r = 0.01;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> along(0.05, 0.95);
  int landed = 0;
  for (int i = 0; i < 2000; ++i) {
    // a point of the long edge v0-v1, then a millionth of the width beyond it
    const Vec3 on_edge = v0 + along(rng) * (v1 - v0);
    const double width = (v2 - v1).norm() * (on_edge - v0).norm() / (v1 - v0).norm();
    const Vec3 out = n.cross(v1 - v0).normalized();  // across the edge, away from v2
    const Vec3 beside = on_edge + (out.dot(v2 - v0) > 0 ? -1.0 : 1.0) * 1e-6 * width * out;
    SphereTriangleHit hit;
    if (SweepSphereTriangle(beside + 2 * r * n, -4 * r * n, 1.0, r, v0, v1, v2, n, 1e-9, &hit)) {
      landed += hit.normal == n;  // the face's normal: landed on the face
    }
  }
  EXPECT_EQ(landed, 0);
}

}  // namespace
}  // namespace hapticad
