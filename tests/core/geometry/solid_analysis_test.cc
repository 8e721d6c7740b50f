// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/solid_analysis.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "test_meshes.h"

namespace hapticad {
namespace {

TriangleSoup Boxes(const std::vector<std::array<Vec3, 2>>& boxes, bool last_inward = false) {
  TriangleSoup soup;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    testing::AppendBoxSoup(&soup, boxes[i][0], boxes[i][1], last_inward && i + 1 == boxes.size());
  }
  return soup;
}

// Appends the square sheet z = height over [-half, half]^2 (two triangles, one CAD face).
void AppendSheet(TriangleSoup* soup, double half, double height) {
  const TriangleSoup sheet = testing::MakeSheetSoup(half, height);
  const auto base = static_cast<std::int32_t>(soup->vertices.size());
  soup->vertices.insert(soup->vertices.end(), sheet.vertices.begin(), sheet.vertices.end());
  for (const auto& c : sheet.triangles) {
    soup->triangles.push_back({base + c[0], base + c[1], base + c[2]});
    soup->cad_faces.push_back(100);
  }
}

SolidAnalysis Analyse(const TriangleSoup& soup, std::unique_ptr<TriangleMesh>* keep = nullptr) {
  auto mesh =
      TriangleMesh::Build(soup.vertices, soup.triangles, soup.cad_faces, soup.corner_normals);
  SolidAnalysis out = AnalyseSolids(*mesh);
  if (keep) *keep = std::move(mesh);
  return out;
}

const Vec3 kLo = Vec3::Constant(-0.05);
const Vec3 kHi = Vec3::Constant(0.05);

TEST(AnalyseSolids, AClosedBoxBoundsASolidWoundOutward) {
  const SolidAnalysis s = Analyse(testing::MakeBoxSoup(kLo, kHi));
  EXPECT_TRUE(s.closed);
  EXPECT_FALSE(s.self_intersecting);
  EXPECT_TRUE(s.bounds_solids);
  EXPECT_TRUE(s.pieces_bound_solids);
  ASSERT_EQ(s.piece_winding, std::vector<std::int8_t>{1});
  EXPECT_EQ(s.piece_lo[0], kLo);
  EXPECT_EQ(s.piece_hi[0], kHi);
  // the parity of all crossings decides: no piece per vertex is kept
  EXPECT_TRUE(s.piece_of_vertex.empty());
  // its box, faces and corners included
  EXPECT_TRUE(s.InAnySolidPiece(Vec3(0.01, -0.02, 0.03)));
  EXPECT_TRUE(s.InAnySolidPiece(kHi));
  EXPECT_TRUE(s.InPiece(0, Vec3(0.05, 0.0, -0.05)));
  EXPECT_FALSE(s.InAnySolidPiece(Vec3(0.0, 0.0, 0.0501)));
  EXPECT_FALSE(s.InAnySolidPiece(Vec3(-0.06, 0.0, 0.0)));
}

TEST(AnalyseSolids, ABoxWoundInwardIsACavityWhereverItIs) {
  // alone, near the origin and far from it (the volume's sign must not depend on where
  // the part lies)
  for (const Vec3& shift : {Vec3::Zero().eval(), Vec3(3.0, -2.0, 5.0)}) {
    const SolidAnalysis out = Analyse(Boxes({{kLo + shift, kHi + shift}}));
    EXPECT_EQ(out.piece_winding, std::vector<std::int8_t>{1}) << shift.transpose();
    const SolidAnalysis in = Analyse(Boxes({{kLo + shift, kHi + shift}}, true));
    EXPECT_TRUE(in.bounds_solids) << shift.transpose();
    EXPECT_EQ(in.piece_winding, std::vector<std::int8_t>{-1}) << shift.transpose();
  }
  // a hollow part: the outer shell outward, the cavity's inward; they do not cross
  const SolidAnalysis hollow =
      Analyse(Boxes({{kLo, kHi}, {Vec3::Constant(-0.04), Vec3::Constant(0.04)}}, true));
  EXPECT_TRUE(hollow.closed);
  EXPECT_FALSE(hollow.self_intersecting);
  EXPECT_TRUE(hollow.bounds_solids);
  EXPECT_EQ(hollow.piece_winding, (std::vector<std::int8_t>{1, -1}));
  EXPECT_EQ(hollow.piece_hi[1], Vec3::Constant(0.04));
}

TEST(AnalyseSolids, PartsThatTouchCrossButEachBoundsASolid) {
  // a box and a smaller one against its +x face: the surface crosses itself where they
  // touch, so the parity of all crossings means nothing; each piece alone still bounds
  std::unique_ptr<TriangleMesh> mesh;
  const SolidAnalysis s = Analyse(
      Boxes({{kLo, Vec3(0.0, 0.05, 0.05)}, {Vec3(0.0, -0.04, -0.04), Vec3(0.05, 0.04, 0.04)}}),
      &mesh);
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.self_intersecting);
  EXPECT_FALSE(s.bounds_solids);
  EXPECT_TRUE(s.pieces_bound_solids);
  EXPECT_EQ(s.piece_winding, (std::vector<std::int8_t>{1, 1}));
  EXPECT_EQ(s.piece_lo[1], Vec3(0.0, -0.04, -0.04));
  EXPECT_EQ(s.piece_hi[0], Vec3(0.0, 0.05, 0.05));
  // sweeps that see one piece alone need each vertex's piece
  ASSERT_EQ(s.piece_of_vertex.size(), mesh->num_vertices());
  for (std::uint32_t v = 0; v < 16; ++v) EXPECT_EQ(s.piece_of_vertex[v], v < 8 ? 0u : 1u) << v;
  EXPECT_TRUE(s.InPiece(1, Vec3(0.03, 0.0, 0.0)));
  EXPECT_FALSE(s.InPiece(0, Vec3(0.03, 0.0, 0.0)));
  EXPECT_GE(s.CalcMemoryBytes(), 16 * sizeof(std::uint32_t) + 4 * sizeof(Vec3) + 2);
  // apart, they are two solids and the whole surface's parity holds
  const SolidAnalysis apart = Analyse(
      Boxes({{kLo, Vec3(0.0, 0.05, 0.05)}, {Vec3(0.01, -0.04, -0.04), Vec3(0.06, 0.04, 0.04)}}));
  EXPECT_FALSE(apart.self_intersecting);
  EXPECT_TRUE(apart.bounds_solids);
  EXPECT_EQ(apart.piece_winding, (std::vector<std::int8_t>{1, 1}));
  EXPECT_TRUE(apart.piece_of_vertex.empty());
}

TEST(AnalyseSolids, APieceThatCrossesItselfBoundsNothing) {
  // a box whose top corner is pulled down through its bottom: closed, and its faces cross
  TriangleSoup soup = testing::MakeBoxSoup(kLo, kHi);
  for (Vec3& v : soup.vertices) {
    if (v == kHi) v = Vec3(0.05, 0.05, -0.08);
  }
  const SolidAnalysis s = Analyse(soup);
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.self_intersecting);
  EXPECT_FALSE(s.bounds_solids);
  EXPECT_FALSE(s.pieces_bound_solids);
  EXPECT_TRUE(s.piece_winding.empty());
  EXPECT_FALSE(s.InAnySolidPiece(Vec3::Zero()));
}

TEST(AnalyseSolids, AnOpenPieceBoundsNothingAndLeavesTheClosedOnesKnown) {
  // a box without its lid: nothing is inside anything
  TriangleSoup cup = testing::MakeBoxSoup(kLo, kHi);
  cup.triangles.resize(10);
  cup.cad_faces.resize(10);
  const SolidAnalysis open = Analyse(cup);
  EXPECT_FALSE(open.closed);
  EXPECT_FALSE(open.self_intersecting);
  EXPECT_FALSE(open.bounds_solids);
  EXPECT_FALSE(open.pieces_bound_solids);
  // a box and a sheet above it, and one through it (crossing the box, not itself)
  for (const double height : {0.08, 0.0}) {
    TriangleSoup soup = testing::MakeBoxSoup(kLo, kHi);
    AppendSheet(&soup, 0.1, height);
    const SolidAnalysis s = Analyse(soup);
    EXPECT_FALSE(s.closed) << height;
    EXPECT_EQ(s.self_intersecting, height == 0.0) << height;
    EXPECT_FALSE(s.bounds_solids) << height;
    EXPECT_TRUE(s.pieces_bound_solids) << height;
    EXPECT_EQ(s.piece_winding, (std::vector<std::int8_t>{1, 0})) << height;
    // in the sheet's box but not the part's: in no solid piece
    EXPECT_TRUE(s.InPiece(1, Vec3(0.08, 0.0, height)));
    EXPECT_FALSE(s.InAnySolidPiece(Vec3(0.08, 0.0, height))) << height;
    EXPECT_TRUE(s.InAnySolidPiece(Vec3(0.0, 0.0, -0.02))) << height;
  }
}

}  // namespace
}  // namespace hapticad
