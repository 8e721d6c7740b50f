// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/connected_pieces.h"

#include <gtest/gtest.h>

#include "test_meshes.h"

namespace hapticad {
namespace {

TEST(ConnectedPieces, EachPartIsOnePieceWithItsBox) {
  // two boxes apart, and a vertex that no triangle uses
  TriangleSoup soup = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const TriangleSoup second = testing::MakeBoxSoup(Vec3(3, 0, 0), Vec3(4, 2, 1));
  const auto base = static_cast<std::int32_t>(soup.vertices.size());
  soup.vertices.insert(soup.vertices.end(), second.vertices.begin(), second.vertices.end());
  for (const auto& t : second.triangles) {
    soup.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    soup.cad_faces.push_back(0);
  }
  soup.vertices.push_back(Vec3(9, 9, 9));
  const auto mesh =
      TriangleMesh::Build(soup.vertices, soup.triangles, soup.cad_faces, soup.corner_normals);
  const ConnectedPieces pieces = FindConnectedPieces(*mesh);
  ASSERT_EQ(pieces.lo.size(), 2u);
  ASSERT_EQ(pieces.of_vertex.size(), 17u);
  EXPECT_EQ(pieces.of_vertex[16], ConnectedPieces::kNone);
  for (int v = 1; v < 8; ++v) EXPECT_EQ(pieces.of_vertex[v], pieces.of_vertex[0]) << v;
  for (int v = 9; v < 16; ++v) EXPECT_EQ(pieces.of_vertex[v], pieces.of_vertex[8]) << v;
  const std::uint32_t a = pieces.of_vertex[0], b = pieces.of_vertex[8];
  ASSERT_NE(a, b);
  EXPECT_EQ(pieces.lo[a], Vec3(0, 0, 0));
  EXPECT_EQ(pieces.hi[a], Vec3(1, 1, 1));
  EXPECT_EQ(pieces.lo[b], Vec3(3, 0, 0));
  EXPECT_EQ(pieces.hi[b], Vec3(4, 2, 1));
}

}  // namespace
}  // namespace hapticad
