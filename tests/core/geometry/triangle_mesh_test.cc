// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/triangle_mesh.h"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "test_meshes.h"

namespace hapticad {
namespace {

std::unique_ptr<TriangleMesh> BuildSoup(const TriangleSoup& s) {
  return TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
}

std::string BuildError(const TriangleSoup& s) {
  try {
    BuildSoup(s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(TriangleMesh, KeepsTheCadFaceOfEveryTriangle) {
  const auto mesh = BuildSoup(testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 2, 3)));
  ASSERT_EQ(mesh->num_triangles(), 12u);
  EXPECT_EQ(mesh->num_vertices(), 8u);
  EXPECT_EQ(mesh->num_cad_faces(), 6);
  for (std::uint32_t t = 0; t < 12; ++t) {
    EXPECT_EQ(mesh->cad_face(t), static_cast<int>(t / 2));
    EXPECT_EQ(mesh->cad_faces()[t], static_cast<int>(t / 2));
  }
}

TEST(TriangleMesh, KnowsTheTriangleAcrossEveryEdgeOfAClosedBox) {
  const auto mesh = BuildSoup(testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 2, 3)));
  EXPECT_TRUE(mesh->closed());
  for (std::uint32_t t = 0; t < 12; ++t) {
    const auto& tri = mesh->triangle(t);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = mesh->across(t)[k];
      ASSERT_LT(u, 12u) << t << ' ' << k;
      ASSERT_NE(u, t);
      // u holds the edge the other way round, and its own entry for it leads back to t
      const auto& tri_u = mesh->triangle(u);
      int back = -1;
      for (int j = 0; j < 3; ++j) {
        if (tri_u[j] == tri[(k + 1) % 3] && tri_u[(j + 1) % 3] == tri[k]) back = j;
      }
      ASSERT_GE(back, 0) << t << ' ' << k;
      EXPECT_EQ(mesh->across(u)[back], t);
    }
  }
}

TEST(TriangleMesh, AnOpenSheetHasNothingAcrossItsRim) {
  const auto mesh = BuildSoup(testing::MakeSheetSoup(1.0, 0.0));
  EXPECT_FALSE(mesh->closed());
  // {0, 1, 2} and {0, 2, 3} share the diagonal 0-2: edge 2 of the first, edge 0 of the second
  using A = std::array<std::uint32_t, 3>;
  const std::uint32_t none = TriangleMesh::kNone;
  EXPECT_EQ(mesh->across(0), (A{none, none, 1}));
  EXPECT_EQ(mesh->across(1), (A{0, none, none}));
}

TEST(TriangleMesh, ADiscOfTrianglesFannedRoundItsCentreKnowsItsNeighbours) {
  // triangle i = {centre, rim i, rim i + 1}: its spokes lead to triangles i - 1 and i + 1
  constexpr int kRim = 500;
  TriangleSoup s;
  s.vertices.push_back(Vec3::Zero());
  for (int i = 0; i < kRim; ++i) {
    const double angle = 2.0 * M_PI * i / kRim;
    s.vertices.emplace_back(std::cos(angle), std::sin(angle), 0.0);
  }
  for (int i = 0; i < kRim; ++i) s.triangles.push_back({0, 1 + i, 1 + (i + 1) % kRim});
  s.cad_faces.assign(kRim, 0);
  const auto mesh = BuildSoup(s);
  EXPECT_FALSE(mesh->closed());
  for (std::uint32_t i = 0; i < kRim; ++i) {
    const std::array<std::uint32_t, 3> expected = {(i + kRim - 1) % kRim, TriangleMesh::kNone,
                                                   (i + 1) % kRim};
    ASSERT_EQ(mesh->across(i), expected) << i;
  }
}

TEST(TriangleMesh, RejectsNeighboursWoundAgainstEachOtherNamingTheLaterTriangle) {
  TriangleSoup s = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  std::swap(s.triangles[7][1], s.triangles[7][2]);
  const std::string error = BuildError(s);
  EXPECT_NE(error.find("triangle 7: has an edge that runs the same way in triangle"),
            std::string::npos)
      << error;
}

TEST(TriangleMesh, RejectsAVertexWhereTwoFansMeet) {
  // two closed tetrahedra sharing vertex 0 only
  TriangleSoup s;
  s.vertices = {Vec3(0, 0, 0),  Vec3(1, 0, 0),  Vec3(0, 1, 0), Vec3(0, 0, 1),
                Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)};
  s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
                 {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  s.cad_faces.assign(8, 0);
  EXPECT_NE(BuildError(s).find("vertex 0: its triangles form more than one fan"), std::string::npos)
      << BuildError(s);
  // and two triangles touching at a corner (a bow tie)
  TriangleSoup bow;
  bow.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
  bow.triangles = {{0, 1, 2}, {0, 3, 4}};
  bow.cad_faces = {0, 0};
  EXPECT_NE(BuildError(bow).find("non-manifold vertex"), std::string::npos) << BuildError(bow);
}

TEST(TriangleMesh, FaceNormalsPointOutOfTheBox) {
  const auto mesh = BuildSoup(testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  const Vec3 expected[6] = {-Vec3::UnitX(), Vec3::UnitX(),  -Vec3::UnitY(),
                            Vec3::UnitY(),  -Vec3::UnitZ(), Vec3::UnitZ()};
  for (std::uint32_t t = 0; t < 12; ++t) {
    EXPECT_NEAR((mesh->face_normal(t) - expected[t / 2]).norm(), 0.0, 1e-15) << t;
  }
}

TEST(TriangleMesh, StoresCornerNormalsPerCorner) {
  TriangleSoup s = testing::MakeSheetSoup(1.0, 0.0);
  s.corner_normals = {{Vec3::UnitZ(), Vec3(0, 1, 1).normalized(), Vec3::UnitZ()},
                      {Vec3::UnitZ(), Vec3::UnitZ(), Vec3(1, 0, 1).normalized()}};
  const auto mesh = BuildSoup(s);
  ASSERT_TRUE(mesh->has_corner_normals());
  EXPECT_NEAR((mesh->corner_normal(0, 1) - Vec3(0, 1, 1).normalized()).norm(), 0.0, 1e-7);
  EXPECT_NEAR((mesh->corner_normal(1, 2) - Vec3(1, 0, 1).normalized()).norm(), 0.0, 1e-7);
  EXPECT_NEAR((mesh->corner_normal(0, 0) - Vec3::UnitZ()).norm(), 0.0, 1e-7);
}

TEST(TriangleMesh, RejectsBadInputWithAMessageNamingIt) {
  TriangleSoup s = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  TriangleSoup bad_index = s;
  bad_index.triangles[3][1] = 8;
  EXPECT_NE(BuildError(bad_index).find("triangle 3"), std::string::npos);
  TriangleSoup nan_vertex = s;
  nan_vertex.vertices[5].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(BuildError(nan_vertex).find("vertex 5"), std::string::npos);
  TriangleSoup short_faces = s;
  short_faces.cad_faces.pop_back();
  EXPECT_NE(BuildError(short_faces).find("11 CAD face ids for 12"), std::string::npos);
  TriangleSoup repeated = s;
  repeated.triangles[0] = {1, 1, 2};
  EXPECT_NE(BuildError(repeated).find("repeats a vertex"), std::string::npos);
}

TEST(TriangleMesh, RejectsANonManifoldEdge) {
  // three triangles on one edge (0, 1)
  TriangleSoup s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  s.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  s.cad_faces = {0, 0, 0};
  EXPECT_NE(BuildError(s).find("non-manifold"), std::string::npos) << BuildError(s);
}

}  // namespace
}  // namespace hapticad
