// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: TriangleGrid::FirstHit and WarmUp run on the servo thread every tick.
#include "hapticad/core/geometry/triangle_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hapticad {
namespace {

constexpr int kAxisBits = 20;
constexpr std::int64_t kAxisOffset = std::int64_t{1} << (kAxisBits - 1);
constexpr std::uint64_t kAxisMask = (std::uint64_t{1} << kAxisBits) - 1;
// A sliver along an axis may stay in fine cells; a large face goes up a level or more.
constexpr std::size_t kMaxCellsPerTriangle = 32;

std::size_t NextPowerOfTwo(std::size_t n) {
  std::size_t p = 16;
  while (p < n) p <<= 1;
  return p;
}

// Cells of one triangle: its level and the range of cells its padded box covers.
struct Filing {
  std::int32_t lo[3];
  std::int32_t hi[3];
  std::int32_t level;
};

}  // namespace

std::uint64_t TriangleGrid::Key(int level, std::int64_t ix, std::int64_t iy, std::int64_t iz) {
  return (static_cast<std::uint64_t>(level) << (3 * kAxisBits)) |
         (static_cast<std::uint64_t>(ix + kAxisOffset) & kAxisMask) << (2 * kAxisBits) |
         (static_cast<std::uint64_t>(iy + kAxisOffset) & kAxisMask) << kAxisBits |
         (static_cast<std::uint64_t>(iz + kAxisOffset) & kAxisMask);
}

std::size_t TriangleGrid::Slot(std::uint64_t key) const {
  // Fibonacci hashing: the top bits of the product, the only ones every bit of the key
  // (level, x, y and z) reaches
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
}

void TriangleGrid::SetTableSize(std::size_t size) {
  mask_ = size - 1;
  shift_ = 64;
  for (std::size_t n = size; n > 1; n >>= 1) --shift_;
}

const TriangleGrid::Cell* TriangleGrid::Find(std::uint64_t key) const {
  for (std::size_t i = Slot(key);; i = (i + 1) & mask_) {
    const Cell& cell = table_[i];
    if (cell.key == key) return &cell;
    if (cell.key == kEmpty) return nullptr;
  }
}

std::unique_ptr<TriangleGrid> TriangleGrid::Build(const TriangleMesh& mesh, double pad) {
  if (!(pad > 0.0) || !std::isfinite(pad)) {
    throw std::invalid_argument("TriangleGrid: the pad must be finite and > 0");
  }
  std::unique_ptr<TriangleGrid> grid(new TriangleGrid());
  grid->mesh_ = &mesh;
  const std::size_t n = mesh.num_triangles();
  if (n == 0) return grid;
  auto box = [&](std::size_t t, Vec3* lo, Vec3* hi) {
    const auto& tri = mesh.triangle(static_cast<std::uint32_t>(t));
    const Vec3& a = mesh.vertex(tri[0]);
    const Vec3& b = mesh.vertex(tri[1]);
    const Vec3& c = mesh.vertex(tri[2]);
    *lo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(pad);
    *hi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(pad);
  };
  // Level 0's cell: a little over twice the 90th percentile of the triangles' widths
  // (the height over the longest edge), from a sample, so a cell meets about a dozen
  // triangles whether they are compact or long slivers (a cylinder's sides).
  const std::size_t stride = std::max<std::size_t>(1, n / 65536);
  std::vector<double> widths;
  widths.reserve(n / stride + 1);
  for (std::size_t t = 0; t < n; t += stride) {
    const auto& tri = mesh.triangle(static_cast<std::uint32_t>(t));
    const Vec3& a = mesh.vertex(tri[0]);
    const Vec3& b = mesh.vertex(tri[1]);
    const Vec3& c = mesh.vertex(tri[2]);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    widths.push_back(longest > 0.0 ? (b - a).cross(c - a).norm() / longest : 0.0);
  }
  double reach = 0.0;  // the largest coordinate, for the index range
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    reach = std::max(reach, mesh.vertex(static_cast<std::uint32_t>(v)).cwiseAbs().maxCoeff());
  }
  const auto p90 = widths.begin() + static_cast<std::ptrdiff_t>(0.9 * (widths.size() - 1));
  std::nth_element(widths.begin(), p90, widths.end());
  // every cell index must fit its 20 bits, with room for a query a little outside
  const double h_min = (reach + pad) / static_cast<double>(kAxisOffset / 4);
  grid->h0_ = std::max(2.3 * *p90 + 2.0 * pad, h_min);
  for (int level = 0; level < kMaxLevels; ++level) {
    grid->inv_h_[level] = 1.0 / std::ldexp(grid->h0_, level);
  }

  // the cells of every triangle, and how many references they make
  std::vector<Filing> filings(n);
  std::size_t total = 0;
  grid->lo_ = Vec3::Constant(std::numeric_limits<double>::infinity());
  grid->hi_ = -grid->lo_;
  for (int level = 0; level < kMaxLevels; ++level) {
    grid->level_lo_[level] = grid->lo_;
    grid->level_hi_[level] = grid->hi_;
    for (int k = 0; k < 3; ++k) {
      grid->cell_lo_[level][k] = std::numeric_limits<std::int32_t>::max();
      grid->cell_hi_[level][k] = std::numeric_limits<std::int32_t>::min();
    }
  }
  for (std::size_t t = 0; t < n; ++t) {
    Vec3 lo, hi;
    box(t, &lo, &hi);
    grid->lo_ = grid->lo_.cwiseMin(lo);
    grid->hi_ = grid->hi_.cwiseMax(hi);
    // the finest level where the box covers at most kMaxCellsPerTriangle cells
    Filing& f = filings[t];
    std::size_t cells = 0;
    for (int level = 0; level < kMaxLevels; ++level) {
      f.level = level;
      cells = 1;
      for (int k = 0; k < 3; ++k) {
        f.lo[k] = static_cast<std::int32_t>(std::floor(lo[k] * grid->inv_h_[level]));
        f.hi[k] = static_cast<std::int32_t>(std::floor(hi[k] * grid->inv_h_[level]));
        cells *= static_cast<std::size_t>(f.hi[k] - f.lo[k] + 1);
      }
      if (cells <= kMaxCellsPerTriangle) break;
    }
    const int level = f.level;
    total += cells;
    grid->level_mask_ |= 1u << level;
    grid->level_lo_[level] = grid->level_lo_[level].cwiseMin(lo);
    grid->level_hi_[level] = grid->level_hi_[level].cwiseMax(hi);
    for (int k = 0; k < 3; ++k) {
      grid->cell_lo_[level][k] = std::min(grid->cell_lo_[level][k], f.lo[k]);
      grid->cell_hi_[level][k] = std::max(grid->cell_hi_[level][k], f.hi[k]);
    }
  }

  for (int level = 0; level < kMaxLevels; ++level) {
    grid->level_is_whole_[level] =
        grid->level_lo_[level] == grid->lo_ && grid->level_hi_[level] == grid->hi_;
  }
  while (grid->first_level_ + 1 < kMaxLevels && !(grid->level_mask_ & (1u << grid->first_level_))) {
    ++grid->first_level_;
  }
  // Count per cell. The table starts at a quarter of the references (cells hold several
  // each) and doubles whenever it passes half full.
  HugePageVector<Cell>& table = grid->table_;
  table.assign(NextPowerOfTwo(total / 4), Cell{kEmpty, 0, 0});
  grid->SetTableSize(table.size());
  auto insert = [&](std::uint64_t key) -> std::size_t {
    for (std::size_t i = grid->Slot(key);; i = (i + 1) & grid->mask_) {
      if (table[i].key == key) return i;
      if (table[i].key == kEmpty) {
        table[i].key = key;
        ++grid->num_cells_;
        return i;
      }
    }
  };
  auto rehash = [&](std::size_t size) {
    HugePageVector<Cell> old(size, Cell{kEmpty, 0, 0});
    old.swap(table);
    grid->SetTableSize(table.size());
    for (const Cell& cell : old) {
      if (cell.key == kEmpty) continue;
      std::size_t i = grid->Slot(cell.key);
      while (table[i].key != kEmpty) i = (i + 1) & grid->mask_;
      table[i] = cell;
    }
  };
  auto for_each_cell = [&](const Filing& f, auto&& visit) {
    for (std::int32_t x = f.lo[0]; x <= f.hi[0]; ++x) {
      for (std::int32_t y = f.lo[1]; y <= f.hi[1]; ++y) {
        for (std::int32_t z = f.lo[2]; z <= f.hi[2]; ++z) visit(Key(f.level, x, y, z));
      }
    }
  };
  for (std::size_t t = 0; t < n; ++t) {
    for_each_cell(filings[t], [&](std::uint64_t key) {
      if (2 * (grid->num_cells_ + 1) > table.size()) rehash(2 * table.size());
      ++table[insert(key)].count;
    });
  }
  // each cell's references in one run of refs_, in triangle order
  std::uint32_t begin = 0;
  for (Cell& cell : table) {
    cell.begin = begin;
    begin += cell.count;
    cell.count = 0;
  }
  grid->refs_.resize(total);
  for (std::size_t t = 0; t < n; ++t) {
    for_each_cell(filings[t], [&](std::uint64_t key) {
      Cell& cell = table[insert(key)];
      grid->refs_[cell.begin + cell.count++] = static_cast<std::uint32_t>(t);
    });
  }
  // the table the servo keeps: at most half full
  if (table.size() > NextPowerOfTwo(2 * grid->num_cells_))
    rehash(NextPowerOfTwo(2 * grid->num_cells_));
  return grid;
}

namespace {

// Amanatides and Woo's walk through one level's cells along the segment, in order.
struct CellWalk {
  int level;
  std::int64_t cell[3];
  std::int64_t step[3];
  double next[3];   // s at which the segment crosses into the next cell along each axis
  double delta[3];  // s between crossings along each axis
  double entry;     // s at which the segment entered the current cell

  // From `start` = a + s0 d, the segment's point at s0.
  void Start(int l, double inv_h, const Vec3& start, double s0, const Vec3& d) {
    level = l;
    entry = s0;
    for (int k = 0; k < 3; ++k) {
      const double x = start[k] * inv_h;
      const double fx = std::floor(x);
      cell[k] = static_cast<std::int64_t>(fx);
      const double dx = d[k] * inv_h;
      if (dx > 0.0) {
        step[k] = 1;
        delta[k] = 1.0 / dx;
        next[k] = s0 + (fx + 1.0 - x) * delta[k];
      } else if (dx < 0.0) {
        step[k] = -1;
        delta[k] = -1.0 / dx;
        next[k] = s0 + (x - fx) * delta[k];
      } else {
        step[k] = 0;
        delta[k] = 0.0;
        next[k] = std::numeric_limits<double>::infinity();
      }
    }
  }

  void Advance() {
    const int k = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
    entry = next[k];
    cell[k] += step[k];
    next[k] += delta[k];
  }

  // Whether the walk has gone past the cells [lo, hi] for good: beyond them on an axis
  // it moves away along, or beside them on an axis it does not move along.
  bool Past(const std::int32_t lo[3], const std::int32_t hi[3]) const {
    for (int k = 0; k < 3; ++k) {
      if (cell[k] > hi[k] && step[k] >= 0) return true;
      if (cell[k] < lo[k] && step[k] <= 0) return true;
    }
    return false;
  }
};

}  // namespace

bool TriangleGrid::FirstHit(const SweepQuery& query, SweepHit* hit,
                            std::size_t* cells_visited) const {
  SweepSearch search(*mesh_, query);
  const std::size_t cells = Search(&search);
  if (cells_visited != nullptr) *cells_visited += cells;
  if (!search.found()) return false;
  search.Report(hit);
  return true;
}

std::size_t TriangleGrid::Search(SweepSearch* search) const {
  const SegmentRay ray(search->a(), search->d());  // the divisions once per query
  double s0 = 0.0;  // where the segment enters the box around every triangle
  if (!table_.empty() && IntersectSegmentBox(ray, 1.0, lo_.data(), hi_.data(), 0.0, &s0) &&
      s0 <= search->best_s()) {
    return Walk(ray, s0, search);
  }
  return 0;
}

// The levels' walks merged in order of s, so the nearest contact, whatever its level,
// is found first and ends every walk early. Each starts where the segment enters its
// level's box and ends when it leaves its level's cells. Returns the cells looked up.
std::size_t TriangleGrid::Walk(const SegmentRay& ray, double s0, SweepSearch* search) const {
  CellWalk walks[kMaxLevels];
  int count = 0;
  const Vec3& a = search->a();
  const Vec3& d = search->d();
  for (int level = 0; level < kMaxLevels; ++level) {
    if (!(level_mask_ & (1u << level))) continue;
    double l0 = s0;
    // (a level spread over the whole model starts where the model's box does)
    if (!level_is_whole_[level]) {
      double entry = 0.0;
      if (!IntersectSegmentBox(ray, 1.0, level_lo_[level].data(), level_hi_[level].data(), 0.0,
                               &entry)) {
        continue;
      }
      l0 = std::max(l0, entry);
    }
    walks[count].Start(level, inv_h_[level], a + l0 * d, l0, d);
    if (!walks[count].Past(cell_lo_[level], cell_hi_[level])) ++count;
  }
  std::size_t cells = 0;
  while (count > 0) {
    int i = 0;
    for (int j = 1; j < count; ++j) {
      if (walks[j].entry < walks[i].entry) i = j;
    }
    CellWalk& walk = walks[i];
    if (!(walk.entry <= search->best_s())) break;  // every other walk is further still
    ++cells;
    if (const Cell* c = Find(Key(walk.level, walk.cell[0], walk.cell[1], walk.cell[2]))) {
      const std::uint32_t* ref = refs_.data() + c->begin;
      for (std::uint32_t r = 0; r < c->count; ++r) search->Test(ref[r]);
    }
    walk.Advance();
    if (walk.Past(cell_lo_[walk.level], cell_hi_[walk.level])) walk = walks[--count];
  }
  return cells;
}

void TriangleGrid::WarmUp(const Vec3& from, const Vec3& to, Prefetch* state) const {
  if (table_.empty() || !from.allFinite() || !to.allFinite()) return;
  // the part of the segment inside the grid's box: a proxy coming down onto the model
  // from outside it warms the cell it will land in
  const Vec3 d = to - from;
  double s0 = 0.0;
  double s1 = 1.0;
  const auto inside = [this](const Vec3& p) {
    return p.cwiseMax(lo_) == p && p.cwiseMin(hi_) == p;
  };
  if (!(inside(from) && inside(to))) {  // the usual case needs no clipping
    for (int k = 0; k < 3; ++k) {
      if (d[k] == 0.0) {
        if (from[k] < lo_[k] || from[k] > hi_[k]) return;
        continue;
      }
      double t0 = (lo_[k] - from[k]) / d[k];
      double t1 = (hi_[k] - from[k]) / d[k];
      if (t0 > t1) std::swap(t0, t1);
      s0 = std::max(s0, t0);
      s1 = std::min(s1, t1);
      if (s0 > s1) return;
    }
  }
  const double inv_h = inv_h_[first_level_];
  const Vec3 a = (from + s0 * d) * inv_h;
  const Vec3 b = (from + s1 * d) * inv_h;
  std::int64_t cell[3];
  std::int64_t end[3];
  for (int k = 0; k < 3; ++k) {
    cell[k] = static_cast<std::int64_t>(std::floor(a[k]));
    end[k] = static_cast<std::int64_t>(std::floor(b[k]));
  }
  std::uint64_t key[Prefetch::kCells] = {kEmpty, kEmpty, kEmpty, kEmpty};
  int count = 0;
  if (s0 > 0.0) key[count++] = Key(first_level_, cell[0], cell[1], cell[2]);  // entered
  // the cells after the first, in the order the segment enters them: at most one
  // boundary per axis, crossed at parameter t
  double t[3];
  int axis[3];
  int crossings = 0;
  for (int k = 0; k < 3; ++k) {
    if (cell[k] == end[k]) continue;
    const double boundary = static_cast<double>(b[k] > a[k] ? cell[k] + 1 : cell[k]);
    const double tk = (boundary - a[k]) / (b[k] - a[k]);
    int i = crossings++;
    for (; i > 0 && t[i - 1] > tk; --i) {
      t[i] = t[i - 1];
      axis[i] = axis[i - 1];
    }
    t[i] = tk;
    axis[i] = k;
  }
  for (int i = 0; i < crossings; ++i) {
    cell[axis[i]] += b[axis[i]] > a[axis[i]] ? 1 : -1;
    key[count++] = Key(first_level_, cell[0], cell[1], cell[2]);
  }
  if (!std::equal(key, key + Prefetch::kCells, state->key)) {
    // new cells ahead: those still ahead keep their progress
    Prefetch next;
    for (int i = 0; i < count; ++i) {
      next.key[i] = key[i];
      for (int j = 0; j < Prefetch::kCells; ++j) {
        if (state->key[j] == key[i]) next.stage[i] = state->stage[j];
      }
    }
    *state = next;
  }
  for (int i = 0; i < count; ++i) {
    if (state->stage[i] < 4) AdvanceWarmUp(state->key[i], &state->stage[i]);
  }
}

std::uint64_t TriangleGrid::CellKey(const Vec3& point) const {
  const double inv_h = inv_h_[first_level_];
  return Key(first_level_, static_cast<std::int64_t>(std::floor(point.x() * inv_h)),
             static_cast<std::int64_t>(std::floor(point.y() * inv_h)),
             static_cast<std::int64_t>(std::floor(point.z() * inv_h)));
}

void TriangleGrid::AdvanceWarmUp(std::uint64_t key, int* stage) const {
  // each stage reads only what the stage before it prefetched
  switch (*stage) {
    case 0:
      __builtin_prefetch(&table_[Slot(key)]);
      break;
    case 1:
      if (const Cell* c = Find(key)) {
        __builtin_prefetch(refs_.data() + c->begin);
        __builtin_prefetch(refs_.data() + c->begin + c->count - 1);
      }
      break;
    case 2:
      if (const Cell* c = Find(key)) {
        for (std::uint32_t i = 0; i < c->count; ++i) {
          mesh_->PrefetchTriangle(refs_[c->begin + i]);
        }
      }
      break;
    case 3:
      if (const Cell* c = Find(key)) {
        for (std::uint32_t i = 0; i < c->count; ++i) mesh_->PrefetchVertices(refs_[c->begin + i]);
      }
      break;
    default:
      return;
  }
  ++*stage;
}

double TriangleGrid::CalcMeanProbeLength() const {
  std::size_t probes = 0;
  for (std::size_t i = 0; i < table_.size(); ++i) {
    if (table_[i].key != kEmpty) probes += ((i - Slot(table_[i].key)) & mask_) + 1;
  }
  return num_cells_ > 0 ? static_cast<double>(probes) / static_cast<double>(num_cells_) : 0.0;
}

std::size_t TriangleGrid::CalcMemoryBytes() const {
  return table_.capacity() * sizeof(Cell) + refs_.capacity() * sizeof(std::uint32_t);
}

}  // namespace hapticad
