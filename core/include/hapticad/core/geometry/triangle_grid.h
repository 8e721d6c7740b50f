// SPDX-License-Identifier: GPL-3.0-or-later
// TriangleGrid: hashed uniform grids of triangles, for the point proxy's sweeps.
//
// A sweep of a point proxy is short (the proxy moves a fraction of a millimetre per
// tick, and the last contact, tested first, ends the search within one cell): a grid
// answers it from the one or two cells the segment starts in, in a time that does not
// depend on how many triangles the model has, where a tree walks log2(n) levels from
// its root every time. The tree stays for the sphere proxy and closest points.
//
// Every triangle is filed in one level of cells: level L has cells of side h0 2^L, and a
// triangle goes to the finest level where its box (plus the pad) covers at most 32
// cells: a compact triangle or a sliver along an axis stays in level 0, a large face
// climbs. h0 is a little over twice the 90th percentile of the triangles' widths (the
// height over the longest edge), so most triangles share level 0 and a cell meets
// about a dozen, compact or sliver.
// Cells are found by hashing (level, cell): only cells that hold triangles use memory.
// A query walks each occupied level's cells along the segment (a 3D DDA), the levels
// merged in order of distance, and stops at the first cell entered beyond the nearest
// contact found so far. Each level's walk starts where the segment enters the box around
// that level's triangles and ends where it leaves their range of cells, so a segment
// however long, from however far, walks at most across the model.
//
// Units and frame: the mesh's. FirstHit is servo-tick safe: no allocation, no lock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "hapticad/core/geometry/segment_triangle.h"
#include "hapticad/core/geometry/sweep_search.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/huge_page_allocator.h"

namespace hapticad {

class TriangleGrid {
 public:
  static constexpr int kMaxLevels = 15;

  // `mesh` must outlive the grid. `pad` (model units, finite, > 0) grows every triangle's
  // box, so a segment that meets a triangle within rounding of a cell's face finds it in
  // the cell on either side. Throws std::invalid_argument for any other pad.
  static std::unique_ptr<TriangleGrid> Build(const TriangleMesh& mesh, double pad);

  // First contact of a point query (query.radius must be 0: a sphere is the tree's).
  // The segment is clipped to the box around every triangle first, so a device far
  // away costs nothing; inside it the walk is as long as the segment up to its first
  // contact or its exit. Servo-tick safe. `cells_visited`, if given, is increased by the
  // number of cells looked up (for tests and benchmarks).
  bool FirstHit(const SweepQuery& query, SweepHit* hit, std::size_t* cells_visited = nullptr) const;
  // Feeds a point query's search every triangle that could beat its nearest contact so
  // far: its answer is then the first contact. Returns the cells looked up. Servo-tick safe.
  std::size_t Search(SweepSearch* search) const;

  // Warms the caches for the cells the segment `from` -> `to` enters after the one it
  // starts in (in the finest occupied level; the segment no longer than a cell, so at
  // most one step along each axis: three cells; a segment that starts outside the
  // grid's box is clipped to it, and the cell where it enters is warmed too), one
  // dependent step per cell and call,
  // so the servo tick that reaches a cell finds its data loaded: the hash slot, then the
  // cell's references, then its triangles (indices, normals, CAD faces), then their
  // vertices. A proxy calls it every tick with the stretch of its path just ahead: every
  // cell on it, not only the one at its end, since a path that cuts the corner of a
  // cell is in it for a tick or two, too soon for a cell first warmed then (1M
  // triangles, p99: 2.3 us unwarmed, 1.1 us warming the cell at the end, 0.97 us every
  // cell; BENCHMARKS.md). Prefetch instructions only: no waiting on memory, servo-tick
  // safe. Does nothing for a segment that misses the grid's box or is not finite.
  struct Prefetch {
    static constexpr int kCells = 4;
    std::uint64_t key[kCells] = {kEmpty, kEmpty, kEmpty, kEmpty};  // CellKey()s, in order
    int stage[kCells] = {};
  };
  void WarmUp(const Vec3& from, const Vec3& to, Prefetch* state) const;
  // The key of the cell of the finest occupied level that holds `point` (what
  // Prefetch::key holds).
  std::uint64_t CellKey(const Vec3& point) const;

  double cell_size() const { return h0_; }                       // level 0, model units
  std::uint32_t occupied_levels() const { return level_mask_; }  // bit L: level L has cells
  std::size_t CalcMemoryBytes() const;
  // Slots a look-up of a stored cell reads, on average over every cell (1 is ideal).
  double CalcMeanProbeLength() const;

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  struct Cell {
    std::uint64_t key;  // kEmpty, or (level, ix, iy, iz) packed
    std::uint32_t begin;
    std::uint32_t count;
  };
  TriangleGrid() = default;
  static std::uint64_t Key(int level, std::int64_t ix, std::int64_t iy, std::int64_t iz);
  std::size_t Slot(std::uint64_t key) const;
  void SetTableSize(std::size_t size);  // a power of two
  const Cell* Find(std::uint64_t key) const;
  // One step of the warm-up of a cell: *stage 0 to 3, then nothing.
  void AdvanceWarmUp(std::uint64_t key, int* stage) const;
  std::size_t Walk(const SegmentRay& ray, double s0, SweepSearch* search) const;

  const TriangleMesh* mesh_ = nullptr;
  int first_level_ = 0;  // the finest occupied level
  double h0_ = 0.0;
  Vec3 lo_ = Vec3::Zero();  // the box around every (padded) triangle
  Vec3 hi_ = Vec3::Zero();
  Vec3 level_lo_[kMaxLevels];  // the same per level
  Vec3 level_hi_[kMaxLevels];
  bool level_is_whole_[kMaxLevels] = {};      // its box is the model's
  std::int32_t cell_lo_[kMaxLevels][3] = {};  // the range of each level's occupied cells
  std::int32_t cell_hi_[kMaxLevels][3] = {};
  double inv_h_[kMaxLevels] = {};
  std::uint32_t level_mask_ = 0;
  std::size_t num_cells_ = 0;
  HugePageVector<Cell> table_;  // open addressing, linear probing, a power of two long
  std::uint64_t mask_ = 0;
  int shift_ = 64;  // 64 - log2(table size): the slot is the top bits of the hash
  HugePageVector<std::uint32_t> refs_;
};

}  // namespace hapticad
