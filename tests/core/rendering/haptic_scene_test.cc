// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/rendering/haptic_scene.h"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "test_meshes.h"

namespace hapticad {
namespace {

TEST(HapticScene, StoresMetresAroundALocalOrigin) {
  // a 20 x 40 x 60 mm box modelled in mm, 1 km from the world origin
  const Vec3 lo(1e6, 1e6, 1e6);
  const auto scene = HapticScene::Build(testing::MakeBoxSoup(lo, lo + Vec3(20, 40, 60)), 1e-3);
  EXPECT_NEAR((scene->origin_w() - Vec3(1000.010, 1000.020, 1000.030)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(scene->size_m(), std::sqrt(0.02 * 0.02 + 0.04 * 0.04 + 0.06 * 0.06), 1e-15);
  // the repair may renumber vertices: the box's far corner is there, in local metres
  double nearest = 1.0;
  for (std::uint32_t v = 0; v < scene->mesh().num_vertices(); ++v) {
    nearest = std::min(nearest, (scene->mesh().vertex(v) - Vec3(0.010, 0.020, 0.030)).norm());
  }
  EXPECT_NEAR(nearest, 0.0, 1e-15);
  EXPECT_TRUE(scene->repair_report().watertight()) << scene->repair_report().Describe();
}

TEST(HapticScene, BuildsEachContactStructureOnceOnFirstRequestFromAnyThread) {
  const auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(20, 40, 60)), 1e-3);
  const std::size_t mesh_only = scene->CalcMemoryBytes();
  // four threads ask at once: one builds, all get the same structure
  std::vector<const TriangleGrid*> grids(4);
  std::vector<const TriangleTree*> trees(4);
  std::vector<std::thread> threads;
  for (int i = 0; i < 4; ++i) {
    threads.emplace_back([&, i] {
      grids[i] = &scene->BuildGrid();
      trees[i] = &scene->BuildTree();
    });
  }
  for (auto& t : threads) t.join();
  for (int i = 1; i < 4; ++i) {
    EXPECT_EQ(grids[i], grids[0]);
    EXPECT_EQ(trees[i], trees[0]);
  }
  EXPECT_EQ(&scene->BuildGrid(), grids[0]);
  EXPECT_EQ(scene->CalcMemoryBytes(),
            mesh_only + grids[0]->CalcMemoryBytes() + trees[0]->CalcMemoryBytes());
  EXPECT_GT(grids[0]->CalcMemoryBytes(), 0u);
}

TEST(HapticScene, ClosestPointGivesFaceAndOutwardNormalInWorld) {
  const auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(20, 40, 60)), 1e-3);
  const SurfaceSample s = scene->CalcClosestPoint(Vec3(0.010, 0.020, 0.100));
  EXPECT_EQ(s.cad_face, 5);
  EXPECT_NEAR((s.point_w - Vec3(0.010, 0.020, 0.060)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.normal_w - Vec3::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(s.distance_m, 0.040, 1e-15);
}

TEST(HapticScene, ClosestPointRefusesANonFiniteOrAbsurdlyFarPointAndAnswersAFarOne) {
  const auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(20, 40, 60)), 1e-3);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(scene->CalcClosestPoint(Vec3(std::nan(""), 0, 0)), std::invalid_argument);
  EXPECT_THROW(scene->CalcClosestPoint(Vec3(0, inf, 0)), std::invalid_argument);
  // where squared distances overflow (CGAL's projection answered -1.7e184 there)
  EXPECT_THROW(scene->CalcClosestPoint(Vec3(1e200, 0, 0)), std::invalid_argument);
  // and just beyond the reach, where nothing overflows yet
  const Vec3 beyond =
      scene->origin_w() + Vec3(1.01 * HapticScene::kClosestPointReach * scene->size_m(), 0, 0);
  EXPECT_THROW(scene->CalcClosestPoint(beyond), std::invalid_argument);
  // far, but within reach: the +x face, at the true distance (37 km off a 75 mm part:
  // the projection keeps 16 digits of the distance, 1e-11 of the part's size)
  const double x = 0.5 * HapticScene::kClosestPointReach * scene->size_m();
  const SurfaceSample far = scene->CalcClosestPoint(Vec3(x, 0.020, 0.030));
  EXPECT_EQ(far.cad_face, 1);
  EXPECT_NEAR((far.point_w - Vec3(0.020, 0.020, 0.030)).norm(), 0.0, 1e-9 * scene->size_m());
  EXPECT_NEAR(far.distance_m, x - 0.020, 1e-9);
}

TEST(HapticScene, RejectsBadUnitsAndRepairsOrRejectsNonFiniteVertices) {
  const TriangleSoup box = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_THROW(HapticScene::Build(box, 0.0), std::invalid_argument);
  EXPECT_THROW(HapticScene::Build(box, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  // a NaN vertex: its triangles go, and the hole they leave is reported
  TriangleSoup nan_box = box;
  nan_box.vertices[2].x() = std::numeric_limits<double>::quiet_NaN();
  const auto scene = HapticScene::Build(nan_box, 1.0);
  const RepairReport& report = scene->repair_report();
  EXPECT_EQ(report.removed_nonfinite, 4u);  // vertex 2 is a corner of four triangles
  EXPECT_EQ(scene->mesh().num_triangles(), 8u);
  EXPECT_FALSE(report.watertight());
  EXPECT_NE(report.Describe().find("NOT REPAIRED"), std::string::npos) << report.Describe();
  for (std::uint32_t v = 0; v < scene->mesh().num_vertices(); ++v) {
    EXPECT_TRUE(scene->mesh().vertex(v).allFinite());
  }
  // nothing finite left: a clear error
  TriangleSoup all_nan = box;
  for (Vec3& v : all_nan.vertices) v.x() = std::numeric_limits<double>::infinity();
  try {
    HapticScene::Build(all_nan, 1.0);
    FAIL() << "an all-infinite soup was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

// A sheet welded to a part (at a corner, or along an edge as a fin) shares the part's
// vertices; the repair splits them, so the part stays a closed piece that bounds a solid
// and the sheet an open one that bounds nothing.
TEST(HapticScene, ASheetWeldedToAPartLeavesThePartAClosedPiece) {
  const TriangleSoup box = testing::MakeBoxSoup(Vec3::Constant(-50), Vec3::Constant(50));
  const std::array<Vec3, 4> at_a_corner = {Vec3(50, 50, 50), Vec3(150, 50, 50), Vec3(150, 150, 50),
                                           Vec3(50, 150, 50)};
  const std::array<Vec3, 4> along_an_edge = {Vec3(50, -50, 50), Vec3(50, 50, 50), Vec3(150, 50, 50),
                                             Vec3(150, -50, 50)};
  for (const auto& sheet : {at_a_corner, along_an_edge}) {
    TriangleSoup soup = box;
    const auto base = static_cast<std::int32_t>(soup.vertices.size());
    soup.vertices.insert(soup.vertices.end(), sheet.begin(), sheet.end());
    soup.triangles.push_back({base, base + 1, base + 2});
    soup.triangles.push_back({base, base + 2, base + 3});
    soup.cad_faces.resize(soup.triangles.size(), 6);
    const auto scene = HapticScene::Build(soup, 1e-3);
    const std::string report = scene->repair_report().Describe();
    EXPECT_NE(report.find("non-manifold vertices split"), std::string::npos) << report;
    const SolidAnalysis& solids = scene->BuildSolids();
    EXPECT_FALSE(solids.closed);
    EXPECT_TRUE(solids.pieces_bound_solids) << report;
    ASSERT_EQ(solids.piece_winding.size(), 2u) << report;
    // the piece whose box is the part's winds outward; the sheet's is open
    const Vec3 part_lo = Vec3::Constant(-0.05) - scene->origin_w();
    const Vec3 part_hi = Vec3::Constant(0.05) - scene->origin_w();
    int parts = 0;
    for (std::size_t c = 0; c < 2; ++c) {
      const bool is_part = (solids.piece_lo[c] - part_lo).norm() < 1e-12 &&
                           (solids.piece_hi[c] - part_hi).norm() < 1e-12;
      parts += is_part;
      EXPECT_EQ(solids.piece_winding[c], is_part ? 1 : 0) << report;
    }
    EXPECT_EQ(parts, 1) << report;
  }
}

}  // namespace
}  // namespace hapticad
