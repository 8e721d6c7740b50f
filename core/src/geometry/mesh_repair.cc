// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL translation unit (walled off in hapticad_cgal).
#include "hapticad/core/geometry/mesh_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Simple_cartesian.h>

#include "hapticad/core/geometry/vertex_buckets.h"

namespace hapticad {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Polygon = std::array<std::size_t, 3>;
namespace PMP = CGAL::Polygon_mesh_processing;

Vec3 ToVec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

// Undirected edges with the number of triangles on each, sorted. A counting sort by the
// lower vertex, then each vertex's few edges sorted in place: O(n), where a sort of the
// 3n edge copies was a third of a 1M-triangle repair.
std::vector<std::pair<std::pair<std::size_t, std::size_t>, int>> CountEdges(
    const std::vector<Polygon>& polygons) {
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
  std::vector<std::pair<std::pair<std::size_t, std::size_t>, int>> counted;
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

bool Degenerate(const std::vector<Point>& points, const Polygon& p, double needle_tolerance) {
  if (p[0] == p[1] || p[1] == p[2] || p[0] == p[2]) return true;
  const Vec3 a = ToVec(points[p[0]]), b = ToVec(points[p[1]]), c = ToVec(points[p[2]]);
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const double height = (b - a).cross(c - a).norm() / longest;  // to the longest edge
  return !(height > needle_tolerance * longest);
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
  item(removed_duplicates, "duplicate triangles removed");
  item(reoriented, "triangles reoriented");
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
  for (std::size_t t = 0; t < polygons.size(); ++t) {
    if (Degenerate(points, polygons[t], options.needle_tolerance)) {
      keep[t] = 0;
      ++r.removed_degenerate;
    }
  }
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

  // 5. what is still open
  for (const auto& [edge, count] : CountEdges(polygons)) {
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
