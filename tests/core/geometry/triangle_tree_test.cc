// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/triangle_tree.h"

#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/geometry/segment_triangle.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "closest_on_triangle.h"
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

TEST_F(BoxTree, ClosestPointWithinADistanceFindsOnlyWhatIsCloser) {
  SurfacePoint p{7, Vec3(9, 9, 9), 9.0};
  // 2 from the x = 1 face: not within 1.5, nor within exactly 2
  EXPECT_FALSE(tree_->FindClosestPointWithin(Vec3(3, 0.5, 0.25), 1.5, &p));
  EXPECT_FALSE(tree_->FindClosestPointWithin(Vec3(3, 0.5, 0.25), 2.0, &p));
  EXPECT_EQ(p.triangle, 7u);  // left as it was
  // within 2.5: the same answer as the unbounded search
  ASSERT_TRUE(tree_->FindClosestPointWithin(Vec3(3, 0.5, 0.25), 2.5, &p));
  EXPECT_EQ(mesh_->cad_face(p.triangle), 1);
  EXPECT_NEAR((p.point - Vec3(1, 0.5, 0.25)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(p.distance, 2.0, 1e-12);
  // inside the box, nearest the top (0.1 away) though the bottom is within the bound too
  ASSERT_TRUE(tree_->FindClosestPointWithin(Vec3(0.5, 0.5, 0.9), 5.0, &p));
  EXPECT_NEAR((p.point - Vec3(0.5, 0.5, 1.0)).norm(), 0.0, 1e-12);
  // nothing is closer than 0, nor than a negative or NaN bound
  EXPECT_FALSE(tree_->FindClosestPointWithin(Vec3(0.5, 0.5, 0.9), 0.0, &p));
  EXPECT_FALSE(tree_->FindClosestPointWithin(Vec3(0.5, 0.5, 0.9), -5.0, &p));
  EXPECT_FALSE(tree_->FindClosestPointWithin(Vec3(0.5, 0.5, 0.9), std::nan(""), &p));
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

TEST(TriangleTree, ClosestPointMatchesEveryTriangleTested) {
  // a bumpy ball (radial noise keeps it a closed surface) and points inside, near and
  // far: the answer is as near as the nearest of all triangles, and lies on its own
  TriangleSoup s = MakeIcosphere(IcosphereFrequencyFor(3000), 1.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> bump(0.8, 1.2);
  for (Vec3& v : s.vertices) v *= bump(rng);
  const auto mesh = TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
  const auto tree = TriangleTree::Build(*mesh, 1e-12);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  std::uniform_real_distribution<double> reach(0.0, 4.0);
  for (int i = 0; i < 300; ++i) {
    const Vec3 dir = Vec3(coord(rng), coord(rng), coord(rng)).normalized();
    const Vec3 q = reach(rng) * dir;
    const SurfacePoint got = tree->CalcClosestPoint(q);
    double nearest = INFINITY;
    for (std::uint32_t t = 0; t < mesh->num_triangles(); ++t) {
      const auto& tri = mesh->triangle(t);
      const Vec3 c = testing::ClosestOnTriangle(q, mesh->vertex(tri[0]), mesh->vertex(tri[1]),
                                                mesh->vertex(tri[2]));
      nearest = std::min(nearest, (c - q).norm());
    }
    ASSERT_NEAR(got.distance, nearest, 1e-12) << i;
    ASSERT_NEAR((got.point - q).norm(), got.distance, 1e-12) << i;
    const auto& own = mesh->triangle(got.triangle);
    const Vec3 on = testing::ClosestOnTriangle(got.point, mesh->vertex(own[0]),
                                               mesh->vertex(own[1]), mesh->vertex(own[2]));
    ASSERT_NEAR((on - got.point).norm(), 0.0, 1e-12) << i << ": not on triangle " << got.triangle;
  }
}

TEST(TriangleTree, ClosestPointDoesNotAllocate) {
  const TriangleSoup s = MakeIcosphere(IcosphereFrequencyFor(2000), 1.0);
  const auto mesh = TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
  const auto tree = TriangleTree::Build(*mesh, 1e-12);
  testing::AllocationCounter counter;
  double sum = 0.0;
  for (int i = 0; i < 100; ++i) sum += tree->CalcClosestPoint(Vec3(0.03 * i, 0.5, 2.0)).distance;
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(sum, 0.0);
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
