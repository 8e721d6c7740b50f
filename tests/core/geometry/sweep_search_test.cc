// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/sweep_search.h"

#include <gtest/gtest.h>

#include "hapticad/core/geometry/connected_pieces.h"
#include "hapticad/core/geometry/triangle_grid.h"
#include "hapticad/core/geometry/triangle_tree.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

// A query that sees one piece alone skips every other piece's triangles, whichever
// structure feeds it: a box inside a box, a ray down through both tops.
TEST(SweepSearch, AQueryForOnePieceSeesThatPieceAlone) {
  TriangleSoup soup = testing::MakeBoxSoup(Vec3::Constant(-1.0), Vec3::Constant(1.0));
  const TriangleSoup inner = testing::MakeBoxSoup(Vec3::Constant(-0.5), Vec3::Constant(0.5));
  const auto base = static_cast<std::int32_t>(soup.vertices.size());
  soup.vertices.insert(soup.vertices.end(), inner.vertices.begin(), inner.vertices.end());
  for (std::size_t t = 0; t < inner.triangles.size(); ++t) {
    const auto& c = inner.triangles[t];
    soup.triangles.push_back({base + c[0], base + c[1], base + c[2]});
    soup.cad_faces.push_back(6 + inner.cad_faces[t]);
  }
  const auto mesh = TriangleMesh::Build(soup.vertices, soup.triangles, soup.cad_faces, {});
  const ConnectedPieces pieces = FindConnectedPieces(*mesh);
  ASSERT_EQ(pieces.lo.size(), 2u);
  const std::uint32_t outer_piece = pieces.of_vertex[0];
  const std::uint32_t inner_piece = pieces.of_vertex[static_cast<std::size_t>(base)];
  ASSERT_NE(outer_piece, inner_piece);
  const auto tree = TriangleTree::Build(*mesh, 1e-12);
  const auto grid = TriangleGrid::Build(*mesh, 1e-12);
  for (const bool use_grid : {false, true}) {
    const auto top_hit = [&](const std::uint32_t* of_vertex, std::uint32_t piece) {
      SweepQuery q;
      q.a = Vec3(0.1, 0.2, 3.0);
      q.b = Vec3(0.1, 0.2, -3.0);
      q.piece_of_vertex = of_vertex;
      q.piece = piece;
      SweepSearch search(*mesh, q);
      if (use_grid) {
        grid->Search(&search);
      } else {
        tree->Search(&search);
      }
      EXPECT_TRUE(search.found());
      SweepHit hit;
      search.Report(&hit);
      return hit.point.z();
    };
    EXPECT_DOUBLE_EQ(top_hit(nullptr, 0), 1.0) << use_grid;
    EXPECT_DOUBLE_EQ(top_hit(pieces.of_vertex.data(), outer_piece), 1.0) << use_grid;
    EXPECT_DOUBLE_EQ(top_hit(pieces.of_vertex.data(), inner_piece), 0.5) << use_grid;
  }
}

}  // namespace
}  // namespace hapticad
