// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL translation unit (walled off in hapticad_cgal).
#include "hapticad/core/geometry/mesh_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>

#include "hapticad/core/geometry/connected_pieces.h"
#include "hapticad/core/geometry/vertex_buckets.h"

namespace hapticad {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Polygon = std::array<std::size_t, 3>;
using EdgeCounts = std::vector<std::pair<std::pair<std::size_t, std::size_t>, int>>;
namespace PMP = CGAL::Polygon_mesh_processing;
// exact predicates on the same doubles, for the inside tests of step 5
using ExactPredicates = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactPoint = ExactPredicates::Point_3;

Vec3 ToVec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

// Undirected edges with the number of triangles on each, sorted. A counting sort by the
// lower vertex, then each vertex's few edges sorted in place: O(n), where a sort of the
// 3n edge copies was a third of a 1M-triangle repair.
EdgeCounts CountEdges(const std::vector<Polygon>& polygons) {
  std::size_t vertices = 0;
  for (const Polygon& p : polygons) vertices = std::max({vertices, p[0] + 1, p[1] + 1, p[2] + 1});
  // the edges whose lower vertex is v, by their upper vertex
  const auto edge = [&polygons](std::size_t i) {
    const Polygon& p = polygons[i / 3];
    return std::minmax(p[i % 3], p[(i % 3 + 1) % 3]);
  };
  VertexBuckets<std::size_t> upper = BucketByVertex<std::size_t>(
      vertices, 3 * polygons.size(), [&](std::size_t i) { return edge(i).first; },
      [&](std::size_t i) { return edge(i).second; });
  EdgeCounts counted;
  counted.reserve(upper.values.size() / 2 + 1);
  for (std::size_t v = 0; v < vertices; ++v) {
    const auto first = upper.begin(v);
    const auto last = upper.end(v);
    std::sort(first, last);
    for (auto i = first; i != last;) {
      auto j = i;
      while (j != last && *j == *i) ++j;
      counted.push_back({{v, *i}, static_cast<int>(j - i)});
      i = j;
    }
  }
  return counted;
}

// Merges points with equal coordinates into the first of them and numbers the points
// left in the order of their first appearance: what CGAL's
// merge_duplicate_points_in_polygon_soup does, with a sort of the indices in place of
// its std::map (a node allocated per point). Returns how many points were merged away.
std::size_t MergeDuplicatePoints(std::vector<Point>* points, std::vector<Polygon>* polygons) {
  const std::size_t n = points->size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  const std::vector<Point>& p = *points;
  std::sort(order.begin(), order.end(), [&p](std::size_t a, std::size_t b) {
    const Point& u = p[a];
    const Point& v = p[b];
    if (u.x() != v.x()) return u.x() < v.x();
    if (u.y() != v.y()) return u.y() < v.y();
    if (u.z() != v.z()) return u.z() < v.z();
    return a < b;
  });
  std::vector<std::size_t> first(n);  // the first index with the same coordinates
  std::size_t merged = 0;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j < n && p[order[j]] == p[order[i]]) first[order[j++]] = order[i];
    merged += j - i - 1;
    i = j;
  }
  if (merged == 0) return 0;
  std::vector<std::size_t> id(n);
  std::vector<Point> unique;
  unique.reserve(n - merged);
  for (std::size_t i = 0; i < n; ++i) {
    if (first[i] == i) {
      id[i] = unique.size();
      unique.push_back(p[i]);
    } else {
      id[i] = id[first[i]];  // first[i] < i: numbered already
    }
  }
  for (Polygon& polygon : *polygons) {
    for (std::size_t& v : polygon) v = id[v];
  }
  points->swap(unique);
  return merged;
}

// Counts what CGAL's orientation does, and remembers duplicated vertices.
struct OrientationVisitor : PMP::Default_orientation_visitor {
  std::size_t* non_manifold_vertices;
  std::vector<std::size_t>* original;  // vertex id -> the id it was duplicated from
  void non_manifold_vertex(std::size_t, std::size_t) { ++*non_manifold_vertices; }
  void duplicated_vertex(std::size_t from, std::size_t to) {
    if (original->size() <= to) original->resize(to + 1);
    (*original)[to] = from < original->size() ? (*original)[from] : from;
  }
};

// Merges vertices on open edges that lie within `tolerance` of each other. Returns how
// many were merged.
std::size_t WeldOpenEdges(const std::vector<Point>& points, std::vector<Polygon>* polygons,
                          double tolerance) {
  std::vector<std::size_t> open;
  for (const auto& [edge, count] : CountEdges(*polygons)) {
    if (count == 1) {
      open.push_back(edge.first);
      open.push_back(edge.second);
    }
  }
  std::sort(open.begin(), open.end());
  open.erase(std::unique(open.begin(), open.end()), open.end());
  if (open.empty() || !(tolerance > 0.0)) return 0;
  // a hash grid of cells one tolerance wide: a partner lies in one of 27 cells
  auto cell = [&](const Point& p, int dx, int dy, int dz) {
    const auto q = [&](double x, int dk) {
      return static_cast<std::int64_t>(std::floor(x / tolerance)) + dk;
    };
    // unsigned arithmetic: far from the origin the cell indices are large
    const auto ix = static_cast<std::uint64_t>(q(p.x(), dx));
    const auto iy = static_cast<std::uint64_t>(q(p.y(), dy));
    const auto iz = static_cast<std::uint64_t>(q(p.z(), dz));
    return ix * 73856093u ^ iy * 19349663u ^ iz * 83492791u;
  };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  std::unordered_map<std::size_t, std::size_t> into;
  for (std::size_t v : open) {
    const Point& p = points[v];
    std::size_t partner = v;
    for (int dx = -1; dx <= 1 && partner == v; ++dx) {
      for (int dy = -1; dy <= 1 && partner == v; ++dy) {
        for (int dz = -1; dz <= 1 && partner == v; ++dz) {
          const auto found = grid.find(cell(p, dx, dy, dz));
          if (found == grid.end()) continue;
          for (std::size_t w : found->second) {
            if ((ToVec(points[w]) - ToVec(p)).norm() <= tolerance) {
              partner = w;
              break;
            }
          }
        }
      }
    }
    if (partner == v) {
      grid[cell(p, 0, 0, 0)].push_back(v);
    } else {
      into[v] = partner;
    }
  }
  for (Polygon& polygon : *polygons) {
    for (std::size_t& v : polygon) {
      const auto found = into.find(v);
      if (found != into.end()) v = found->second;
    }
  }
  return into.size();
}

// Whether the segment p-q (q outside the triangle's box) crosses triangle abc: 1
// through its inside, 0 not at all, -1 through an edge or a corner, from p on the
// triangle or within its plane, where a count of crossings could be wrong.
int Crosses(const ExactPoint& p, const ExactPoint& q, const ExactPoint& a, const ExactPoint& b,
            const ExactPoint& c) {
  const CGAL::Orientation side_p = CGAL::orientation(a, b, c, p);
  const CGAL::Orientation side_q = CGAL::orientation(a, b, c, q);
  if (side_p == side_q) return side_p == CGAL::COPLANAR ? -1 : 0;
  if (side_p == CGAL::COPLANAR) {
    // the segment meets the plane at p alone: in the triangle only if in its box
    const CGAL::Bbox_3 box = a.bbox() + b.bbox() + c.bbox();
    return CGAL::do_overlap(box, p.bbox()) ? -1 : 0;
  }
  const CGAL::Orientation s[3] = {CGAL::orientation(p, q, a, b), CGAL::orientation(p, q, b, c),
                                  CGAL::orientation(p, q, c, a)};
  int positive = 0, negative = 0;
  for (const CGAL::Orientation o : s) {
    positive += o == CGAL::POSITIVE;
    negative += o == CGAL::NEGATIVE;
  }
  if (positive == 3 || negative == 3) return 1;
  return positive == 0 || negative == 0 ? -1 : 0;  // on an edge or a corner, or outside
}

// The pairs (i, j) of boxes a[i] and b[j] that meet (closed boxes: a point on a box's
// face is in it), by their infos, sorted. CGAL's box intersection: O(n log n) where a
// loop over all pairs would be quadratic in the number of pieces.
using InfoBox = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
std::vector<std::pair<std::size_t, std::size_t>> MeetingBoxes(std::vector<InfoBox> a,
                                                              std::vector<InfoBox> b) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  CGAL::box_intersection_d(
      a.begin(), a.end(), b.begin(), b.end(),
      [&pairs](const InfoBox& x, const InfoBox& y) { pairs.emplace_back(x.info(), y.info()); });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

CGAL::Bbox_3 ToBbox(const Vec3& lo, const Vec3& hi) {
  return CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
}

// The connected pieces of an oriented soup, which are closed, which way each winds, and
// which closed pieces hold which: what step 5 needs to tell a part's outer shell from
// its void. The inside tests use exact predicates (SideOf).
class ClosedPieces {
 public:
  ClosedPieces(const std::vector<Point>& points, const std::vector<Polygon>& polygons,
               const EdgeCounts& edges)
      : points_(points),
        polygons_(polygons),
        pieces_(FindConnectedPieces(
            points.size(), polygons.size(),
            [&polygons](std::size_t t, int k) { return polygons[t][k]; },
            [&points](std::size_t v) { return ToVec(points[v]); })),
        closed_(pieces_.lo.size(), 1),
        volume_(pieces_.lo.size(), 0.0) {
    for (const auto& [edge, count] : edges) {
      if (count != 2) closed_[pieces_.of_vertex[edge.first]] = 0;
    }
    // six times each piece's volume, about its box's corner (a part far from the origin
    // keeps its digits)
    for (std::size_t t = 0; t < polygons.size(); ++t) {
      const std::uint32_t c = piece_of(t);
      const Vec3& o = pieces_.lo[c];
      const Vec3 a = ToVec(points[polygons[t][0]]) - o, b = ToVec(points[polygons[t][1]]) - o,
                 d = ToVec(points[polygons[t][2]]) - o;
      volume_[c] += a.dot(b.cross(d));
    }
  }

  std::size_t size() const { return closed_.size(); }
  bool closed(std::size_t c) const { return closed_[c] != 0; }
  double volume(std::size_t c) const { return volume_[c]; }
  std::uint32_t piece_of(std::size_t t) const { return pieces_.of_vertex[polygons_[t][0]]; }
  InfoBox box(std::size_t c) const { return {ToBbox(pieces_.lo[c], pieces_.hi[c]), c}; }
  bool BoxHolds(std::size_t outer, std::size_t inner) const {
    return (pieces_.lo[inner].array() >= pieces_.lo[outer].array()).all() &&
           (pieces_.hi[inner].array() <= pieces_.hi[outer].array()).all();
  }

  // For each piece of `queried`, at up to kTries of its vertices (spread over its
  // triangles), the closed pieces that hold the vertex. A vertex on a piece's surface,
  // or in an open piece's box (a cracked shell round it could be its part), tells
  // nothing. `known`: some vertex told; `pieces`: the first such vertex's holders;
  // `free`: some such vertex is held by none.
  struct Holders {
    bool known = false;
    std::vector<std::size_t> pieces;
    bool free = false;
  };
  std::vector<Holders> FindHolders(const std::vector<std::size_t>& queried) {
    static constexpr std::size_t kTries = 8;
    GroupTriangles();
    const auto vertex = [&](std::size_t c, std::size_t j) {  // j < kTries
      const std::size_t n = start_[c + 1] - start_[c];
      return polygons_[by_piece_[start_[c] + j * n / kTries]][j % 3];
    };
    std::vector<InfoBox> at, round;
    for (std::size_t q = 0; q < queried.size(); ++q) {
      for (std::size_t j = 0; j < kTries; ++j) {
        at.emplace_back(points_[vertex(queried[q], j)].bbox(), q * kTries + j);
      }
    }
    for (std::size_t c = 0; c < size(); ++c) round.push_back(box(c));
    const auto pairs = MeetingBoxes(std::move(at), std::move(round));
    std::vector<std::size_t> asked(size(), 0);
    for (const auto& [key, h] : pairs) ++asked[h];
    std::vector<Holders> out(queried.size());
    auto pair = pairs.begin();
    for (std::size_t q = 0; q < queried.size(); ++q) {
      for (std::size_t j = 0; j < kTries; ++j) {
        const std::size_t key = q * kTries + j;
        const auto first = pair;
        while (pair != pairs.end() && pair->first == key) ++pair;
        const Point& p = points_[vertex(queried[q], j)];
        bool clean = true;
        std::vector<std::size_t> holders;
        for (auto it = first; it != pair && clean; ++it) {
          const std::size_t h = it->second;
          if (h == queried[q]) continue;
          if (!closed(h)) {
            clean = false;  // an open piece's box
            break;
          }
          const CGAL::Bounded_side side = SideOf(h, p, asked[h]);
          clean = side != CGAL::ON_BOUNDARY;
          if (side == CGAL::ON_BOUNDED_SIDE) holders.push_back(h);
        }
        if (!clean) continue;
        out[q].free = out[q].free || holders.empty();
        if (!out[q].known) out[q].pieces = std::move(holders);
        out[q].known = true;
      }
    }
    return out;
  }

  // Whether the surfaces of closed pieces a and b cross or touch (CGAL's do_intersect);
  // true too where either cannot be tested.
  bool SurfacesMeet(std::size_t a, std::size_t b) {
    const Built* x = Build(a);
    const Built* y = Build(b);
    return !x->taken || !y->taken || CGAL::Polygon_mesh_processing::do_intersect(x->mesh, y->mesh);
  }

 private:
  using PieceMesh = CGAL::Surface_mesh<ExactPoint>;
  using InsideTest = CGAL::Side_of_triangle_mesh<PieceMesh, ExactPredicates>;
  struct Built {
    PieceMesh mesh;
    bool taken = true;                   // CGAL took every triangle, and the mesh is closed
    std::unique_ptr<InsideTest> inside;  // its tree, made when many vertices ask
  };

  // Which side of closed piece h the point p lies on, `asked` being how many vertices
  // will ask about h: for a few, exact parity along up to three segments out of h's
  // box, brute force over its triangles (a few ms on a million); for more, CGAL's
  // Side_of_triangle_mesh, whose tree costs as much as some twenty such counts but
  // answers each ask in O(log n). ON_BOUNDARY: the point tells nothing (on the surface,
  // or no clean count).
  CGAL::Bounded_side SideOf(std::size_t h, const Point& p, std::size_t asked) {
    static constexpr std::size_t kAsksForATree = 24;
    const ExactPoint from(p.x(), p.y(), p.z());
    if (asked >= kAsksForATree) {
      Built* built = Build(h);
      if (!built->taken) return CGAL::ON_BOUNDARY;
      if (built->inside == nullptr) built->inside = std::make_unique<InsideTest>(built->mesh);
      return (*built->inside)(from);
    }
    static constexpr double kDirections[3][3] = {
        {0.5773502691896258, 0.6180339887498949, 0.5331584453516463},
        {-0.7071067811865476, 0.2360679774997897, 0.6666666666666666},
        {0.1415926535897932, -0.8660254037844386, -0.4794255386042030}};
    const double far = 2.0 * (pieces_.hi[h] - pieces_.lo[h]).norm();  // well out of the box
    const auto at = [this](std::size_t v) {
      return ExactPoint(points_[v].x(), points_[v].y(), points_[v].z());
    };
    for (const auto& d : kDirections) {
      const ExactPoint to(p.x() + far * d[0], p.y() + far * d[1], p.z() + far * d[2]);
      int crossings = 0;
      bool clean = true;
      for (std::size_t i = start_[h]; i < start_[h + 1] && clean; ++i) {
        const Polygon& t = polygons_[by_piece_[i]];
        const int crossing = Crosses(from, to, at(t[0]), at(t[1]), at(t[2]));
        clean = crossing >= 0;
        crossings += crossing;
      }
      if (clean) return crossings % 2 == 1 ? CGAL::ON_BOUNDED_SIDE : CGAL::ON_UNBOUNDED_SIDE;
    }
    return CGAL::ON_BOUNDARY;
  }

  void GroupTriangles() {
    if (!start_.empty()) return;
    start_.assign(size() + 1, 0);
    for (std::size_t t = 0; t < polygons_.size(); ++t) ++start_[piece_of(t) + 1];
    for (std::size_t c = 0; c < size(); ++c) start_[c + 1] += start_[c];
    by_piece_.resize(polygons_.size());
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    for (std::size_t t = 0; t < polygons_.size(); ++t) by_piece_[next[piece_of(t)]++] = t;
  }

  // Closed piece c as a CGAL mesh, built on first use (`taken` false where CGAL does
  // not take it as a closed triangle mesh).
  Built* Build(std::size_t c) {
    GroupTriangles();
    if (built_.empty()) built_.resize(size());
    if (built_[c] != nullptr) return built_[c].get();
    built_[c] = std::make_unique<Built>();
    PieceMesh& mesh = built_[c]->mesh;
    const std::size_t faces = start_[c + 1] - start_[c];  // closed: V = F / 2 + 2 - 2 genus
    mesh.reserve(static_cast<PieceMesh::size_type>(faces / 2 + 2),
                 static_cast<PieceMesh::size_type>(3 * faces / 2),
                 static_cast<PieceMesh::size_type>(faces));
    if (local_.empty()) local_.assign(points_.size(), kNoVertex);
    std::vector<std::size_t> used;
    bool taken = true;
    for (std::size_t i = start_[c]; i < start_[c + 1] && taken; ++i) {
      std::array<PieceMesh::Vertex_index, 3> corners;
      for (int k = 0; k < 3; ++k) {
        const std::size_t v = polygons_[by_piece_[i]][k];
        if (local_[v] == kNoVertex) {
          local_[v] = static_cast<std::uint32_t>(
              mesh.add_vertex(ExactPoint(points_[v].x(), points_[v].y(), points_[v].z())));
          used.push_back(v);
        }
        corners[k] = PieceMesh::Vertex_index(local_[v]);
      }
      taken = mesh.add_face(corners[0], corners[1], corners[2]) != PieceMesh::null_face();
    }
    for (const std::size_t v : used) local_[v] = kNoVertex;
    built_[c]->taken = taken && CGAL::is_closed(mesh);
    return built_[c].get();
  }

  static constexpr std::uint32_t kNoVertex = ~std::uint32_t{0};
  const std::vector<Point>& points_;
  const std::vector<Polygon>& polygons_;
  ConnectedPieces pieces_;
  std::vector<char> closed_;
  std::vector<double> volume_;
  std::vector<std::size_t> start_;     // piece c's triangles are by_piece_[start_[c],
  std::vector<std::size_t> by_piece_;  // start_[c + 1]), once grouped
  std::vector<std::unique_ptr<Built>> built_;
  std::vector<std::uint32_t> local_;  // while building a piece: a vertex's index in it
};

// Step 5: a closed piece wound inward (a negative volume) with a vertex outside every
// other closed piece is no void (a void lies wholly inside its part): it is the outer
// shell of a part whose triangles were listed the wrong way round (a file's writer that
// winds clockwise), and it is turned round. So is a closed piece wound outward that
// only such a shell holds and whose surface never meets the shell's (that part's void,
// listed the same way; a part overlapping the shell crosses it). Where the vertices
// tried tell nothing (on a surface, or in an open piece's box: a cracked shell round a
// void), a piece is left as it is; so is a part inside another's void, which two
// shells hold. Returns how many pieces were turned. O(n) when no closed piece winds
// inward; else O(n log n) for the boxes, and per closed piece whose box holds a vertex
// tried, O(size) per vertex for a few, or CGAL's tree over it for many.
std::size_t TurnInsideOutShells(const std::vector<Point>& points, const EdgeCounts& edges,
                                std::vector<Polygon>* polygons,
                                std::vector<std::array<Vec3, 3>>* corner_normals) {
  ClosedPieces pieces(points, *polygons, edges);
  std::vector<std::size_t> inward;
  for (std::size_t c = 0; c < pieces.size(); ++c) {
    if (pieces.closed(c) && pieces.volume(c) < 0.0) inward.push_back(c);
  }
  if (inward.empty()) return 0;
  std::vector<char> turn(pieces.size(), 0);
  std::vector<ClosedPieces::Holders> holders = pieces.FindHolders(inward);
  std::vector<InfoBox> turned_boxes, outward_boxes;
  for (std::size_t i = 0; i < inward.size(); ++i) {
    if (!holders[i].free) continue;
    turn[inward[i]] = 1;
    turned_boxes.push_back(pieces.box(inward[i]));
  }
  if (turned_boxes.empty()) return 0;
  // a turned shell's voids: closed pieces wound outward in its box
  for (std::size_t c = 0; c < pieces.size(); ++c) {
    if (pieces.closed(c) && pieces.volume(c) > 0.0) outward_boxes.push_back(pieces.box(c));
  }
  std::vector<std::size_t> in_a_turned_box;
  for (const auto& [c, shell] : MeetingBoxes(std::move(outward_boxes), std::move(turned_boxes))) {
    if (pieces.BoxHolds(shell, c) && (in_a_turned_box.empty() || in_a_turned_box.back() != c)) {
      in_a_turned_box.push_back(c);
    }
  }
  holders = pieces.FindHolders(in_a_turned_box);
  for (std::size_t i = 0; i < in_a_turned_box.size(); ++i) {
    const std::size_t c = in_a_turned_box[i];
    if (holders[i].known && holders[i].pieces.size() == 1 && turn[holders[i].pieces[0]] == 1 &&
        !pieces.SurfacesMeet(c, holders[i].pieces[0])) {
      turn[c] = 2;
    }
  }
  for (std::size_t t = 0; t < polygons->size(); ++t) {
    if (turn[pieces.piece_of(t)] == 0) continue;
    std::swap((*polygons)[t][1], (*polygons)[t][2]);
    // the corner normals follow their corners: they are the CAD surface's
    if (!corner_normals->empty()) std::swap((*corner_normals)[t][1], (*corner_normals)[t][2]);
  }
  return static_cast<std::size_t>(
      std::count_if(turn.begin(), turn.end(), [](char t) { return t != 0; }));
}

// What a triangle is, for step 3: sound, or which kind of degenerate, which says how
// it is mended. A needle: its shortest edge, too, is below the tolerance (two vertices
// nearly one); a cap: a vertex lies on the longest edge, away from its ends.
enum class Shape { kSound, kRepeated, kNeedle, kCap };

// For a degenerate triangle, `shortest` and `longest` say which of its edges k (corner k
// to corner k + 1) are.
Shape ShapeOf(const std::vector<Point>& points, const Polygon& p, double needle_tolerance,
              int* shortest = nullptr, int* longest = nullptr) {
  if (p[0] == p[1] || p[1] == p[2] || p[0] == p[2]) return Shape::kRepeated;
  const Vec3 a = ToVec(points[p[0]]), b = ToVec(points[p[1]]), c = ToVec(points[p[2]]);
  const double length[3] = {(b - a).norm(), (c - b).norm(), (a - c).norm()};
  const double most = std::max({length[0], length[1], length[2]});
  const double height = (b - a).cross(c - a).norm() / most;  // to the longest edge
  if (height > needle_tolerance * most) return Shape::kSound;
  const int low = static_cast<int>(std::min_element(length, length + 3) - length);
  const int high = static_cast<int>(std::max_element(length, length + 3) - length);
  if (shortest != nullptr) *shortest = low;
  if (longest != nullptr) *longest = high;
  return length[low] > needle_tolerance * most ? Shape::kCap : Shape::kNeedle;
}

bool Has(const Polygon& p, std::size_t v) { return p[0] == v || p[1] == v || p[2] == v; }

// The live triangles round each of a few vertices (those of degenerate triangles), kept
// up to date as step 3 edits triangles: how it finds a triangle's neighbours, in O(n)
// to build and O(fan) to ask, where a map of every edge would cost the whole soup.
class FewFans {
 public:
  FewFans(std::size_t num_points, const std::vector<std::size_t>& vertices,
          const std::vector<Polygon>& polygons, const std::vector<char>& keep)
      : polygons_(polygons), keep_(keep), slot_(num_points, kNone) {
    for (const std::size_t v : vertices) {
      if (slot_[v] != kNone) continue;
      slot_[v] = fans_.size();
      fans_.emplace_back();
    }
    for (std::size_t t = 0; t < polygons.size(); ++t) {
      if (!keep[t]) continue;
      for (const std::size_t v : polygons[t]) Add(v, t);
    }
  }

  // Triangle t now has vertex v (ignored for a vertex not in the set).
  void Add(std::size_t v, std::size_t t) {
    if (slot_[v] != kNone) fans_[slot_[v]].push_back(t);
  }
  void Remove(std::size_t v, std::size_t t) {
    if (slot_[v] == kNone) return;
    std::vector<std::size_t>& fan = fans_[slot_[v]];
    fan.erase(std::remove(fan.begin(), fan.end(), t), fan.end());
  }
  // The live triangles at v, which must be in the set (some may have died since).
  std::vector<std::size_t>& at(std::size_t v) { return fans_[slot_[v]]; }
  // The live triangles other than `except` with both u (in the set) and v.
  std::vector<std::size_t> With(std::size_t u, std::size_t v, std::size_t except) {
    std::vector<std::size_t> out;
    for (const std::size_t t : at(u)) {
      if (t != except && keep_[t] && Has(polygons_[t], v)) out.push_back(t);
    }
    return out;
  }
  // The vertices other than v of the live triangles at v, sorted, each once.
  std::vector<std::size_t> Neighbours(std::size_t v) {
    std::vector<std::size_t> out;
    for (const std::size_t t : at(v)) {
      if (!keep_[t]) continue;
      for (const std::size_t w : polygons_[t]) {
        if (w != v) out.push_back(w);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  static constexpr std::size_t kNone = ~std::size_t{0};

 private:
  const std::vector<Polygon>& polygons_;
  const std::vector<char>& keep_;
  std::vector<std::size_t> slot_;  // a vertex's fan in fans_, or kNone
  std::vector<std::vector<std::size_t>> fans_;
};

// Step 3's degenerate triangles, removed (keep 0) and mended where that keeps the soup
// as closed as it was: a needle's short edge is collapsed (its second end welded into
// its first, which removes the triangle across it too), if the edge has two triangles and
// the ends share no neighbour but those triangles' third vertices (else the weld would
// pinch the surface); a cap's vertex splits the one triangle across its longest edge
// (each half keeps its CAD face, the new corner's normal is interpolated along the
// edge), so the cap's two short edges find that triangle's halves where the cap had
// been. What cannot be mended is removed as it is, and step 6 reports what it opens.
// O(n) when nothing is degenerate; else one more O(n) pass per kind, and each mend
// O(fans round it); a cap whose long edge has another cap across waits for it.
void MendDegenerate(const std::vector<Point>& points, double needle_tolerance,
                    std::vector<Polygon>* polygons, std::vector<std::int32_t>* faces,
                    std::vector<std::array<Vec3, 3>>* corner_normals, std::vector<char>* keep,
                    RepairReport* r) {
  std::vector<Polygon>& tri = *polygons;
  const auto remove = [&](std::size_t t) {
    (*keep)[t] = 0;
    ++r->removed_degenerate;
  };
  std::vector<std::size_t> needles, caps;
  for (std::size_t t = 0; t < tri.size(); ++t) {
    switch (ShapeOf(points, tri[t], needle_tolerance)) {
      case Shape::kSound:
        break;
      case Shape::kRepeated:
        remove(t);
        break;
      case Shape::kNeedle:
        needles.push_back(t);
        break;
      case Shape::kCap:
        caps.push_back(t);
        break;
    }
  }

  // needles: their short edges collapsed, one after another
  std::vector<std::size_t> changed;  // triangles a weld moved: looked at again below
  if (!needles.empty()) {
    std::vector<std::size_t> corners;
    for (const std::size_t t : needles) corners.insert(corners.end(), tri[t].begin(), tri[t].end());
    FewFans fans(points.size(), corners, tri, *keep);
    for (const std::size_t t : needles) {
      int shortest = 0;
      if (!(*keep)[t] || ShapeOf(points, tri[t], needle_tolerance, &shortest) != Shape::kNeedle) {
        continue;  // gone with an earlier weld, or changed by one: looked at again below
      }
      const std::size_t stays = tri[t][shortest], goes = tri[t][(shortest + 1) % 3];
      const std::vector<std::size_t> on = fans.With(stays, goes, FewFans::kNone);
      if (on.size() != 2) continue;
      std::vector<std::size_t> third;
      for (const std::size_t s : on) {
        for (const std::size_t w : tri[s]) {
          if (w != stays && w != goes) third.push_back(w);
        }
      }
      std::sort(third.begin(), third.end());
      std::vector<std::size_t> shared;
      const std::vector<std::size_t> a = fans.Neighbours(stays), b = fans.Neighbours(goes);
      std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
      shared.erase(std::remove_if(shared.begin(), shared.end(),
                                  [&](std::size_t w) { return w == stays || w == goes; }),
                   shared.end());
      if (shared != third) continue;
      for (const std::size_t s : fans.at(goes)) {
        if (!(*keep)[s]) continue;
        for (std::size_t& w : tri[s]) w = w == goes ? stays : w;
        if (ShapeOf(points, tri[s], needle_tolerance) == Shape::kRepeated) {
          remove(s);
        } else {
          fans.Add(stays, s);
          changed.push_back(s);
        }
      }
      fans.at(goes).clear();
      ++r->collapsed_needles;
    }
  }

  // what is left degenerate is a cap, or a needle that could not be collapsed
  caps.insert(caps.end(), needles.begin(), needles.end());
  caps.insert(caps.end(), changed.begin(), changed.end());
  std::sort(caps.begin(), caps.end());
  caps.erase(std::unique(caps.begin(), caps.end()), caps.end());
  std::vector<std::size_t> open_caps;
  for (const std::size_t t : caps) {
    if (!(*keep)[t]) continue;
    switch (ShapeOf(points, tri[t], needle_tolerance)) {
      case Shape::kSound:
        break;
      case Shape::kCap:
        open_caps.push_back(t);
        break;
      default:
        remove(t);
        break;
    }
  }
  if (open_caps.empty()) return;

  // caps: each splits the triangle across its longest edge at its vertex
  std::vector<std::size_t> corners;
  for (const std::size_t t : open_caps) corners.insert(corners.end(), tri[t].begin(), tri[t].end());
  FewFans fans(points.size(), corners, tri, *keep);
  std::vector<char> is_cap(tri.size(), 0);
  for (const std::size_t t : open_caps) is_cap[t] = 1;
  std::unordered_map<std::size_t, std::vector<std::size_t>> waiting;  // cap -> caps on it
  std::vector<std::size_t> todo(open_caps.rbegin(), open_caps.rend());
  const auto settle = [&](std::size_t cap) {  // removed: mended or not
    is_cap[cap] = 0;
    remove(cap);
    const auto found = waiting.find(cap);
    if (found == waiting.end()) return;
    todo.insert(todo.end(), found->second.begin(), found->second.end());
    waiting.erase(found);
  };
  while (!todo.empty()) {
    const std::size_t cap = todo.back();
    todo.pop_back();
    if (!(*keep)[cap] || !is_cap[cap]) continue;
    int longest = 0;
    ShapeOf(points, tri[cap], needle_tolerance, nullptr, &longest);
    const std::size_t u = tri[cap][longest], v = tri[cap][(longest + 1) % 3];
    const std::size_t tip = tri[cap][(longest + 2) % 3];
    const std::vector<std::size_t> across = fans.With(u, v, cap);
    const auto other_cap =
        std::find_if(across.begin(), across.end(), [&](std::size_t t) { return is_cap[t] != 0; });
    if (other_cap != across.end()) {
      if (across.size() <= 2) {  // a cap of the chain: mended, or not, before this one
        waiting[*other_cap].push_back(cap);
        continue;
      }
    } else if (across.size() == 1) {
      const std::size_t n = across[0];
      const Polygon whole = tri[n];
      const int i = whole[0] != u && whole[0] != v ? 1 : (whole[1] != u && whole[1] != v ? 2 : 0);
      // the long edge is whole[i] -> whole[i + 1]; the halves keep whole's winding
      Polygon first = whole, second = whole;
      first[(i + 1) % 3] = tip;
      second[i] = tip;
      if (!Has(whole, tip) && ShapeOf(points, first, needle_tolerance) == Shape::kSound &&
          ShapeOf(points, second, needle_tolerance) == Shape::kSound) {
        const std::size_t half = tri.size();
        tri[n] = first;
        tri.push_back(second);
        faces->push_back((*faces)[n]);
        keep->push_back(1);
        is_cap.push_back(0);
        if (!corner_normals->empty()) {
          // the CAD surface's normal at the tip, from those at the edge's ends: exact on
          // a sphere or a cylinder
          const std::array<Vec3, 3> old = (*corner_normals)[n];
          const Vec3 a = ToVec(points[whole[i]]), b = ToVec(points[whole[(i + 1) % 3]]);
          const double s =
              std::clamp((ToVec(points[tip]) - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
          const Vec3 blend = (1.0 - s) * old[i] + s * old[(i + 1) % 3];
          const double length = blend.norm();
          const Vec3 normal = std::isfinite(length) && length > 1e-6
                                  ? Vec3(blend / length)
                                  : old[s < 0.5 ? i : (i + 1) % 3];  // opposite: the nearer end's
          (*corner_normals)[n][(i + 1) % 3] = normal;
          std::array<Vec3, 3> halved = old;
          halved[i] = normal;
          corner_normals->push_back(halved);
        }
        fans.Remove(whole[(i + 1) % 3], n);
        fans.Add(tip, n);
        for (const std::size_t w : second) fans.Add(w, half);
        ++r->split_caps;
      }
    }
    settle(cap);
  }
  for (const std::size_t t : open_caps) {  // caps that waited on each other
    if ((*keep)[t] && is_cap[t]) remove(t);
  }
}

}  // namespace

std::string RepairReport::Describe() const {
  std::ostringstream out;
  out << output_triangles << " of " << input_triangles << " triangles kept";
  auto item = [&](std::size_t n, const char* what) {
    if (n > 0) out << "; " << n << ' ' << what;
  };
  item(removed_nonfinite, "with a non-finite vertex removed");
  item(merged_vertices, "duplicate vertices merged");
  item(welded_vertices, "of them welded across open edges");
  item(removed_degenerate, "degenerate or needle triangles removed");
  item(collapsed_needles, "needles collapsed (the two ends of the short edge welded)");
  item(split_caps, "caps mended (the triangle across the long edge split at the tip)");
  item(removed_duplicates, "duplicate triangles removed");
  item(reoriented, "triangles reoriented");
  item(inside_out_shells, "closed shells wound inside out turned round");
  item(non_manifold_edges, "non-manifold edges split");
  item(non_manifold_vertices, "non-manifold vertices split");
  if (boundary_edges > 0) {
    out << "; NOT REPAIRED: " << boundary_edges
        << " open edges (holes or cracks between faces) remain";
  } else {
    out << "; closed";
  }
  return out.str();
}

TriangleSoup RepairSoup(const TriangleSoup& soup, const RepairOptions& options,
                        RepairReport* report) {
  RepairReport r;
  r.input_vertices = soup.vertices.size();
  r.input_triangles = soup.triangles.size();
  const std::size_t n = soup.triangles.size();
  if (soup.cad_faces.size() != n ||
      (!soup.corner_normals.empty() && soup.corner_normals.size() != n)) {
    throw std::invalid_argument("mesh repair: " + std::to_string(soup.cad_faces.size()) +
                                " CAD face ids and " + std::to_string(soup.corner_normals.size()) +
                                " corner-normal triples for " + std::to_string(n) + " triangles");
  }
  if (!(options.weld_tolerance >= 0.0) || !(options.needle_tolerance >= 0.0)) {
    throw std::invalid_argument("mesh repair: tolerances must be >= 0");
  }
  const bool normals = !soup.corner_normals.empty();

  // 1. triangles with a non-finite vertex go; the rest keep only finite vertices
  std::vector<std::int64_t> remap(soup.vertices.size(), -1);
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  std::vector<std::int32_t> faces;
  std::vector<std::array<Vec3, 3>> corner_normals;
  polygons.reserve(n);
  faces.reserve(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = soup.triangles[t];
    bool finite = true;
    for (std::int32_t v : tri) {
      if (v < 0 || static_cast<std::size_t>(v) >= soup.vertices.size()) {
        throw std::invalid_argument("mesh repair: triangle " + std::to_string(t) +
                                    " has vertex index " + std::to_string(v) + ", out of range");
      }
      finite = finite && soup.vertices[v].allFinite();
    }
    if (soup.cad_faces[t] < 0) {
      throw std::invalid_argument("mesh repair: triangle " + std::to_string(t) +
                                  " has a negative CAD face id");
    }
    if (!finite) {
      ++r.removed_nonfinite;
      continue;
    }
    Polygon p{};
    for (int k = 0; k < 3; ++k) {
      std::int64_t& id = remap[tri[k]];
      if (id < 0) {
        id = static_cast<std::int64_t>(points.size());
        const Vec3& v = soup.vertices[tri[k]];
        points.emplace_back(v.x(), v.y(), v.z());
      }
      p[k] = static_cast<std::size_t>(id);
    }
    polygons.push_back(std::move(p));
    faces.push_back(soup.cad_faces[t]);
    if (normals) corner_normals.push_back(soup.corner_normals[t]);
  }
  if (polygons.empty()) {
    throw std::invalid_argument("mesh repair: no triangle has three finite vertices (" +
                                std::to_string(n) + " triangles)");
  }
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Point& p : points) {
    lo = lo.cwiseMin(ToVec(p));
    hi = hi.cwiseMax(ToVec(p));
  }
  const double diagonal = (hi - lo).norm();

  // 2. duplicates, then welds across open edges
  r.merged_vertices = MergeDuplicatePoints(&points, &polygons);
  r.welded_vertices = WeldOpenEdges(points, &polygons, options.weld_tolerance * diagonal);
  r.merged_vertices += r.welded_vertices;

  // 3. degenerate and duplicate triangles
  std::vector<char> keep(polygons.size(), 1);
  MendDegenerate(points, options.needle_tolerance, &polygons, &faces, &corner_normals, &keep, &r);
  {
    std::vector<std::pair<std::array<std::size_t, 3>, std::size_t>> keys;
    for (std::size_t t = 0; t < polygons.size(); ++t) {
      if (!keep[t]) continue;
      std::array<std::size_t, 3> key = {polygons[t][0], polygons[t][1], polygons[t][2]};
      std::sort(key.begin(), key.end());
      keys.push_back({key, t});
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 1; i < keys.size(); ++i) {
      if (keys[i].first == keys[i - 1].first) {
        keep[keys[i].second] = 0;
        ++r.removed_duplicates;
      }
    }
  }
  std::size_t kept = 0;
  for (std::size_t t = 0; t < polygons.size(); ++t) {
    if (!keep[t]) continue;
    if (kept != t) polygons[kept] = std::move(polygons[t]);  // a self-move would empty it
    faces[kept] = faces[t];
    if (normals) corner_normals[kept] = corner_normals[t];
    ++kept;
  }
  polygons.resize(kept);
  faces.resize(kept);
  if (normals) corner_normals.resize(kept);
  if (polygons.empty()) throw std::invalid_argument("mesh repair: every triangle is degenerate");

  // 4. consistent orientation; CGAL splits non-manifold edges and vertices
  for (const auto& [edge, count] : CountEdges(polygons)) {
    if (count > 2) ++r.non_manifold_edges;
  }
  const std::vector<Polygon> before = polygons;
  std::vector<std::size_t> original(points.size());
  for (std::size_t v = 0; v < original.size(); ++v) original[v] = v;
  OrientationVisitor visitor;
  visitor.non_manifold_vertices = &r.non_manifold_vertices;
  visitor.original = &original;
  PMP::orient_polygon_soup(points, polygons, CGAL::parameters::visitor(visitor));
  for (std::size_t t = 0; t < polygons.size(); ++t) {
    // which corner of the triangle before is each corner now
    std::array<int, 3> from{};
    for (int k = 0; k < 3; ++k) {
      const std::size_t v =
          polygons[t][k] < original.size() ? original[polygons[t][k]] : polygons[t][k];
      from[k] = v == before[t][0] ? 0 : (v == before[t][1] ? 1 : 2);
    }
    const bool flipped = (from[1] - from[0] + 3) % 3 != 1;
    if (flipped) ++r.reoriented;
    if (normals) {
      const std::array<Vec3, 3> old = corner_normals[t];
      for (int k = 0; k < 3; ++k) corner_normals[t][k] = old[from[k]];
    }
  }

  // 5. parts wound inside out turned round; 6. what is still open
  const EdgeCounts edges = CountEdges(polygons);
  r.inside_out_shells = TurnInsideOutShells(points, edges, &polygons, &corner_normals);
  for (const auto& [edge, count] : edges) {
    if (count == 1) ++r.boundary_edges;
  }

  // vertices numbered in the order the triangles first use them (the input's may be
  // any, an STL's has none): a triangle's neighbours then find their vertices nearby in
  // memory, which the servo tick feels on big meshes; unused vertices are dropped
  TriangleSoup out;
  std::vector<std::int32_t> renumber(points.size(), -1);
  out.vertices.reserve(points.size());
  out.triangles.reserve(polygons.size());
  for (const Polygon& p : polygons) {
    std::array<std::int32_t, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      std::int32_t& id = renumber[p[k]];
      if (id < 0) {
        id = static_cast<std::int32_t>(out.vertices.size());
        out.vertices.push_back(ToVec(points[p[k]]));
      }
      tri[k] = id;
    }
    out.triangles.push_back(tri);
  }
  out.cad_faces = std::move(faces);
  out.corner_normals = std::move(corner_normals);
  r.output_triangles = out.triangles.size();
  if (report != nullptr) *report = r;
  return out;
}

}  // namespace hapticad
