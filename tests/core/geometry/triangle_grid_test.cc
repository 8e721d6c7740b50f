// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/triangle_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/geometry/segment_triangle.h"
#include "hapticad/core/geometry/triangle_tree.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

std::unique_ptr<TriangleMesh> MeshOf(const TriangleSoup& s) {
  return TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
}

bool FirstHit(const TriangleGrid& grid, const Vec3& a, const Vec3& b, SweepHit* hit) {
  SweepQuery q;
  q.a = a;
  q.b = b;
  return grid.FirstHit(q, hit);
}

// The nearest s over every triangle, or 2 for none: what any first-hit query must find.
double BruteForce(const TriangleMesh& mesh, const Vec3& a, const Vec3& b) {
  double best = 2.0;
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    SegmentTriangleHit h;
    const auto& tri = mesh.triangle(t);
    if (IntersectSegmentTriangle(a, b - a, 1.0, mesh.vertex(tri[0]), mesh.vertex(tri[1]),
                                 mesh.vertex(tri[2]), 1e-9, &h)) {
      best = std::min(best, h.s);
    }
  }
  return best;
}

// Whether the grid finds what checking every triangle finds; true for a hit.
bool AgreesWithBruteForce(const TriangleMesh& mesh, const TriangleGrid& grid, const Vec3& a,
                          const Vec3& b, int i) {
  const double best = BruteForce(mesh, a, b);
  SweepHit hit;
  const bool found = FirstHit(grid, a, b, &hit);
  EXPECT_EQ(found, best <= 1.0) << i;
  if (found) {
    EXPECT_EQ(hit.s, best) << i;
  }
  return found;
}

// Triangles from 1e-3 to 1 across, most of them small, scattered in a 4-unit cube:
// the large ones are filed in coarser levels.
TriangleSoup MakeMixedSoup(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> where(-2.0, 2.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> direction;
  TriangleSoup soup;
  for (int t = 0; t < count; ++t) {
    const Vec3 centre(where(rng), where(rng), where(rng));
    const double size = std::pow(10.0, -3.0 + 3.0 * std::pow(unit(rng), 6));
    for (int k = 0; k < 3; ++k) {
      const Vec3 offset(direction(rng), direction(rng), direction(rng));
      soup.vertices.push_back(centre + size * offset.normalized());
    }
    soup.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    soup.cad_faces.push_back(0);
  }
  return soup;
}

class BoxGrid : public ::testing::Test {
 protected:
  void SetUp() override {
    mesh_ = MeshOf(testing::MakeBoxSoup(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
    grid_ = TriangleGrid::Build(*mesh_, 1e-12);
  }
  std::unique_ptr<TriangleMesh> mesh_;
  std::unique_ptr<TriangleGrid> grid_;
};

TEST_F(BoxGrid, FirstHitIsTheNearestTriangle) {
  SweepHit hit;
  ASSERT_TRUE(FirstHit(*grid_, Vec3(0.2, 0.3, 3), Vec3(0.2, 0.3, -3), &hit));
  EXPECT_EQ(mesh_->cad_face(hit.triangle), 5);  // +z, not -z behind it
  EXPECT_NEAR((hit.point - Vec3(0.2, 0.3, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(hit.s, 2.0 / 6.0, 1e-12);
  EXPECT_NEAR(hit.normal.z(), 1.0, 1e-12);  // facing where the point came from
}

TEST_F(BoxGrid, MissesWhenTheSegmentStopsShortOrPassesBeside) {
  SweepHit hit;
  EXPECT_FALSE(FirstHit(*grid_, Vec3(0, 0, 3), Vec3(0, 0, 1.001), &hit));
  EXPECT_FALSE(FirstHit(*grid_, Vec3(1.5, 0, 3), Vec3(1.5, 0, -3), &hit));
  EXPECT_FALSE(FirstHit(*grid_, Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5), &hit));  // no length
  EXPECT_FALSE(FirstHit(*grid_, Vec3(1e6, 0, 0), Vec3(1e6, 5, 0), &hit));          // far away
}

TEST_F(BoxGrid, ASegmentThroughASharedEdgeStillHits) {
  SweepHit hit;
  ASSERT_TRUE(FirstHit(*grid_, Vec3(0.25, 0.25, 2), Vec3(0.25, 0.25, 0), &hit));
  EXPECT_EQ(mesh_->cad_face(hit.triangle), 5);
}

TEST_F(BoxGrid, ASegmentFromFarAwayIsClippedNotWalked) {
  SweepHit hit;
  ASSERT_TRUE(FirstHit(*grid_, Vec3(0.1, -0.2, 1e9), Vec3(0.1, -0.2, 0), &hit));
  EXPECT_EQ(mesh_->cad_face(hit.triangle), 5);
  EXPECT_NEAR(hit.point.z(), 1.0, 1e-6);
}

TEST_F(BoxGrid, SegmentsAlongCellWallsFindWhatTheTreeFinds) {
  // segments lying exactly in the planes between cells, and through cell corners
  const double h = grid_->cell_size();
  const auto tree = TriangleTree::Build(*mesh_, 1e-12);
  for (int i = -4; i <= 4; ++i) {
    for (int j = -4; j <= 4; ++j) {
      const Vec3 a(i * h, j * h, 3.0);
      const Vec3 b(i * h, j * h, -3.0);
      const Vec3 c(3.0, i * h, j * h);
      const Vec3 e(-3.0, i * h, j * h);
      for (const auto& [p, q] : {std::pair{a, b}, std::pair{c, e}, std::pair{b, a}}) {
        SweepHit from_grid, from_tree;
        SweepQuery query;
        query.a = p;
        query.b = q;
        const bool grid_found = grid_->FirstHit(query, &from_grid);
        ASSERT_EQ(grid_found, tree->FirstHit(query, &from_tree)) << i << ' ' << j;
        if (grid_found) {
          EXPECT_EQ(from_grid.s, from_tree.s) << i << ' ' << j;
        }
      }
    }
  }
}

TEST_F(BoxGrid, FirstHitAndWarmUpDoNotAllocate) {
  SweepHit hit;
  TriangleGrid::Prefetch prefetch;
  FirstHit(*grid_, Vec3(0, 0, 3), Vec3(0, 0, -3), &hit);  // warm
  testing::AllocationCounter counter;
  for (int i = 0; i < 100; ++i) {
    FirstHit(*grid_, Vec3(0.01 * i, 0, 3), Vec3(0, 0.01 * i, -3), &hit);
    grid_->WarmUp(Vec3(0.01 * i, 0.5, 1.0), Vec3(0.01 * i + 0.3, 0.6, 0.9), &prefetch);
  }
  EXPECT_EQ(counter.count(), 0u);
}

// The warm-up loads every cell the stretch ahead enters, in the order it enters them,
// one step a call each, and a cell still ahead keeps its progress.
TEST(TriangleGrid, WarmUpFollowsEveryCellTheStretchAheadEnters) {
  const auto mesh = MeshOf(MakeIcosphere(IcosphereFrequencyFor(20000), 1.0));
  const auto grid = TriangleGrid::Build(*mesh, 1e-9);
  const double h = grid->cell_size();
  // the middle of a cell on the surface, and the cells round it
  const Vec3 c = ((Vec3(0.6, 0.6, 0.52).normalized() / h).array().floor() + 0.5).matrix() * h;
  const auto at = [&](double x, double y, double z) {
    return grid->CellKey(c + h * Vec3(x, y, z));
  };
  constexpr std::uint64_t kNone = ~std::uint64_t{0};
  TriangleGrid::Prefetch state;
  const auto keys = [&state] { return std::vector<std::uint64_t>(state.key, state.key + 4); };
  grid->WarmUp(c, c + Vec3(0.3, 0.2, -0.1) * h, &state);  // stays in the cell
  EXPECT_EQ(keys(), std::vector<std::uint64_t>(4, kNone));
  for (int call = 1; call <= 6; ++call) {  // into the cell at +x: four steps, then done
    grid->WarmUp(c, c + Vec3(0.7, 0.1, 0.0) * h, &state);
    ASSERT_EQ(keys(), (std::vector<std::uint64_t>{at(1, 0, 0), kNone, kNone, kNone}));
    EXPECT_EQ(state.stage[0], std::min(call, 4));
  }
  // +x, then +y (the x boundary comes first): the +x cell keeps its progress
  grid->WarmUp(c, c + Vec3(0.7, 0.6, 0.0) * h, &state);
  EXPECT_EQ(keys(), (std::vector<std::uint64_t>{at(1, 0, 0), at(1, 1, 0), kNone, kNone}));
  EXPECT_EQ(state.stage[0], 4);
  EXPECT_EQ(state.stage[1], 1);
  // +y first, then the diagonal cell: the +x cell is no longer on the way
  grid->WarmUp(c, c + Vec3(0.6, 0.7, 0.0) * h, &state);
  EXPECT_EQ(keys(), (std::vector<std::uint64_t>{at(0, 1, 0), at(1, 1, 0), kNone, kNone}));
  EXPECT_EQ(state.stage[0], 1);
  EXPECT_EQ(state.stage[1], 2);
  // backwards, and through a corner region: x, then -y, then z
  grid->WarmUp(c, c + Vec3(-0.7, 0.1, 0.0) * h, &state);
  EXPECT_EQ(keys(), (std::vector<std::uint64_t>{at(-1, 0, 0), kNone, kNone, kNone}));
  grid->WarmUp(c, c + Vec3(0.7, -0.6, 0.55) * h, &state);
  EXPECT_EQ(keys(), (std::vector<std::uint64_t>{at(1, 0, 0), at(1, -1, 0), at(1, -1, 1), kNone}));
  // a stretch that misses the grid's box, or is not a number: the state stays
  const std::vector<std::uint64_t> before = keys();
  grid->WarmUp(Vec3(5.0, 0.0, 0.0), Vec3(5.0, 0.5, 0.0), &state);
  grid->WarmUp(c, Vec3(std::nan(""), 0.0, 0.0), &state);
  EXPECT_EQ(keys(), before);
}

TEST_F(BoxGrid, WarmUpFromOutsideWarmsTheCellWhereTheProxyWillLand) {
  // coming down onto the top face z = 1 from above the grid's box
  const double h = grid_->cell_size();
  TriangleGrid::Prefetch state;
  grid_->WarmUp(Vec3(0.2, 0.3, 1.0 + 0.3 * h), Vec3(0.2, 0.3, 1.0 - 0.45 * h), &state);
  const std::uint64_t landing = grid_->CellKey(Vec3(0.2, 0.3, 1.0));
  EXPECT_EQ(state.key[0], landing);
  EXPECT_EQ(state.stage[0], 1);
  // and the cell below it, if the stretch reaches it
  const std::uint64_t below = grid_->CellKey(Vec3(0.2, 0.3, 1.0 - 0.45 * h));
  EXPECT_EQ(state.key[1], below == landing ? ~std::uint64_t{0} : below);
}

TEST(TriangleGrid, RandomSegmentsOnAnIcosphereAgreeWithBruteForce) {
  const auto mesh = MeshOf(MakeIcosphere(IcosphereFrequencyFor(5000), 1.0));
  const auto grid = TriangleGrid::Build(*mesh, 1e-9);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::uniform_real_distribution<double> short_step(-0.05, 0.05);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    // long segments across the sphere, and short ones like a proxy's tick
    const Vec3 b =
        i % 2 == 0 ? Vec3(u(rng), u(rng), u(rng))
                   : Vec3(a.normalized() + Vec3(short_step(rng), short_step(rng), short_step(rng)));
    AgreesWithBruteForce(*mesh, *grid, a, b, i);
  }
}

TEST(TriangleGrid, TrianglesOfEverySizeAreFiledInSeveralLevelsAndAllFound) {
  const auto mesh = MeshOf(MakeMixedSoup(600, 3));
  const auto grid = TriangleGrid::Build(*mesh, 1e-9);
  int levels = 0;
  for (std::uint32_t mask = grid->occupied_levels(); mask != 0; mask &= mask - 1) ++levels;
  EXPECT_GE(levels, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    const Vec3 b(u(rng), u(rng), u(rng));
    if (AgreesWithBruteForce(*mesh, *grid, a, b, i)) ++hits;
  }
  EXPECT_GT(hits, 300);  // the segments do meet triangles, small and large
}

TEST(TriangleGrid, FloorsAndHintsGiveTheTreesAnswer) {
  const auto mesh = MeshOf(MakeIcosphere(IcosphereFrequencyFor(20000), 1.0));
  const auto grid = TriangleGrid::Build(*mesh, 1e-9);
  const auto tree = TriangleTree::Build(*mesh, 1e-9);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    // a proxy on the surface pressed inward, with a floor under a tangent plane
    const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
    SweepFloors floors;
    floors.count = 1;
    floors.normal[0] = n;
    floors.offset[0] = 1.0 - 0.01;
    SweepQuery q;
    q.a = 1.0001 * n;
    q.b = 0.97 * n + 0.02 * Vec3(u(rng), u(rng), u(rng));
    q.floors = i % 2 == 0 ? &floors : nullptr;
    q.hint = i % 3 == 0 ? static_cast<std::int64_t>(i % mesh->num_triangles()) : -1;
    SweepHit from_grid, from_tree;
    const bool found = grid->FirstHit(q, &from_grid);
    ASSERT_EQ(found, tree->FirstHit(q, &from_tree)) << i;
    if (found) {
      EXPECT_EQ(from_grid.s, from_tree.s) << i;
      EXPECT_EQ(from_grid.normal, from_tree.normal) << i;
    }
  }
}

// Small triangles scattered in a cube of side `size` around `centre`, added to `soup`.
void AddCluster(const Vec3& centre, double size, double triangle, int count, unsigned seed,
                TriangleSoup* soup) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5 * size, 0.5 * size);
  for (int t = 0; t < count; ++t) {
    const Vec3 p = centre + Vec3(u(rng), u(rng), u(rng));
    const int first = static_cast<int>(soup->vertices.size());
    soup->vertices.insert(soup->vertices.end(),
                          {p, p + Vec3(triangle, 0, 0), p + Vec3(0, triangle, triangle)});
    soup->triangles.push_back({first, first + 1, first + 2});
    soup->cad_faces.push_back(0);
  }
}

TEST(TriangleGrid, AFreeSweepEndsWhereItLeavesTheModelHoweverFarItsGoal) {
  // two clusters at opposite corners of a 2-unit box; sweeps from the middle, touching
  // nothing, toward goals from 1 to 1e12 units away: the walk stops at the box's side
  TriangleSoup soup;
  AddCluster(Vec3(-0.95, -0.95, -0.95), 0.1, 1e-3, 2000, 1, &soup);
  AddCluster(Vec3(0.95, 0.95, 0.95), 0.1, 1e-3, 2000, 2, &soup);
  const auto mesh = MeshOf(soup);
  const auto grid = TriangleGrid::Build(*mesh, 1e-9);
  const Vec3 a(0.0, 0.0, 0.001234);
  const Vec3 direction = Vec3(1.0, 0.01, 0.002).normalized();
  std::size_t across = 0;  // the cells from a to the box's side
  SweepHit unused;
  ASSERT_FALSE(grid->FirstHit({a, a + 2.0 * direction}, &unused, &across));
  EXPECT_LE(across, static_cast<std::size_t>(3.0 * 1.1 / grid->cell_size()));
  for (const double far : {1e3, 1e6, 1e12}) {
    std::size_t cells = 0;
    SweepHit hit;
    SweepQuery query;
    query.a = a;
    query.b = a + far * direction;
    EXPECT_FALSE(grid->FirstHit(query, &hit, &cells)) << far;
    ASSERT_LE(cells, across + 2) << far;
    // and from far outside, across the box
    cells = 0;
    query.a = a - far * direction;
    EXPECT_FALSE(grid->FirstHit(query, &hit, &cells)) << far;
    ASSERT_LE(cells, 2 * across + 4) << far;
  }
}

TEST(TriangleGrid, ASweepPastAClusterOfTinyTrianglesDoesNotWalkItsFineCells) {
  // one large face and a cluster of triangles 1e-5 across: level 0's cells are tiny, but
  // only where the cluster is; a sweep across the box elsewhere looks up a few cells
  TriangleSoup soup;
  soup.vertices = {Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(-1, 1, -1)};
  soup.triangles = {{0, 1, 2}};
  soup.cad_faces = {0};
  AddCluster(Vec3(0, 0, 1), 0.02, 1e-5, 3000, 3, &soup);
  const auto mesh = MeshOf(soup);
  const auto grid = TriangleGrid::Build(*mesh, 1e-9);
  ASSERT_GT(grid->occupied_levels(), 1u);
  const Vec3 a(-0.99, -0.99, -0.5);
  const Vec3 b(0.99, 0.99, 0.5);
  ASSERT_GT((b - a).lpNorm<1>() / grid->cell_size(), 1e5);  // what walking level 0 would cost
  std::size_t cells = 0;
  SweepHit hit;
  EXPECT_FALSE(grid->FirstHit({a, b}, &hit, &cells));
  EXPECT_LT(cells, 100u);
  // the cluster and the face are still found
  EXPECT_TRUE(AgreesWithBruteForce(*mesh, *grid, Vec3(-0.5, -0.5, 0), Vec3(-0.5, -0.5, -2), 0));
  for (int i = 0; i < 200; ++i) {
    const Vec3 through = soup.vertices[3 + 3 * i] + Vec3(2e-6, 2e-6, 0);
    AgreesWithBruteForce(*mesh, *grid, through + Vec3(0, 0, 0.05), through - Vec3(0, 0, 0.05), i);
  }
}

TEST(TriangleGrid, CellsInARowAlongAnyAxisDoNotCrowdTheirSlots) {
  // a thin rod of triangles along x, y or z: a row of cells along one axis. Every bit of
  // the key must reach the slot, or a row piles onto few slots and look-ups probe long.
  for (int axis = 0; axis < 3; ++axis) {
    TriangleSoup soup;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (int t = 0; t < 20000; ++t) {
      Vec3 p = Vec3::Zero();
      p[axis] = u(rng);
      Vec3 a = p, b = p, c = p;
      a[(axis + 1) % 3] += 1e-4;
      b[(axis + 2) % 3] += 1e-4;
      c[axis] += 1e-4;
      soup.vertices.insert(soup.vertices.end(), {a, b, c});
      soup.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
      soup.cad_faces.push_back(0);
    }
    const auto mesh = MeshOf(soup);
    const auto grid = TriangleGrid::Build(*mesh, 1e-9);
    EXPECT_LT(grid->CalcMeanProbeLength(), 1.5) << "axis " << axis;
  }
}

TEST(TriangleGrid, APadThatIsNotAPositiveNumberIsRefused) {
  const auto mesh = MeshOf(testing::MakeBoxSoup(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
  for (const double pad : {0.0, -1e-9, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(TriangleGrid::Build(*mesh, pad), std::invalid_argument) << pad;
  }
}

TEST(TriangleGrid, OneTriangleAndDegenerateOnes) {
  TriangleSoup soup;
  soup.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0),           Vec3(0, 1, 0),
                   Vec3(2, 2, 2), Vec3(2, 2, 2.0 + 1e-12), Vec3(2, 2, 2.0 + 2e-12)};
  soup.triangles = {{0, 1, 2}, {3, 4, 5}};  // the second has no area
  soup.cad_faces = {0, 1};
  const auto mesh = MeshOf(soup);
  const auto grid = TriangleGrid::Build(*mesh, 1e-12);
  SweepHit hit;
  ASSERT_TRUE(FirstHit(*grid, Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -1), &hit));
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_FALSE(FirstHit(*grid, Vec3(2, 2, 3), Vec3(2, 2, 1), &hit));
  EXPECT_GT(grid->CalcMemoryBytes(), 0u);
}

}  // namespace
}  // namespace hapticad
