// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/mesh_refine.h"

#include <chrono>
#include <map>
#include <stdexcept>

#include <gtest/gtest.h>

#include "hapticad/core/geometry/mesh_repair.h"
#include "hapticad/core/rendering/haptic_scene.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

double Area(const TriangleSoup& s, std::size_t t) {
  const Vec3& a = s.vertices[s.triangles[t][0]];
  return 0.5 * (s.vertices[s.triangles[t][1]] - a).cross(s.vertices[s.triangles[t][2]] - a).norm();
}

TEST(MeshRefine, SplitsEveryLongEdgeAndKeepsTheSurfaceClosedWithItsFaces) {
  TriangleSoup box = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(10, 20, 30));
  const Vec3 n = Vec3(1, 2, 3).normalized();
  for (std::size_t t = 0; t < box.triangles.size(); ++t) box.corner_normals.push_back({n, n, n});
  const TriangleSoup out = RefineSoup(box, 4.0);
  EXPECT_GT(out.triangles.size(), 12u * 16u);
  std::map<int, double> area_in, area_out;
  for (std::size_t t = 0; t < box.triangles.size(); ++t) area_in[box.cad_faces[t]] += Area(box, t);
  for (std::size_t t = 0; t < out.triangles.size(); ++t) {
    area_out[out.cad_faces[t]] += Area(out, t);
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = out.vertices[out.triangles[t][k]];
      const Vec3& b = out.vertices[out.triangles[t][(k + 1) % 3]];
      ASSERT_LE((b - a).norm(), 4.0 + 1e-12) << t;
      EXPECT_NEAR((out.corner_normals[t][k] - n).norm(), 0.0, 1e-12);  // blended from equal ones
    }
  }
  for (const auto& [face, area] : area_in) EXPECT_NEAR(area_out[face], area, 1e-9) << face;
  RepairReport report;
  RepairSoup(out, RepairOptions{}, &report);
  EXPECT_TRUE(report.watertight()) << report.Describe();  // conforming: no T-junctions
}

TEST(MeshRefine, BlendsCornerNormalsLinearlyAtNewVertices) {
  TriangleSoup s = testing::MakeSheetSoup(1.0, 0.0);
  s.corner_normals = {{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()},
                      {Vec3::UnitX(), Vec3::UnitZ(), -Vec3::UnitY()}};
  const TriangleSoup out = RefineSoup(s, 1.5);
  // the first triangle's edge from corner 0 (x) to corner 1 (y) was split at its middle
  const Vec3 mid = 0.5 * (s.vertices[0] + s.vertices[1]);
  bool found = false;
  for (std::size_t t = 0; t < out.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if ((out.vertices[out.triangles[t][k]] - mid).norm() < 1e-12) {
        EXPECT_NEAR((out.corner_normals[t][k] - Vec3(1, 1, 0).normalized()).norm(), 0.0, 1e-12);
        found = true;
      }
    }
  }
  EXPECT_TRUE(found);
}

TEST(MeshRefine, RejectsBadLengthsAndRunawayRefinement) {
  const TriangleSoup box = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_THROW(RefineSoup(box, 0.0), std::invalid_argument);
  EXPECT_THROW(RefineSoup(box, std::nan("")), std::invalid_argument);
  EXPECT_THROW(RefineSoup(box, 1e-4, 100000), std::invalid_argument);
}

TEST(MeshRefine, ARefinementThatCannotFitIsRefusedBeforeAnythingIsSplit) {
  // a 100 mm box at 0.01 mm: at least 1.4e9 triangles (its area, 6e4 mm^2, over 4.3e-5
  // mm^2 each); it used to split for a minute and gigabytes before the cap stopped it
  const TriangleSoup box = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(100, 100, 100));
  const auto start = std::chrono::steady_clock::now();
  try {
    RefineSoup(box, 0.01);
    FAIL() << "refined";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "mesh refinement: an edge length of 0.01 makes at least 1.39e+09 triangles of "
                 "this part's area (at most 4000000 are built): give an edge length of 0.186 or "
                 "more");
  }
  // refused from the area alone: nothing was split (the cap, reached splitting, took seconds)
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
  // what the bound lets through and still grows past the cap is refused when it does
  try {
    RefineSoup(box, 1.5, 100000);  // at least 61584: passes the bound
    FAIL() << "refined";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "mesh refinement: more than 100000 triangles at an edge length of 1.5: give a "
                 "longer one");
  }
}

TEST(MeshRefine, TheSceneRefinesWhenAsked) {
  const TriangleSoup box = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(10, 10, 10));
  SceneOptions options;
  options.refine_edge = 2.0;
  const auto scene = HapticScene::Build(box, 1e-3, options);
  EXPECT_GT(scene->mesh().num_triangles(), 12u * 16u);
  EXPECT_EQ(scene->mesh().num_cad_faces(), 6);
  options.refine_edge = -1.0;
  EXPECT_THROW(HapticScene::Build(box, 1e-3, options), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad
