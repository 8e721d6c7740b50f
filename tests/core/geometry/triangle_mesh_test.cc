// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/triangle_mesh.h"

#include <limits>
#include <stdexcept>
#include <string>

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

TEST(TriangleMesh, KeepsTheCadFaceOfEveryTriangleAsAnOpenMeshProperty) {
  const auto mesh = BuildSoup(testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 2, 3)));
  ASSERT_EQ(mesh->num_triangles(), 12u);
  EXPECT_EQ(mesh->num_vertices(), 8u);
  EXPECT_EQ(mesh->num_cad_faces(), 6);
  const auto& om = mesh->openmesh();
  OpenMesh::FPropHandleT<std::int32_t> prop;
  ASSERT_TRUE(om.get_property_handle(prop, "cad_face"));
  for (std::uint32_t t = 0; t < 12; ++t) {
    EXPECT_EQ(mesh->cad_face(t), static_cast<int>(t / 2));
    EXPECT_EQ(om.property(prop, om.face_handle(t)), static_cast<int>(t / 2));
  }
  EXPECT_TRUE(om.is_boundary(om.vertex_handle(0)) == false);  // closed box
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
