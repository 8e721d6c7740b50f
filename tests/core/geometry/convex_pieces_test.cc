// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/convex_pieces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hapticad/core/geometry/icosphere.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

constexpr double kTolerance = 1e-13;

std::unique_ptr<TriangleMesh> MeshOf(const TriangleSoup& s) {
  return TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
}

TriangleSoup Join(const TriangleSoup& a, const TriangleSoup& b) {
  TriangleSoup out = a;
  const auto base = static_cast<std::int32_t>(a.vertices.size());
  out.vertices.insert(out.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles)
    out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  out.cad_faces.insert(out.cad_faces.end(), b.cad_faces.begin(), b.cad_faces.end());
  return out;
}

// A cone over a pentagram, closed by a fan from the centre of its base: every edge is
// convex or flat, the Euler characteristic is 2, but the triangles wrap twice round the
// apex and round the centre. It bounds no convex solid.
TriangleSoup MakePentagramCone() {
  TriangleSoup soup;
  soup.vertices.push_back(Vec3(0, 0, 1));  // apex
  soup.vertices.push_back(Vec3(0, 0, 0));  // centre of the base
  for (int i = 0; i < 5; ++i) {
    const double a = i * 4.0 * M_PI / 5.0;  // every second corner of a pentagon
    soup.vertices.push_back(Vec3(std::cos(a), std::sin(a), 0));
  }
  for (int i = 0; i < 5; ++i) {
    const int p = 2 + i, q = 2 + (i + 1) % 5;
    soup.triangles.push_back({0, p, q});
    soup.triangles.push_back({1, q, p});
    soup.cad_faces.push_back(0);
    soup.cad_faces.push_back(1);
  }
  return soup;
}

// Box [lo, hi] with every face a grid of n x n squares, each split in two (the grid's
// vertices shared between faces), outward winding: flat faces with vertices inside them.
TriangleSoup MakeGridBox(const Vec3& lo, const Vec3& hi, int n) {
  TriangleSoup soup;
  std::map<std::array<int, 3>, std::int32_t> index;
  const auto vertex = [&](std::array<int, 3> c) {
    const auto found = index.find(c);
    if (found != index.end()) return found->second;
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = c[k] == n ? hi[k] : lo[k] + (hi[k] - lo[k]) * c[k] / n;
    soup.vertices.push_back(p);
    return index[c] = static_cast<std::int32_t>(soup.vertices.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto at = [&](int i, int j) {
        std::array<int, 3> c{};
        c[axis] = side * n;
        c[u] = i;
        c[v] = j;
        return vertex(c);
      };
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          std::array<std::int32_t, 3> quad[2] = {{at(i, j), at(i + 1, j), at(i + 1, j + 1)},
                                                 {at(i, j), at(i + 1, j + 1), at(i, j + 1)}};
          for (auto& t : quad) {
            if (side == 0) std::swap(t[1], t[2]);
            soup.triangles.push_back(t);
            soup.cad_faces.push_back(2 * axis + side);
          }
        }
      }
    }
  }
  return soup;
}

// A prism over the convex polygon `base` (counter-clockwise seen from +z), height h.
TriangleSoup MakePrism(const std::vector<Vec3>& base, double h) {
  TriangleSoup soup;
  const int n = static_cast<int>(base.size());
  for (const Vec3& p : base) soup.vertices.push_back(p);
  for (const Vec3& p : base) soup.vertices.push_back(p + Vec3(0, 0, h));
  for (int i = 1; i + 1 < n; ++i) {
    soup.triangles.push_back({0, i + 1, i});
    soup.triangles.push_back({n, n + i, n + i + 1});
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    soup.triangles.push_back({i, j, n + j});
    soup.triangles.push_back({i, n + j, n + i});
  }
  soup.cad_faces.assign(soup.triangles.size(), 0);
  return soup;
}

Vec3 Centre(const TriangleMesh& mesh, std::uint32_t t) {
  const auto& tri = mesh.triangle(t);
  return (mesh.vertex(tri[0]) + mesh.vertex(tri[1]) + mesh.vertex(tri[2])) / 3.0;
}

// The triangle of piece `piece` (any, for kNone) whose normal is nearest `direction`.
std::uint32_t Facing(const TriangleMesh& mesh, const ConvexPieces& pieces, const Vec3& direction,
                     std::uint32_t piece = ConvexPieces::kNone) {
  std::uint32_t best = 0;
  double best_dot = -2.0;
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const double dot = mesh.face_normal(t).dot(direction);
    if ((piece == ConvexPieces::kNone || pieces.piece(t) == piece) && dot > best_dot) {
      best = t;
      best_dot = dot;
    }
  }
  return best;
}

// What every triangle tested gives: the answer a settled sweep must equal.
struct Answer {
  bool found = false;
  double s = 0.0;
  Vec3 normal = Vec3::Zero();
  std::uint32_t triangle = 0;
};

Answer Exhaustive(const TriangleMesh& mesh, SweepQuery query) {
  query.hint = -1;
  SweepSearch search(mesh, query);
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) search.Test(t);
  Answer out;
  out.found = search.found();
  out.s = search.best_s();
  out.normal = search.best_normal();
  out.triangle = search.best_triangle();
  return out;
}

// Settles the query if it can; if so, checks the answer against every triangle.
// Returns whether it settled.
bool SettlesRightly(const TriangleMesh& mesh, const ConvexPieces& pieces, const SweepQuery& query,
                    int i) {
  SweepSearch search(mesh, query);
  if (!pieces.Settle(query, &search)) return false;
  const Answer truth = Exhaustive(mesh, query);
  EXPECT_EQ(search.found(), truth.found) << i;
  if (search.found() && truth.found) {
    // the same contact; on a shared edge or vertex another triangle may report it
    const double length = (query.b - query.a).norm();
    EXPECT_NEAR(search.best_s() * length, truth.s * length, 1e-12) << i;
    if (search.best_triangle() != truth.triangle) {
      SweepQuery alone = query;
      alone.hint = search.best_triangle();
      SweepSearch only(mesh, alone);
      EXPECT_TRUE(only.found()) << i;
      EXPECT_NEAR(only.best_s() * length, truth.s * length, 1e-12) << i;
    } else {
      EXPECT_LT((search.best_normal() - truth.normal).norm(), 1e-9) << i;
    }
  }
  return true;
}

// Proxy-like sweeps over a convex piece: from just off a random triangle (or a little
// further, or a little inside), toward a goal a short or a long way off, mostly into
// the solid; half of them along the triangle's plane with its floor, as a proxy slides
// after a contact. Returns the share settled.
double FuzzSettle(const TriangleMesh& mesh, const ConvexPieces& pieces, double radius, double size,
                  unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  const double offset = 1e-9 * size;
  int settled = 0;
  for (int i = 0; i < count; ++i) {
    const auto t = static_cast<std::uint32_t>(unit(rng) * mesh.num_triangles());
    const auto& tri = mesh.triangle(t);
    double u = unit(rng), v = unit(rng);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    const Vec3 on =
        (1 - u - v) * mesh.vertex(tri[0]) + u * mesh.vertex(tri[1]) + v * mesh.vertex(tri[2]);
    const Vec3& n = mesh.face_normal(t);
    const double edge = (mesh.vertex(tri[1]) - mesh.vertex(tri[0])).norm();
    const Vec3 jitter(gauss(rng), gauss(rng), gauss(rng));
    Vec3 a = on + (radius + offset) * n;
    const int kind = i % 6;
    if (kind == 4) a += 2.0 * edge * unit(rng) * n;  // above it
    if (kind == 5) a -= 0.3 * edge * unit(rng) * n;  // a little inside
    SweepQuery q;
    q.radius = radius;
    q.hint = t;
    q.a = a;
    SweepFloors floors;
    // a slide at rest height along the plane across m through `through`, with its floor
    const auto slide = [&](const Vec3& m, const Vec3& through) {
      q.a = through + (radius + offset) * m;
      const Vec3 along = (jitter - jitter.dot(m) * m).normalized();
      q.b = q.a + edge * (0.1 + 2.0 * unit(rng)) * along;
      floors.count = 1;
      floors.normal[0] = m;
      floors.offset[0] = m.dot(through) + 0.5 * offset;
      q.floors = &floors;
    };
    if (kind == 0) {
      slide(n, on);  // along the triangle's plane
    } else if (kind == 1) {
      // a slide along an edge's plane (the mean of its triangles' normals), at rest height
      // over the edge, with its floor: the triangle's own plane does not clear it
      const std::uint32_t p = tri[0], r = tri[1];
      Vec3 m = n;
      for (std::uint32_t o = 0; o < mesh.num_triangles(); ++o) {
        const auto& other = mesh.triangle(o);
        const bool has_p = other[0] == p || other[1] == p || other[2] == p;
        const bool has_r = other[0] == r || other[1] == r || other[2] == r;
        if (o != t && has_p && has_r) m = (n + mesh.face_normal(o)).normalized();
      }
      slide(m, 0.5 * (mesh.vertex(p) + mesh.vertex(r)));
    } else {
      // toward a goal pressed into the solid, a short or a long way across
      const double reach = edge * std::pow(10.0, -2.0 + 2.5 * unit(rng));
      q.b = a + reach * jitter.normalized() - (radius + size * 0.02 * unit(rng)) * n;
    }
    if (SettlesRightly(mesh, pieces, q, i)) ++settled;
  }
  return static_cast<double>(settled) / count;
}

// Solids with sharp vertices whose planes do not all lean toward the sum of their
// normals: the corner cut off a cube (at (1, 0, 0) the slanted face's normal is 100
// degrees from the sum), and a square pyramid whose apex leans far past its base.
TriangleSoup CornerTetrahedron() {
  TriangleSoup s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  s.cad_faces = {0, 1, 2, 3};
  return s;
}

TriangleSoup LeaningPyramid() {
  TriangleSoup s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(4, 0.5, 0.3)};
  s.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  s.cad_faces = {0, 0, 1, 2, 3, 4};
  return s;
}

TEST(ConvexPieces, AClosedConvexSurfaceIsOnePieceWithRoomAllRound) {
  for (const TriangleSoup& soup :
       {MakeIcosphere(4, 1.0), testing::MakeBoxSoup(Vec3(-1, -2, -3), Vec3(1, 2, 3)),
        testing::MakeBoxSoup(Vec3(-5, -5, 0), Vec3(5, 5, 1e-5))}) {
    const auto mesh = MeshOf(soup);
    const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
    ASSERT_EQ(pieces->num_pieces(), 1u);
    for (std::uint32_t t = 0; t < mesh->num_triangles(); ++t) EXPECT_EQ(pieces->piece(t), 0u);
    EXPECT_TRUE((pieces->clear_lo(0).array() == -INFINITY).all());
    EXPECT_TRUE((pieces->clear_hi(0).array() == INFINITY).all());
  }
}

TEST(ConvexPieces, SurfacesThatBoundNoConvexSolidAreNoPiece) {
  TriangleSoup dented = MakeIcosphere(4, 1.0);
  dented.vertices[5] *= 0.9;  // a dimple: the edges round it turn concave
  TriangleSoup open = MakeIcosphere(4, 1.0);
  open.triangles.pop_back();  // a hole
  open.cad_faces.pop_back();
  TriangleSoup inside_out = testing::MakeBoxSoup(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  TriangleSoup flat = testing::MakeBoxSoup(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  flat.vertices[7] = flat.vertices[6];  // two triangles of the top collapse to lines
  flat.vertices[7].x() += 1e-300;
  for (const TriangleSoup* soup : {&dented, &open, &inside_out, &flat}) {
    const auto mesh = MeshOf(*soup);
    const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
    EXPECT_EQ(pieces->num_pieces(), 0u);
    for (std::uint32_t t = 0; t < mesh->num_triangles(); ++t) {
      EXPECT_EQ(pieces->piece(t), ConvexPieces::kNone);
    }
    EXPECT_EQ(pieces->CalcMemoryBytes(), 0u);  // keeps nothing it cannot use
    SweepQuery q;
    q.hint = 0;
    q.a = Vec3(0, 0, 2);
    q.b = Vec3(0, 0, 0.5);
    SweepSearch search(*mesh, q);
    EXPECT_FALSE(pieces->Settle(q, &search));
    for (int step = 0; step < ConvexPieces::kWarmUpSteps; ++step) {
      EXPECT_FALSE(pieces->WarmUp(0, step));
    }
  }
}

TEST(ConvexPieces, ASurfaceWrappingTwiceRoundAVertexIsNoPiece) {
  const auto mesh = MeshOf(MakePentagramCone());
  ASSERT_TRUE(mesh->closed());
  // every edge convex or flat, as a convex solid's would be
  const auto loose = ConvexPieces::Build(*mesh, 1e-9);
  EXPECT_EQ(loose->num_pieces(), 0u);
  EXPECT_EQ(loose->piece(0), ConvexPieces::kNone);
}

TEST(ConvexPieces, ConvexSolidsWithSharpEdgesAndVerticesAreOnePiece) {
  // a regular tetrahedron, and prisms with edges from 90 down to 10 degrees (their
  // square sides split in two: a face counted once per triangle would tip the vertex's
  // mean normal off the sharp faces)
  TriangleSoup tetrahedron;
  tetrahedron.vertices = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  tetrahedron.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  tetrahedron.cad_faces = {0, 0, 0, 0};
  std::vector<TriangleSoup> solids = {tetrahedron, MakeGridBox(Vec3(0, 0, 0), Vec3(1, 2, 3), 3),
                                      CornerTetrahedron(), LeaningPyramid()};
  for (const double degrees : {90.0, 60.0, 30.0, 10.0}) {
    const double a = degrees * M_PI / 180.0;
    solids.push_back(
        MakePrism({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(std::cos(a), std::sin(a), 0)}, 1));
  }
  for (const TriangleSoup& soup : solids) {
    const auto mesh = MeshOf(soup);
    EXPECT_EQ(ConvexPieces::Build(*mesh, kTolerance)->num_pieces(), 1u) << mesh->num_triangles();
  }
}

TEST(ConvexPieces, AToleranceThatIsNotAFiniteNonNegativeNumberIsRefused) {
  const auto mesh = MeshOf(MakeIcosphere(2, 1.0));
  EXPECT_THROW(ConvexPieces::Build(*mesh, -1.0), std::invalid_argument);
  EXPECT_THROW(ConvexPieces::Build(*mesh, NAN), std::invalid_argument);
  EXPECT_THROW(ConvexPieces::Build(*mesh, INFINITY), std::invalid_argument);
}

TEST(ConvexPieces, SettledSweepsOfAPointAreTheFirstContact) {
  const auto sphere = MeshOf(MakeIcosphere(12, 1.0));
  const auto box = MeshOf(testing::MakeBoxSoup(Vec3(-1, -2, -3), Vec3(1, 2, 3)));
  const auto plate = MeshOf(testing::MakeBoxSoup(Vec3(-5, -5, 0), Vec3(5, 5, 1e-5)));
  for (const TriangleMesh* mesh : {sphere.get(), box.get(), plate.get()}) {
    const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
    const double share = FuzzSettle(*mesh, *pieces, 0.0, 10.0, 7, 3000);
    EXPECT_GT(share, 0.8);  // and it does settle most of them
  }
}

TEST(ConvexPieces, SettledSweepsOfASphereAreTheFirstContact) {
  const auto sphere = MeshOf(MakeIcosphere(12, 1.0));
  const auto box = MeshOf(testing::MakeBoxSoup(Vec3(-1, -2, -3), Vec3(1, 2, 3)));
  for (const TriangleMesh* mesh : {sphere.get(), box.get()}) {
    const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
    for (const double radius : {0.01, 0.1, 0.5}) {
      const double share = FuzzSettle(*mesh, *pieces, radius, 6.0, 11, 2000);
      EXPECT_GT(share, 0.7) << radius;
    }
  }
}

TEST(ConvexPieces, SettledSweepsOnSharpLeaningVerticesAreTheFirstContact) {
  for (const TriangleSoup& soup : {CornerTetrahedron(), LeaningPyramid()}) {
    const auto mesh = MeshOf(soup);
    const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
    ASSERT_EQ(pieces->num_pieces(), 1u);
    for (const double radius : {0.0, 0.01, 0.1}) {
      const double share = FuzzSettle(*mesh, *pieces, radius, 4.0, 13, 2000);
      EXPECT_GT(share, 0.5) << radius;
    }
  }
}

TEST(ConvexPieces, PiecesApartHaveTheRoomBetweenTheirBoxes) {
  const auto mesh =
      MeshOf(Join(MakeIcosphere(6, 1.0, Vec3(-3, 0, 0)), MakeIcosphere(6, 1.0, Vec3(3, 0, 0))));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  ASSERT_EQ(pieces->num_pieces(), 2u);
  // boxes [-4, -2] and [2, 4] along x: each has all the room but the other's side
  EXPECT_NEAR(pieces->clear_hi(0).x(), 2.0, 1e-12);
  EXPECT_NEAR(pieces->clear_lo(1).x(), -2.0, 1e-12);
  EXPECT_EQ(pieces->clear_lo(0).x(), -INFINITY);
  EXPECT_EQ(pieces->clear_hi(1).x(), INFINITY);
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(pieces->clear_lo(0)[k], -INFINITY);
    EXPECT_EQ(pieces->clear_hi(0)[k], INFINITY);
  }
  // a sweep from the left sphere's top: settled while it stays in the room, not when it
  // reaches toward the right sphere (the box it would enter is the other piece's)
  SweepQuery q;
  q.hint = Facing(*mesh, *pieces, Vec3(0, 0, 1), 0);
  q.a = Vec3(-3, 0, 1.01);
  q.b = Vec3(-3, 0, 0.9);
  EXPECT_TRUE(SettlesRightly(*mesh, *pieces, q, 0));
  q.b = Vec3(2.5, 0, 0.9);
  SweepSearch search(*mesh, q);
  EXPECT_FALSE(pieces->Settle(q, &search));
  // and a sphere whose radius reaches past the room is not settled either
  q.b = Vec3(-3, 0, 0.9);
  q.radius = 4.9;
  SweepSearch fat(*mesh, q);
  EXPECT_FALSE(pieces->Settle(q, &fat));
}

// More pieces than ConvexPieces compares all against all: small balls strewn at random
// (their boxes apart), and a rod beside them along the axis they spread along most,
// long enough to be compared with every piece.
TEST(ConvexPieces, ManyPiecesEachHaveARoomClearOfEveryOtherBox) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(0.0, 60.0), yz(0.0, 20.0);
  TriangleSoup soup = testing::MakeBoxSoup(Vec3(-1, -3, -1), Vec3(61, -2, 1));
  std::vector<Vec3> centres;
  while (centres.size() < 1200) {
    const Vec3 c(x(rng), yz(rng), yz(rng));
    bool apart = true;  // boxes of half-side 0.4 (and a hair) overlap nowhere
    for (const Vec3& o : centres) apart = apart && ((c - o).cwiseAbs().array() > 0.81).any();
    if (!apart) continue;
    centres.push_back(c);
    soup = Join(soup, MakeIcosphere(1, 0.4, c));
  }
  const auto mesh = MeshOf(soup);
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  ASSERT_EQ(pieces->num_pieces(), 1201u);
  std::vector<Vec3> lo(1201, Vec3::Constant(INFINITY)), hi(1201, Vec3::Constant(-INFINITY));
  for (std::uint32_t t = 0; t < mesh->num_triangles(); ++t) {
    const std::uint32_t p = pieces->piece(t);
    ASSERT_LT(p, 1201u);
    for (const std::uint32_t v : mesh->triangle(t)) {
      lo[p] = lo[p].cwiseMin(mesh->vertex(v));
      hi[p] = hi[p].cwiseMax(mesh->vertex(v));
    }
  }
  int cut_short = 0;  // rooms that reach less than 0.1 beyond their piece on some side
  for (std::uint32_t p = 0; p < 1201; ++p) {
    const Vec3& room_lo = pieces->clear_lo(p);
    const Vec3& room_hi = pieces->clear_hi(p);
    ASSERT_TRUE((room_lo.array() < lo[p].array()).all() && (hi[p].array() < room_hi.array()).all())
        << "piece " << p << " is not inside its own room";
    cut_short += ((lo[p] - room_lo).minCoeff() < 0.1 || (room_hi - hi[p]).minCoeff() < 0.1);
    for (std::uint32_t q = 0; q < 1201; ++q) {
      if (q == p) continue;
      const bool clear =
          (lo[q].array() >= room_hi.array()).any() || (hi[q].array() <= room_lo.array()).any();
      ASSERT_TRUE(clear) << "piece " << q << "'s box is in piece " << p << "'s room";
    }
  }
  EXPECT_LT(cut_short, 120);  // the slabs leave most rooms some room
  // and sweeps settled there are the first contact (against every triangle)
  EXPECT_GT(FuzzSettle(*mesh, *pieces, 0.0, 60.0, 17, 300), 0.5);
  EXPECT_GT(FuzzSettle(*mesh, *pieces, 0.05, 60.0, 19, 300), 0.5);
}

TEST(ConvexPieces, ASmallPieceInsideABigOnesBoxIsNeverMissed) {
  // a pebble beside a ball, inside the ball's box: the ball has no room to settle in
  const auto mesh = MeshOf(Join(MakeIcosphere(10, 1.0), MakeIcosphere(3, 0.05, Vec3(0.8, 0.8, 0))));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  ASSERT_EQ(pieces->num_pieces(), 2u);
  // from just off the ball, straight out through the pebble
  const Vec3 out = Vec3(1, 1, 0).normalized();
  SweepQuery q;
  q.hint = Facing(*mesh, *pieces, out, pieces->piece(0));  // the ball's triangle facing it
  q.a = 1.001 * out;
  q.b = 1.3 * out;
  SweepSearch search(*mesh, q);
  EXPECT_FALSE(pieces->Settle(q, &search));
  EXPECT_TRUE(Exhaustive(*mesh, q).found);  // (the pebble is there)
}

TEST(ConvexPieces, AFloorThatCutsTheSolidProvesNothing) {
  // a sweep across the ball's upper half, above the plane z = 0: it stays clear of that
  // floor, yet it goes through the ball
  const auto mesh = MeshOf(MakeIcosphere(10, 1.0));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  const std::uint32_t top = Facing(*mesh, *pieces, Vec3(0, 0, 1));
  SweepFloors floors;
  floors.count = 1;
  floors.normal[0] = Vec3(0, 0, 1);
  floors.offset[0] = 0.0;
  SweepQuery q;
  q.hint = top;
  q.a = Vec3(-2, 0, 0.5);
  q.b = Vec3(2, 0, 0.5);
  q.floors = &floors;
  SweepSearch search(*mesh, q);
  const bool settled = pieces->Settle(q, &search);
  EXPECT_TRUE(!settled || search.found());
  EXPECT_TRUE(Exhaustive(*mesh, q).found);
}

TEST(ConvexPieces, AFloorUnderTheFarSideOfTheSolidProvesNothing) {
  // The floor z >= 1 lies under the bottom of the box, yet every vertex of the top face
  // ties with its neighbours along -z: a climb from the top face's centre stops there.
  // A sweep well away from that floor, across the box's middle, goes through the side.
  const auto mesh = MeshOf(MakeGridBox(Vec3(-1, -1, -1), Vec3(1, 1, 1), 2));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  ASSERT_EQ(pieces->num_pieces(), 1u);
  SweepFloors floors;
  floors.count = 1;
  floors.normal[0] = Vec3(0, 0, -1);
  floors.offset[0] = -1.0;  // the half-space z >= 1
  int tried = 0;
  for (std::uint32_t t = 0; t < mesh->num_triangles(); ++t) {
    // a hint on the top face, whose first corner is the face's centre
    if (mesh->face_normal(t).z() < 0.5 || mesh->vertex(mesh->triangle(t)[0]) != Vec3(0, 0, 1)) {
      continue;
    }
    ++tried;
    for (const double radius : {0.0, 0.1}) {
      SweepQuery q;
      q.hint = t;
      q.radius = radius;
      q.floors = &floors;
      q.a = Vec3(1.5, 0.3, 0);
      q.b = Vec3(0.5, 0.3, 0);
      SweepSearch search(*mesh, q);
      const bool settled = pieces->Settle(q, &search);
      EXPECT_TRUE(!settled || search.found()) << t << " radius " << radius;
      EXPECT_TRUE(Exhaustive(*mesh, q).found);
    }
  }
  EXPECT_GT(tried, 0);
}

TEST(ConvexPieces, ASphereGrazingAnEdgeAtExactlyItsRadiusIsNotClear) {
  // sliding exactly its radius above the top face and on over the edge x = 1: the
  // exhaustive test touches the edge (with no depth); Settle must not call it clear
  const auto mesh = MeshOf(testing::MakeBoxSoup(Vec3(-1, -2, -3), Vec3(1, 2, 3)));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  SweepQuery q;
  q.hint = Facing(*mesh, *pieces, Vec3(0, 0, 1));
  q.radius = 0.25;
  q.a = Vec3(0.5, 0.1, 3.25);
  q.b = Vec3(1.5, 0.1, 3.25);
  ASSERT_TRUE(Exhaustive(*mesh, q).found);
  SweepSearch search(*mesh, q);
  EXPECT_TRUE(!pieces->Settle(q, &search) || search.found());
}

TEST(ConvexPieces, PiecesWhoseBoxesOverlapSettleOnlyOutsideTheOthersBox) {
  // two balls apart, but their boxes overlap (side by side on a diagonal): each has room
  // up to the other's box along x, and sweeps there are settled rightly
  const auto mesh = MeshOf(Join(MakeIcosphere(6, 1.0), MakeIcosphere(6, 1.0, Vec3(1.5, 1.5, 0))));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  ASSERT_EQ(pieces->num_pieces(), 2u);
  EXPECT_NEAR(pieces->clear_hi(0).x(), 0.5, 1e-12);
  EXPECT_NEAR(pieces->clear_lo(1).x(), 1.0, 1e-12);
  int settled = 0, beyond = 0;
  for (std::uint32_t t = 0; t < mesh->num_triangles(); t += 3) {
    const Vec3 c = Centre(*mesh, t);
    for (const double radius : {0.0, 0.05}) {
      SweepQuery q;
      q.hint = t;
      q.radius = radius;
      q.a = c + (radius + 1e-3) * mesh->face_normal(t);
      q.b = c - 1e-2 * mesh->face_normal(t) + 0.05 * mesh->face_normal(t).cross(Vec3(0, 0, 1));
      const bool in_room =
          (q.a.cwiseMax(q.b).array() + radius < pieces->clear_hi(pieces->piece(t)).array()).all() &&
          (q.a.cwiseMin(q.b).array() - radius > pieces->clear_lo(pieces->piece(t)).array()).all();
      if (SettlesRightly(*mesh, *pieces, q, static_cast<int>(t))) {
        ++settled;
        beyond += !in_room;
      }
    }
  }
  EXPECT_GT(settled, 100);
  EXPECT_EQ(beyond, 0);
}

TEST(ConvexPieces, ASweepFromInsideTheSolidIsLeftToTheWalk) {
  const auto mesh = MeshOf(MakeIcosphere(8, 1.0));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  int settled = 0;
  for (std::uint32_t t = 0; t < mesh->num_triangles(); t += 5) {
    const Vec3 c = Centre(*mesh, t);
    for (const double radius : {0.0, 0.05}) {
      SweepQuery q;
      q.hint = t;
      q.radius = radius;
      q.a = c - (radius + 1e-3) * mesh->face_normal(t);  // inside, under t
      q.b = c + 0.1 * mesh->face_normal(t);              // out through t
      SweepSearch search(*mesh, q);
      if (pieces->Settle(q, &search)) ++settled;
    }
  }
  EXPECT_EQ(settled, 0);
}

TEST(ConvexPieces, AHintOffThePiecesOrOutOfRangeSettlesNothing) {
  const auto mesh = MeshOf(Join(MakeIcosphere(4, 1.0), testing::MakeSheetSoup(1.0, 3.0)));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  ASSERT_EQ(pieces->num_pieces(), 1u);
  const auto sheet = static_cast<std::uint32_t>(mesh->num_triangles() - 1);
  EXPECT_EQ(pieces->piece(sheet), ConvexPieces::kNone);
  for (const std::int64_t hint :
       {std::int64_t{-1}, std::int64_t{sheet}, static_cast<std::int64_t>(mesh->num_triangles())}) {
    SweepQuery q;
    q.hint = hint;
    q.a = Vec3(0, 0, 3.1);
    q.b = Vec3(0, 0, 2.9);
    SweepSearch search(*mesh, q);
    EXPECT_FALSE(pieces->Settle(q, &search)) << hint;
  }
}

TEST(ConvexPieces, SettleAndWarmUpAllocateNothing) {
  const auto mesh = MeshOf(MakeIcosphere(10, 1.0));
  const auto pieces = ConvexPieces::Build(*mesh, kTolerance);
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::uint32_t> pick(0, mesh->num_triangles() - 1);
  testing::AllocationCounter counter;
  int settled = 0;
  for (int i = 0; i < 1000; ++i) {
    const std::uint32_t t = pick(rng);
    const Vec3& n = mesh->face_normal(t);
    const Vec3 p = mesh->vertex(mesh->triangle(t)[0]) + 0.05 * n;
    SweepQuery q;
    q.hint = t;
    q.radius = (i % 2) * 0.02;
    q.a = p;
    q.b = p - 0.2 * n + 0.05 * n.cross(Vec3(1, 2, 3)).normalized();
    SweepSearch search(*mesh, q);
    settled += pieces->Settle(q, &search);
    for (int step = 0; step < ConvexPieces::kWarmUpSteps; ++step) {
      EXPECT_TRUE(pieces->WarmUp(t, step));
    }
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(settled, 500);
}

}  // namespace
}  // namespace hapticad
