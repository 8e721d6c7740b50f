// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/contact/constraint_set.h"

#include <random>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

ConstraintPlane Plane(const Vec3& n, double d) { return {n.normalized(), d, 0}; }

TEST(ConstraintSet, AFeasibleGoalIsItsOwnProjection) {
  ConstraintSet set;
  set.Add(Plane(Vec3::UnitZ(), 0.0), 1e-12);
  EXPECT_EQ(set.Project(Vec3(1, 2, 3), Vec3::Zero(), 1e-12), Vec3(1, 2, 3));
}

TEST(ConstraintSet, OnePlaneProjectsAlongItsNormal) {
  ConstraintSet set;
  set.Add(Plane(Vec3::UnitZ(), 0.5), 1e-12);
  EXPECT_NEAR((set.Project(Vec3(1, 2, -3), Vec3::Zero(), 1e-12) - Vec3(1, 2, 0.5)).norm(), 0,
              1e-15);
}

TEST(ConstraintSet, TwoPlanesMakeAnEdgeOnlyWhenBothBind) {
  // concave edge along y: floor z >= 0 and wall x >= 0
  ConstraintSet set;
  set.Add(Plane(Vec3::UnitZ(), 0.0), 1e-12);
  set.Add(Plane(Vec3::UnitX(), 0.0), 1e-12);
  EXPECT_NEAR((set.Project(Vec3(-1, 3, -1), Vec3::Zero(), 1e-12) - Vec3(0, 3, 0)).norm(), 0, 1e-15);
  // goal below the floor but inside the wall's free side: only the floor binds
  EXPECT_NEAR((set.Project(Vec3(2, 3, -1), Vec3::Zero(), 1e-12) - Vec3(2, 3, 0)).norm(), 0, 1e-15);
}

TEST(ConstraintSet, ThreePlanesMakeACorner) {
  ConstraintSet set;
  set.Add(Plane(Vec3::UnitX(), 0.1), 1e-12);
  set.Add(Plane(Vec3::UnitY(), 0.2), 1e-12);
  set.Add(Plane(Vec3::UnitZ(), 0.3), 1e-12);
  EXPECT_TRUE(set.full());
  EXPECT_NEAR((set.Project(Vec3(-1, -1, -1), Vec3::Zero(), 1e-12) - Vec3(0.1, 0.2, 0.3)).norm(), 0,
              1e-15);
}

TEST(ConstraintSet, DuplicatePlanesAreNotAdded) {
  ConstraintSet set;
  EXPECT_TRUE(set.Add(Plane(Vec3::UnitZ(), 0.0), 1e-9));
  EXPECT_FALSE(set.Add(Plane(Vec3::UnitZ(), 1e-12), 1e-9));
  EXPECT_EQ(set.count(), 1);
}

TEST(ConstraintSet, ProjectionIsTheQpOptimumAgainstSampling) {
  // random wedge corners: no sampled feasible point is closer than the projection
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    ConstraintSet set;
    for (int i = 0; i < 3; ++i) set.Add(Plane(Vec3(g(rng), g(rng), g(rng) + 2.0), 0.0), 1e-12);
    const Vec3 goal(g(rng), g(rng), -std::abs(g(rng)) - 0.5);
    const Vec3 x = set.Project(goal, Vec3::Zero(), 1e-12);
    for (int i = 0; i < set.count(); ++i) EXPECT_GE(set.plane(i).normal.dot(x), -1e-9);
    for (int s = 0; s < 200; ++s) {
      const Vec3 y = x + 0.2 * Vec3(g(rng), g(rng), g(rng));
      bool feasible = true;
      for (int i = 0; i < set.count(); ++i) feasible &= set.plane(i).normal.dot(y) >= 0.0;
      if (feasible) {
        EXPECT_GE((y - goal).norm(), (x - goal).norm() - 1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace hapticad
