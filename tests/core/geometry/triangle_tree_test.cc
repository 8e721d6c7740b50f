// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/triangle_tree.h"

#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/geometry/segment_triangle.h"

#include <random>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

bool FirstHit(const TriangleTree& tree, const Vec3& a, const Vec3& b, SweepHit* hit) {
  SweepQuery q;
  q.a = a;
  q.b = b;
  return tree.FirstHit(q, hit);
}

class BoxTree : public ::testing::Test {
 protected:
  void SetUp() override {
    const TriangleSoup s = testing::MakeBoxSoup(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    mesh_ = TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
    tree_ = TriangleTree::Build(*mesh_, 1e-12);
  }
  std::unique_ptr<TriangleMesh> mesh_;
  std::unique_ptr<TriangleTree> tree_;
};

TEST_F(BoxTree, FirstHitIsTheNearestTriangle) {
  SweepHit hit;
  ASSERT_TRUE(FirstHit(*tree_, Vec3(0.2, 0.3, 3), Vec3(0.2, 0.3, -3), &hit));
  EXPECT_EQ(mesh_->cad_face(hit.triangle), 5);  // +z, not -z behind it
  EXPECT_NEAR((hit.point - Vec3(0.2, 0.3, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(hit.s, 2.0 / 6.0, 1e-12);
}

TEST_F(BoxTree, MissesWhenTheSegmentStopsShortOrPassesBeside) {
  SweepHit hit;
  EXPECT_FALSE(FirstHit(*tree_, Vec3(0, 0, 3), Vec3(0, 0, 1.001), &hit));
  EXPECT_FALSE(FirstHit(*tree_, Vec3(1.5, 0, 3), Vec3(1.5, 0, -3), &hit));
}

TEST_F(BoxTree, ASegmentThroughASharedEdgeStillHits) {
  // the top face's diagonal from (-1,-1) to (1,1) is shared by its two triangles
  SweepHit hit;
  ASSERT_TRUE(FirstHit(*tree_, Vec3(0.25, 0.25, 2), Vec3(0.25, 0.25, 0), &hit));
  EXPECT_EQ(mesh_->cad_face(hit.triangle), 5);
}

TEST_F(BoxTree, RandomSegmentsAgreeWithBruteForce) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    const Vec3 b(u(rng), u(rng), u(rng));
    double best = 2.0;
    for (std::uint32_t t = 0; t < mesh_->num_triangles(); ++t) {
      SegmentTriangleHit h;
      const auto& tri = mesh_->triangle(t);
      if (IntersectSegmentTriangle(a, b - a, 1.0, mesh_->vertex(tri[0]), mesh_->vertex(tri[1]),
                                   mesh_->vertex(tri[2]), 1e-9, &h)) {
        best = std::min(best, h.s);
      }
    }
    SweepHit hit;
    const bool found = FirstHit(*tree_, a, b, &hit);
    ASSERT_EQ(found, best <= 1.0) << i;
    if (found) {
      EXPECT_NEAR(hit.s, best, 1e-12) << i;
    }
  }
}

TEST_F(BoxTree, FirstHitDoesNotAllocate) {
  SweepHit hit;
  FirstHit(*tree_, Vec3(0, 0, 3), Vec3(0, 0, -3), &hit);  // warm
  testing::AllocationCounter counter;
  for (int i = 0; i < 100; ++i) FirstHit(*tree_, Vec3(0.01 * i, 0, 3), Vec3(0, 0.01 * i, -3), &hit);
  EXPECT_EQ(counter.count(), 0u);
}

TEST_F(BoxTree, ClosestPointIsOnTheNearestFace) {
  const SurfacePoint p = tree_->CalcClosestPoint(Vec3(3, 0.5, 0.25));
  EXPECT_EQ(mesh_->cad_face(p.triangle), 1);
  EXPECT_NEAR((p.point - Vec3(1, 0.5, 0.25)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(p.distance, 2.0, 1e-12);
}

TEST(TriangleTree, ClosestPointAtAVertexNamesATriangleThatHasIt) {
  // off a convex vertex the closest point is the vertex itself, where the search's
  // starting hints lie: the answer's triangle must be one of the vertex's
  const TriangleSoup s = MakeIcosphere(IcosphereFrequencyFor(2000), 1.0);
  const auto mesh = TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
  const auto tree = TriangleTree::Build(*mesh, 1e-12);
  int checked = 0;
  for (std::uint32_t v = 0; v < mesh->num_vertices(); ++v) {
    const Vec3 q = 1.5 * mesh->vertex(v);
    const SurfacePoint p = tree->CalcClosestPoint(q);
    ASSERT_NEAR((p.point - mesh->vertex(v)).norm(), 0.0, 1e-12) << v;
    const auto& t = mesh->triangle(p.triangle);
    EXPECT_TRUE(t[0] == v || t[1] == v || t[2] == v)
        << "vertex " << v << ", triangle " << p.triangle;
    EXPECT_GT(mesh->face_normal(p.triangle).dot(q - p.point), 0.0) << v;
    ++checked;
  }
  EXPECT_GT(checked, 900);
}

TEST_F(BoxTree, ClosestPointOffACornerIsOnAFaceAtThatCorner) {
  const SurfacePoint p = tree_->CalcClosestPoint(Vec3(-2, -2, -2));
  EXPECT_NEAR((p.point - Vec3(-1, -1, -1)).norm(), 0.0, 1e-12);
  const Vec3& n = mesh_->face_normal(p.triangle);
  EXPECT_NEAR(n.minCoeff(), -1.0, 1e-12);  // -x, -y or -z: facing the query
  EXPECT_GT(n.dot(Vec3(-2, -2, -2) - p.point), 0.0);
}

}  // namespace
}  // namespace hapticad
