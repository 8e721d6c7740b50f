// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/mesh_repair.h"

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

// A box whose six faces are tessellated on their own, as a CAD tessellator hands them
// over: each face has its own four vertices (24 in all), optionally nudged by `nudge`.
TriangleSoup FacewiseBox(double nudge) {
  const TriangleSoup box = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(10, 20, 30));
  TriangleSoup out;
  for (std::size_t t = 0; t < box.triangles.size(); ++t) {
    std::array<std::int32_t, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      tri[k] = static_cast<std::int32_t>(out.vertices.size());
      out.vertices.push_back(box.vertices[box.triangles[t][k]] +
                             Vec3::Constant(nudge * ((t + k) % 3 == 0 ? 1.0 : -0.5)));
    }
    out.triangles.push_back(tri);
    out.cad_faces.push_back(box.cad_faces[t]);
  }
  return out;
}

RepairReport Repair(const TriangleSoup& soup, TriangleSoup* out = nullptr) {
  RepairReport report;
  TriangleSoup repaired = RepairSoup(soup, RepairOptions{}, &report);
  if (out != nullptr) *out = repaired;
  return report;
}

TEST(MeshRepair, MergesTheVerticesOfSeparatelyTessellatedFacesIntoAClosedSurface) {
  TriangleSoup out;
  const RepairReport r = Repair(FacewiseBox(0.0), &out);
  EXPECT_EQ(r.merged_vertices, 36u - 8u);
  EXPECT_EQ(r.output_triangles, 12u);
  EXPECT_TRUE(r.watertight()) << r.Describe();
  // the CAD faces follow their triangles
  ASSERT_EQ(out.cad_faces.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t) EXPECT_EQ(out.cad_faces[t], static_cast<int>(t / 2));
}

TEST(MeshRepair, AnIcosphereWithEveryCornerItsOwnVertexInShuffledOrderComesBackWhole) {
  // an STL's kind of soup: no vertex shared, triangles in no order
  const TriangleSoup sphere = MakeIcosphere(12, 50.0);
  std::vector<std::size_t> order(sphere.triangles.size());
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = t;
  std::mt19937 rng(7);
  std::shuffle(order.begin(), order.end(), rng);
  TriangleSoup soup;
  for (const std::size_t t : order) {
    std::array<std::int32_t, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      tri[k] = static_cast<std::int32_t>(soup.vertices.size());
      soup.vertices.push_back(sphere.vertices[sphere.triangles[t][k]]);
    }
    soup.triangles.push_back(tri);
    soup.cad_faces.push_back(static_cast<std::int32_t>(t));
  }
  TriangleSoup out;
  const RepairReport r = Repair(soup, &out);
  EXPECT_TRUE(r.watertight()) << r.Describe();
  EXPECT_EQ(r.output_triangles, sphere.triangles.size());
  EXPECT_EQ(r.reoriented, 0u);
  EXPECT_EQ(out.vertices.size(), sphere.vertices.size());
  EXPECT_EQ(r.merged_vertices, soup.vertices.size() - sphere.vertices.size());
  // every triangle keeps its corners, in order up to rotation, and its CAD face
  ASSERT_EQ(out.triangles.size(), soup.triangles.size());
  for (std::size_t t = 0; t < out.triangles.size(); ++t) {
    const auto& in = sphere.triangles[static_cast<std::size_t>(out.cad_faces[t])];
    const Vec3 first = out.vertices[out.triangles[t][0]];
    int shift = 0;
    while (shift < 3 && sphere.vertices[in[shift]] != first) ++shift;
    ASSERT_LT(shift, 3) << "triangle " << t;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(out.vertices[out.triangles[t][k]], sphere.vertices[in[(shift + k) % 3]]);
    }
  }
}

TEST(MeshRepair, WeldsCracksBetweenFacesWithinTheToleranceAndReportsWiderOnes) {
  // 3e-8 mm apart on a 37 mm box (8e-10 of its diagonal): welded
  const RepairReport close = Repair(FacewiseBox(3e-8));
  EXPECT_GT(close.welded_vertices, 0u);
  EXPECT_TRUE(close.watertight()) << close.Describe();
  // 10 um apart: a real crack, reported, never silently closed
  const RepairReport wide = Repair(FacewiseBox(1e-2));
  EXPECT_EQ(wide.welded_vertices, 0u);
  EXPECT_EQ(wide.boundary_edges, 24u);  // each face's four sides
  EXPECT_NE(wide.Describe().find("NOT REPAIRED: 24 open edges"), std::string::npos)
      << wide.Describe();
}

TEST(MeshRepair, RemovesDegenerateNeedleAndDuplicateTriangles) {
  TriangleSoup s = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  s.vertices.push_back(Vec3(0.5, 0, 0));          // 8: on the edge 0-1 of the bottom
  s.vertices.push_back(Vec3(0.5, 1e-13, 1e-13));  // 9: a hair off it
  s.triangles.push_back({0, 0, 1});               // repeated vertex
  s.triangles.push_back({0, 8, 1});               // collinear: zero area
  s.triangles.push_back({0, 9, 1});               // a cap 1e-13 high on a unit edge
  s.triangles.push_back({0, 2, 3});               // the bottom's first triangle again
  s.triangles.push_back({3, 0, 2});               // ... and again, turned
  for (int i = 0; i < 5; ++i) s.cad_faces.push_back(4);
  TriangleSoup out;
  const RepairReport r = Repair(s, &out);
  EXPECT_EQ(r.removed_degenerate, 3u);
  EXPECT_EQ(r.removed_duplicates, 2u);
  EXPECT_EQ(out.triangles.size(), 12u);
  EXPECT_TRUE(r.watertight()) << r.Describe();
}

// The unit box with its top (CAD face 5) tessellated again with more vertices on its
// front edge 4-5, (0, 0, 1)-(1, 0, 1), for a filler to close: as FreeCAD's mesher leaves
// T-junctions. The box's own front triangle 0-5-4 keeps the whole edge.
TriangleSoup BoxWithANewTop(const std::vector<Vec3>& more,
                            const std::vector<std::array<std::int32_t, 3>>& top) {
  TriangleSoup s = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  s.triangles.resize(10);  // the top's two triangles go
  s.cad_faces.resize(10);
  s.vertices.insert(s.vertices.end(), more.begin(), more.end());
  for (const auto& t : top) {
    s.triangles.push_back(t);
    s.cad_faces.push_back(5);
  }
  return s;
}

TEST(MeshRepair, ACollinearCapAtATJunctionIsMendedSoAClosedSoupStaysClosed) {
  // the top fanned from 8, the middle of the front edge, and a cap 4-5-8 (zero area)
  // filling the T-junction between the top's edges 4-8, 8-5 and the front's 5-4: every
  // edge has two triangles. Removed, the cap would leave three open edges
  TriangleSoup s = BoxWithANewTop({Vec3(0.5, 0, 1)}, {{4, 8, 6}, {8, 5, 7}, {8, 7, 6}, {4, 5, 8}});
  // corner normals of a ball round the box's centre: what the split's new corner gets,
  // interpolated between the front edge's ends, is the ball's own there
  const auto ball = [](const Vec3& v) { return Vec3((v - Vec3::Constant(0.5)).normalized()); };
  for (const auto& t : s.triangles) {
    s.corner_normals.push_back(
        {ball(s.vertices[t[0]]), ball(s.vertices[t[1]]), ball(s.vertices[t[2]])});
  }
  for (const double shift : {0.0, 1e6}) {
    TriangleSoup moved = s;
    for (Vec3& v : moved.vertices) v += Vec3::Constant(shift);
    TriangleSoup out;
    const RepairReport r = Repair(moved, &out);
    const std::string where = "shift " + std::to_string(shift) + ": " + r.Describe();
    EXPECT_TRUE(r.watertight()) << where;
    EXPECT_EQ(r.boundary_edges, 0u) << where;
    EXPECT_EQ(r.removed_degenerate, 1u) << where;
    EXPECT_EQ(r.split_caps, 1u) << where;
    EXPECT_EQ(r.output_triangles, 14u) << where;  // 14 in: the cap out, the front's 0-5-4 in two
    EXPECT_NE(r.Describe().find("1 caps mended"), std::string::npos) << where;
    // the front (CAD face 2) is now 0-1-5, 0-5-8 and 0-8-4; every corner keeps the
    // ball's normal at its vertex
    int front = 0;
    for (std::size_t t = 0; t < out.triangles.size(); ++t) {
      front += out.cad_faces[t] == 2;
      for (int k = 0; k < 3; ++k) {
        const Vec3 at = out.vertices[out.triangles[t][k]] - Vec3::Constant(shift);
        EXPECT_LT((out.corner_normals[t][k] - ball(at)).norm(), 1e-12) << where << ", " << t;
      }
    }
    EXPECT_EQ(front, 3) << where;
    EXPECT_NO_THROW(
        TriangleMesh::Build(out.vertices, out.triangles, out.cad_faces, out.corner_normals));
  }
}

TEST(MeshRepair, AChainOfCapsIsMendedCapByCap) {
  // two vertices on the front edge, 8 at x = 0.25 and 9 at 0.5, and two caps: 4-5-9
  // across the front's edge 4-5, and 4-9-8 across the first cap's edge 4-9. Listed
  // first, the second waits for the first's split to give it a triangle across
  TriangleSoup s =
      BoxWithANewTop({Vec3(0.25, 0, 1), Vec3(0.5, 0, 1)},
                     {{6, 4, 8}, {6, 8, 9}, {6, 9, 5}, {6, 5, 7}, {4, 9, 8}, {4, 5, 9}});
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    s.corner_normals.push_back({Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()});
  }
  TriangleSoup out;
  const RepairReport r = Repair(s, &out);
  EXPECT_TRUE(r.watertight()) << r.Describe();
  EXPECT_EQ(r.split_caps, 2u) << r.Describe();
  EXPECT_EQ(r.removed_degenerate, 2u) << r.Describe();
  EXPECT_EQ(r.output_triangles, 16u) << r.Describe();
  EXPECT_EQ(std::count(out.cad_faces.begin(), out.cad_faces.end(), 2), 4);  // the front, in four
  // the split corners' normals are unit (interpolated) and the mesh takes them
  EXPECT_NO_THROW(
      TriangleMesh::Build(out.vertices, out.triangles, out.cad_faces, out.corner_normals));
}

TEST(MeshRepair, TJunctionCapsAllOverASphereAreAllMendedWithTheSpheresNormals) {
  // an icosphere where each triangle a-b-c not yet taken, whose neighbour b-a-d across
  // its first edge is not either, is cut in two at that edge's middle m (a T-junction:
  // a-m-c, m-b-c) and a cap a-b-m fills it against b-a-d. Every corner normal is the
  // sphere's own at its vertex (m/|m| at m): so must be the ones the splits add
  const TriangleSoup sphere = MakeIcosphere(6, 10.0);
  const auto radial = [](const Vec3& v) { return Vec3(v.normalized()); };
  std::map<std::pair<std::int32_t, std::int32_t>, std::size_t> by_edge;
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      by_edge[{sphere.triangles[t][k], sphere.triangles[t][(k + 1) % 3]}] = t;
    }
  }
  std::vector<char> taken(sphere.triangles.size(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  // a-b-c and its neighbour b-a-d
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
    const std::size_t across = by_edge.at({sphere.triangles[t][1], sphere.triangles[t][0]});
    if (taken[t] || taken[across]) continue;
    taken[t] = taken[across] = 1;
    pairs.emplace_back(t, across);
  }
  TriangleSoup soup;
  soup.vertices = sphere.vertices;
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
    if (!taken[t]) soup.triangles.push_back(sphere.triangles[t]);
  }
  for (const auto& [t, across] : pairs) {
    const auto [a, b, c] = sphere.triangles[t];
    const auto m = static_cast<std::int32_t>(soup.vertices.size());
    soup.vertices.push_back(0.5 * (sphere.vertices[a] + sphere.vertices[b]));
    soup.triangles.push_back({a, m, c});
    soup.triangles.push_back({m, b, c});
    soup.triangles.push_back({a, b, m});
    soup.triangles.push_back(sphere.triangles[across]);
  }
  const std::size_t caps = pairs.size();
  for (const auto& t : soup.triangles) {
    soup.cad_faces.push_back(0);
    soup.corner_normals.push_back(
        {radial(soup.vertices[t[0]]), radial(soup.vertices[t[1]]), radial(soup.vertices[t[2]])});
  }
  ASSERT_GT(caps, sphere.triangles.size() / 4);
  TriangleSoup out;
  const RepairReport r = Repair(soup, &out);
  EXPECT_TRUE(r.watertight()) << r.Describe();
  EXPECT_EQ(r.split_caps, caps) << r.Describe();
  EXPECT_EQ(r.removed_degenerate, caps) << r.Describe();
  EXPECT_EQ(r.output_triangles, sphere.triangles.size() + 2 * caps) << r.Describe();
  EXPECT_EQ(r.reoriented, 0u) << r.Describe();
  for (std::size_t t = 0; t < out.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT((out.corner_normals[t][k] - radial(out.vertices[out.triangles[t][k]])).norm(),
                1e-12)
          << t;
    }
  }
  EXPECT_NO_THROW(
      TriangleMesh::Build(out.vertices, out.triangles, out.cad_faces, out.corner_normals));
}

TEST(MeshRepair, ANeedleIsCollapsedSoAClosedSoupStaysClosed) {
  // the top fanned from two vertices 1e-12 apart in its middle, 8 and 9, and two needles
  // 8-5-9 and 9-6-8 between the fans: every edge has two triangles. Removed, the needles
  // would leave four open edges; collapsed, 8 and 9 are one vertex and the top one fan
  const Vec3 middle(0.5, 0.5, 1);
  TriangleSoup s =
      BoxWithANewTop({middle, middle + Vec3(1e-12, 0, 0)},
                     {{4, 5, 8}, {5, 7, 9}, {7, 6, 9}, {6, 4, 8}, {8, 5, 9}, {9, 6, 8}});
  TriangleSoup out;
  const RepairReport r = Repair(s, &out);
  EXPECT_TRUE(r.watertight()) << r.Describe();
  EXPECT_EQ(r.collapsed_needles, 1u) << r.Describe();
  EXPECT_EQ(r.removed_degenerate, 2u) << r.Describe();
  EXPECT_EQ(r.output_triangles, 14u) << r.Describe();
  EXPECT_EQ(out.vertices.size(), 9u);
  EXPECT_NE(r.Describe().find("1 needles collapsed"), std::string::npos) << r.Describe();
  EXPECT_NO_THROW(
      TriangleMesh::Build(out.vertices, out.triangles, out.cad_faces, out.corner_normals));
}

TEST(MeshRepair, ANeedleWhoseCollapseWouldPinchTheSurfaceIsRemovedAsBefore) {
  // as above, with a fin 4-9-10 standing on the top: 4 is a neighbour of both 8 and 9
  // without a triangle 8-9-4, so welding them would give edge 4-8 three triangles. The
  // needles are removed, and what that opens is reported: their four outer edges and
  // the fin's three
  const Vec3 middle(0.5, 0.5, 1);
  TriangleSoup s = BoxWithANewTop(
      {middle, middle + Vec3(1e-12, 0, 0), Vec3(0.5, -1, 2)},
      {{4, 5, 8}, {5, 7, 9}, {7, 6, 9}, {6, 4, 8}, {8, 5, 9}, {9, 6, 8}, {4, 9, 10}});
  const RepairReport r = Repair(s);
  EXPECT_EQ(r.collapsed_needles, 0u) << r.Describe();
  EXPECT_EQ(r.removed_degenerate, 2u) << r.Describe();
  EXPECT_EQ(r.non_manifold_edges, 0u) << r.Describe();
  EXPECT_EQ(r.boundary_edges, 7u) << r.Describe();
}

TEST(MeshRepair, OrientsConsistentlyAndFlipsTheCornerNormalsWithTheTriangle) {
  TriangleSoup s = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    s.corner_normals.push_back({Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()});
  }
  std::swap(s.triangles[5][1], s.triangles[5][2]);  // one triangle wound the wrong way
  std::swap(s.corner_normals[5][1], s.corner_normals[5][2]);
  TriangleSoup out;
  const RepairReport r = Repair(s, &out);
  EXPECT_EQ(r.reoriented, 1u);
  EXPECT_TRUE(r.watertight());
  // each corner keeps its own normal, whichever way the triangle now turns
  for (std::size_t t = 0; t < out.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = out.vertices[out.triangles[t][k]];
      const Vec3& q = s.vertices[s.triangles[t][0]];
      if ((p - q).norm() == 0.0) {
        EXPECT_EQ(out.corner_normals[t][k], s.corner_normals[t][0]) << t;
      }
    }
  }
  // and the winding agrees: every edge is used once each way
  const auto mesh =
      TriangleMesh::Build(out.vertices, out.triangles, out.cad_faces, out.corner_normals);
  EXPECT_EQ(mesh->num_triangles(), 12u);
}

// Appends `more` to `soup`, every triangle on CAD face `face`.
void Append(const TriangleSoup& more, std::int32_t face, TriangleSoup* soup) {
  const auto base = static_cast<std::int32_t>(soup->vertices.size());
  soup->vertices.insert(soup->vertices.end(), more.vertices.begin(), more.vertices.end());
  for (const auto& t : more.triangles) {
    soup->triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    soup->cad_faces.push_back(face);
    if (!more.corner_normals.empty()) soup->corner_normals.push_back({});
  }
}

// Every triangle wound the other way, its corner normals with their corners.
TriangleSoup WoundTheOtherWay(TriangleSoup soup) {
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    std::swap(soup.triangles[t][1], soup.triangles[t][2]);
    if (!soup.corner_normals.empty())
      std::swap(soup.corner_normals[t][1], soup.corner_normals[t][2]);
  }
  return soup;
}

// Six times the signed volume bounded by the triangles whose corners all lie on the
// surface of the box [lo, hi] (one piece of a scene of boxes), about lo.
double VolumeOnBox(const TriangleSoup& soup, const Vec3& lo, const Vec3& hi) {
  const auto on = [&](const Vec3& p) {
    const bool in = (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    return in && ((p - lo).cwiseAbs().minCoeff() == 0.0 || (p - hi).cwiseAbs().minCoeff() == 0.0);
  };
  double volume = 0.0;
  for (const auto& t : soup.triangles) {
    const Vec3 &a = soup.vertices[t[0]], &b = soup.vertices[t[1]], &c = soup.vertices[t[2]];
    if (on(a) && on(b) && on(c)) volume += (a - lo).dot((b - lo).cross(c - lo));
  }
  return volume;
}

TEST(MeshRepair, TurnsAPartWoundInsideOutOutwardAndItsVoidInward) {
  // a hollow part: a 10 mm cube round a 4 mm void (wound inward, as a B-rep's inner shell)
  TriangleSoup hollow = testing::MakeBoxSoup(Vec3::Zero(), Vec3::Constant(10.0));
  Append(WoundTheOtherWay(testing::MakeBoxSoup(Vec3::Constant(3.0), Vec3::Constant(7.0))), 6,
         &hollow);
  for (std::size_t t = 0; t < hollow.triangles.size(); ++t) {
    hollow.corner_normals.push_back({Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()});
  }
  for (const double scale : {1.0, 1e-3}) {
    for (const double shift : {0.0, 1e6}) {
      const auto moved = [&](TriangleSoup s) {
        for (Vec3& v : s.vertices) v = v * scale + Vec3::Constant(shift);
        return s;
      };
      const std::string where =
          "scale " + std::to_string(scale) + ", shift " + std::to_string(shift);
      const Vec3 lo = Vec3::Constant(shift), hi = Vec3::Constant(10.0 * scale + shift);
      const Vec3 void_lo = Vec3::Constant(3.0 * scale + shift);
      const Vec3 void_hi = Vec3::Constant(7.0 * scale + shift);
      // as made: nothing to turn
      TriangleSoup out;
      RepairReport r = Repair(moved(hollow), &out);
      EXPECT_EQ(r.inside_out_shells, 0u) << where;
      EXPECT_GT(VolumeOnBox(out, lo, hi), 0.0) << where;
      EXPECT_LT(VolumeOnBox(out, void_lo, void_hi), 0.0) << where;
      // as a file wound clockwise hands it over: both shells turned round, and said so
      const TriangleSoup inside_out = moved(WoundTheOtherWay(hollow));
      r = Repair(inside_out, &out);
      EXPECT_EQ(r.inside_out_shells, 2u) << where;
      EXPECT_NE(r.Describe().find("2 closed shells wound inside out turned round"),
                std::string::npos)
          << r.Describe();
      EXPECT_TRUE(r.watertight()) << where;
      EXPECT_GT(VolumeOnBox(out, lo, hi), 0.0) << where;
      EXPECT_LT(VolumeOnBox(out, void_lo, void_hi), 0.0) << where;
      // each corner keeps its own normal (the CAD surface's, not the winding's)
      ASSERT_EQ(out.triangles.size(), inside_out.triangles.size());
      for (std::size_t t = 0; t < out.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
          for (int j = 0; j < 3; ++j) {
            if (out.vertices[out.triangles[t][k]] ==
                inside_out.vertices[inside_out.triangles[t][j]]) {
              EXPECT_EQ(out.corner_normals[t][k], inside_out.corner_normals[t][j]) << where;
            }
          }
        }
      }
    }
  }
}

TEST(MeshRepair, TurnsOnlyTheShellsThatAreInsideOut) {
  // three cubes in a row: the second, wound inward, touches the first face to face,
  // offset (its corner at lo lies on the first's face: no clean count from there), the
  // third stands apart
  TriangleSoup row = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const Vec3 second_lo(1, 0.5, 0.25), second_hi(2, 1.5, 1.25);
  Append(WoundTheOtherWay(testing::MakeBoxSoup(second_lo, second_hi)), 6, &row);
  Append(testing::MakeBoxSoup(Vec3(3, 0, 0), Vec3(4, 1, 1)), 7, &row);
  // and a lidless cup wound inward: open, it bounds nothing, and stays as it is
  TriangleSoup cup = WoundTheOtherWay(testing::MakeBoxSoup(Vec3(5, 0, 0), Vec3(6, 1, 1)));
  cup.triangles.resize(10);
  cup.cad_faces.resize(10);
  Append(cup, 8, &row);
  TriangleSoup out;
  const RepairReport r = Repair(row, &out);
  EXPECT_EQ(r.inside_out_shells, 1u) << r.Describe();
  EXPECT_GT(VolumeOnBox(out, Vec3(0, 0, 0), Vec3(1, 1, 1)), 0.0);
  EXPECT_GT(VolumeOnBox(out, second_lo, second_hi), 0.0);
  EXPECT_GT(VolumeOnBox(out, Vec3(3, 0, 0), Vec3(4, 1, 1)), 0.0);
  EXPECT_LT(VolumeOnBox(out, Vec3(5, 0, 0), Vec3(6, 1, 1)), 0.0);  // the cup, untouched
}

TEST(MeshRepair, PartsThatOverlapAreNoVoidsAndACrackedShellsVoidIsLeftAlone) {
  // a cube with one triangle wound the wrong way: the orientation follows that triangle
  // and winds the whole cube inward (11 reoriented); a second cube, wound outward,
  // overlaps it. Only the first is turned; the second is a part, not its void
  TriangleSoup overlapping = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(2, 2, 2));
  std::swap(overlapping.triangles[0][1], overlapping.triangles[0][2]);
  Append(testing::MakeBoxSoup(Vec3(1, 1, 1), Vec3(3, 3, 3)), 6, &overlapping);
  TriangleSoup out;
  RepairReport r = Repair(overlapping, &out);
  EXPECT_EQ(r.reoriented, 11u) << r.Describe();
  EXPECT_EQ(r.inside_out_shells, 1u) << r.Describe();
  EXPECT_GT(VolumeOnBox(out, Vec3(0, 0, 0), Vec3(2, 2, 2)), 0.0);
  EXPECT_GT(VolumeOnBox(out, Vec3(1, 1, 1), Vec3(3, 3, 3)), 0.0);
  // both wound inward (a file listed clockwise): each has a corner outside the other,
  // so neither is a void, and both are turned
  TriangleSoup clockwise = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(2, 2, 2));
  Append(testing::MakeBoxSoup(Vec3(1, 1, 1), Vec3(3, 3, 3)), 6, &clockwise);
  r = Repair(WoundTheOtherWay(clockwise), &out);
  EXPECT_EQ(r.inside_out_shells, 2u) << r.Describe();
  EXPECT_GT(VolumeOnBox(out, Vec3(0, 0, 0), Vec3(2, 2, 2)), 0.0);
  EXPECT_GT(VolumeOnBox(out, Vec3(1, 1, 1), Vec3(3, 3, 3)), 0.0);
  // a hollow part whose outer shell has a crack (one triangle missing): its void, wound
  // inward, lies in the cracked shell's box and is left as the tessellator wound it
  TriangleSoup cracked = testing::MakeBoxSoup(Vec3::Zero(), Vec3::Constant(10.0));
  cracked.triangles.pop_back();
  cracked.cad_faces.pop_back();
  Append(WoundTheOtherWay(testing::MakeBoxSoup(Vec3::Constant(3.0), Vec3::Constant(7.0))), 6,
         &cracked);
  r = Repair(cracked, &out);
  EXPECT_EQ(r.inside_out_shells, 0u) << r.Describe();
  EXPECT_LT(VolumeOnBox(out, Vec3::Constant(3.0), Vec3::Constant(7.0)), 0.0);
}

TEST(MeshRepair, APartWithManyVoidsIsToldApartFromItsVoidsAsWithOne) {
  // four voids in one block: 32 vertices ask about the block's inside, enough that the
  // repair answers them from CGAL's tree over it rather than one parity count each
  TriangleSoup block = testing::MakeBoxSoup(Vec3::Zero(), Vec3::Constant(10.0));
  for (const double at : {1.0, 3.0, 5.0, 7.0}) {
    Append(WoundTheOtherWay(testing::MakeBoxSoup(Vec3::Constant(at), Vec3::Constant(at + 1.0))), 6,
           &block);
  }
  for (const bool clockwise : {false, true}) {
    TriangleSoup out;
    const RepairReport r = Repair(clockwise ? WoundTheOtherWay(block) : block, &out);
    EXPECT_EQ(r.inside_out_shells, clockwise ? 5u : 0u) << r.Describe();
    EXPECT_GT(VolumeOnBox(out, Vec3::Zero(), Vec3::Constant(10.0)), 0.0) << clockwise;
    for (const double at : {1.0, 3.0, 5.0, 7.0}) {
      EXPECT_LT(VolumeOnBox(out, Vec3::Constant(at), Vec3::Constant(at + 1.0)), 0.0)
          << clockwise << ", void at " << at;
    }
  }
}

TEST(MeshRepair, SplitsANonManifoldEdgeAndSaysSo) {
  TriangleSoup s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  s.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  s.cad_faces = {0, 0, 0};
  TriangleSoup out;
  const RepairReport r = Repair(s, &out);
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_FALSE(r.watertight());
  EXPECT_EQ(out.triangles.size(), 3u);
  EXPECT_NE(r.Describe().find("non-manifold"), std::string::npos);
  // the result is manifold: the mesh, which checks its edges and fans, takes it
  EXPECT_NO_THROW(
      TriangleMesh::Build(out.vertices, out.triangles, out.cad_faces, out.corner_normals));
}

TEST(MeshRepair, TwoClosedPartsTouchingAlongAnEdgeAreClosedAfterTheSplit) {
  // two tagged blocks sharing one edge: the edge is split, every edge then has two
  // triangles, and the report says closed in both its words and watertight()
  TriangleSoup s = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const TriangleSoup b = testing::MakeBoxSoup(Vec3(1, 1, 0), Vec3(2, 2, 1));
  const auto offset = static_cast<std::int32_t>(s.vertices.size());
  s.vertices.insert(s.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (std::size_t t = 0; t < b.triangles.size(); ++t) {
    s.triangles.push_back(
        {b.triangles[t][0] + offset, b.triangles[t][1] + offset, b.triangles[t][2] + offset});
    s.cad_faces.push_back(b.cad_faces[t] + 6);
  }
  TriangleSoup out;
  const RepairReport r = Repair(s, &out);
  EXPECT_EQ(r.non_manifold_edges, 1u) << r.Describe();
  EXPECT_EQ(r.boundary_edges, 0u) << r.Describe();
  EXPECT_TRUE(r.watertight()) << r.Describe();
  EXPECT_NE(r.Describe().find("; closed"), std::string::npos) << r.Describe();
}

TEST(MeshRepair, DropsNonFiniteTrianglesAndRejectsWhatCannotBeRepaired) {
  TriangleSoup s = testing::MakeBoxSoup(Vec3(0, 0, 0), Vec3(1, 1, 1));
  s.vertices.push_back(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  s.triangles.push_back({0, 1, 8});
  s.cad_faces.push_back(0);
  const RepairReport r = Repair(s);
  EXPECT_EQ(r.removed_nonfinite, 1u);
  EXPECT_TRUE(r.watertight());

  TriangleSoup bad_index = s;
  bad_index.triangles[3][2] = 99;
  try {
    Repair(bad_index);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 3"), std::string::npos) << e.what();
  }
  TriangleSoup all_degenerate;
  all_degenerate.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  all_degenerate.triangles = {{0, 1, 2}};
  all_degenerate.cad_faces = {0};
  EXPECT_THROW(Repair(all_degenerate), std::invalid_argument);
}

TEST(MeshRepair, ToleranceIsRelativeSoMillimetresAndMetresRepairAlike) {
  TriangleSoup mm = FacewiseBox(3e-8);
  TriangleSoup m = mm;
  for (Vec3& v : m.vertices) v *= 1e-3;
  TriangleSoup far = mm;
  for (Vec3& v : far.vertices) v += Vec3::Constant(1e6);
  const RepairReport a = Repair(mm), b = Repair(m), c = Repair(far);
  EXPECT_EQ(a.merged_vertices, b.merged_vertices);
  EXPECT_TRUE(a.watertight() && b.watertight() && c.watertight()) << c.Describe();
  // Cracks at a fifth and at 3.5 times the weld tolerance (1e-7 of the 37.4 mm diagonal),
  // in mm, in m and far from the origin: welded, and reported, in all three. No absolute
  // tolerance can do both in mm and in m, a thousand times apart.
  for (const auto& [nudge, welds] : {std::pair{3e-7, true}, std::pair{5e-6, false}}) {
    for (const auto& [scale, shift] :
         {std::pair{1.0, 0.0}, std::pair{1e-3, 0.0}, std::pair{1.0, 1e6}}) {
      TriangleSoup soup = FacewiseBox(nudge);
      for (Vec3& v : soup.vertices) v = v * scale + Vec3::Constant(shift);
      const RepairReport r = Repair(soup);
      const std::string where = "nudge " + std::to_string(nudge) + " mm, scale " +
                                std::to_string(scale) + ", shift " + std::to_string(shift);
      EXPECT_EQ(r.watertight(), welds) << where << ": " << r.Describe();
      EXPECT_EQ(r.welded_vertices > 0, welds) << where;
      if (!welds) EXPECT_EQ(r.boundary_edges, 24u) << where;
    }
  }
}

}  // namespace
}  // namespace hapticad
