// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: TriangleMesh::CalcShadingNormal runs on the servo tick (Build does not).
#include "hapticad/core/geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "hapticad/core/geometry/vertex_buckets.h"

namespace hapticad {
namespace {

std::string Describe(const char* what, std::size_t index, const std::string& problem) {
  std::ostringstream out;
  out << "triangle mesh: " << what << ' ' << index << ": " << problem;
  return out.str();
}

bool IsFinite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

}  // namespace

TriangleMesh::TriangleMesh() = default;
TriangleMesh::~TriangleMesh() = default;

std::unique_ptr<TriangleMesh> TriangleMesh::Build(
    const std::vector<Vec3>& vertices_l, const std::vector<std::array<std::int32_t, 3>>& triangles,
    const std::vector<std::int32_t>& cad_faces,
    const std::vector<std::array<Vec3, 3>>& corner_normals) {
  // check shapes first, so a bad input leaves nothing half-built
  if (triangles.empty()) throw std::invalid_argument("triangle mesh: no triangles");
  // edges are numbered 3t + k in 32 bits
  if (triangles.size() > std::numeric_limits<std::uint32_t>::max() / 3) {
    throw std::invalid_argument("triangle mesh: more than " +
                                std::to_string(std::numeric_limits<std::uint32_t>::max() / 3) +
                                " triangles");
  }
  if (cad_faces.size() != triangles.size()) {
    throw std::invalid_argument("triangle mesh: " + std::to_string(cad_faces.size()) +
                                " CAD face ids for " + std::to_string(triangles.size()) +
                                " triangles");
  }
  if (!corner_normals.empty() && corner_normals.size() != triangles.size()) {
    throw std::invalid_argument("triangle mesh: " + std::to_string(corner_normals.size()) +
                                " corner-normal triples for " + std::to_string(triangles.size()) +
                                " triangles");
  }
  for (std::size_t v = 0; v < vertices_l.size(); ++v) {
    if (!IsFinite(vertices_l[v])) throw std::invalid_argument(Describe("vertex", v, "not finite"));
  }
  const auto num_vertices = static_cast<std::int64_t>(vertices_l.size());
  std::int32_t max_face = -1;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (std::int32_t v : triangles[t]) {
      if (v < 0 || v >= num_vertices) {
        throw std::invalid_argument(
            Describe("triangle", t, "vertex index " + std::to_string(v) + " out of range"));
      }
    }
    const auto& tri = triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      throw std::invalid_argument(Describe("triangle", t, "repeats a vertex"));
    }
    if (cad_faces[t] < 0)
      throw std::invalid_argument(Describe("triangle", t, "negative CAD face id"));
    max_face = std::max(max_face, cad_faces[t]);
    if (!corner_normals.empty()) {
      for (const Vec3& n : corner_normals[t]) {
        if (!IsFinite(n) || n.squaredNorm() < 0.25) {
          throw std::invalid_argument(Describe("triangle", t, "corner normal not a unit vector"));
        }
      }
    }
  }

  std::unique_ptr<TriangleMesh> mesh(new TriangleMesh());
  mesh->points_.assign(vertices_l.begin(), vertices_l.end());
  const auto n = static_cast<std::uint32_t>(triangles.size());
  mesh->triangles_.resize(n);
  mesh->cad_faces_.assign(cad_faces.begin(), cad_faces.end());
  mesh->face_normals_.resize(n);
  mesh->corner_normals_.reserve(3 * corner_normals.size());
  for (std::uint32_t t = 0; t < n; ++t) {
    const auto& tri = triangles[t];
    mesh->triangles_[t] = {static_cast<std::uint32_t>(tri[0]), static_cast<std::uint32_t>(tri[1]),
                           static_cast<std::uint32_t>(tri[2])};
    const Vec3 normal =
        (vertices_l[tri[1]] - vertices_l[tri[0]]).cross(vertices_l[tri[2]] - vertices_l[tri[0]]);
    const double len = normal.norm();
    mesh->face_normals_[t] = len > 0.0 ? Vec3(normal / len) : Vec3::Zero();
    if (!corner_normals.empty()) {
      for (const Vec3& c : corner_normals[t])
        mesh->corner_normals_.push_back(c.normalized().cast<float>());
    }
  }
  mesh->BuildConnectivity();
  mesh->num_cad_faces_ = max_face + 1;
  for (const Vec3& p : mesh->points_) {
    mesh->bounding_radius_ = std::max(mesh->bounding_radius_, p.norm());
  }
  return mesh;
}

void TriangleMesh::BuildConnectivity() {
  const auto n = static_cast<std::uint32_t>(triangles_.size());
  const auto num_vertices = static_cast<std::uint32_t>(points_.size());
  // Edge k of triangle t (half-edge 3t + k) runs from corner k to corner k + 1. The
  // half-edges grouped by the vertex they start from: one per triangle at the vertex.
  VertexBuckets<std::uint32_t> out = BucketByVertex<std::uint32_t>(
      num_vertices, 3 * std::size_t{n}, [this](std::size_t h) { return triangles_[h / 3][h % 3]; },
      [](std::size_t h) { return static_cast<std::uint32_t>(h); });
  const auto end_of = [this](std::uint32_t h) { return triangles_[h / 3][(h % 3 + 1) % 3]; };
  // each vertex's edges sorted by where they lead (then by triangle): a repeated edge
  // sits next to its twin, and the edge back is found by a binary search, so a vertex
  // of high valence (the centre of a fan-tessellated disc) costs n log n, not n^2
  const auto by_end = [&end_of](std::uint32_t g, std::uint32_t h) {
    const std::uint32_t eg = end_of(g), eh = end_of(h);
    return eg != eh ? eg < eh : g < h;
  };
  for (std::uint32_t v = 0; v < num_vertices; ++v) {
    std::sort(out.begin(v), out.end(v), by_end);
  }

  // Across each edge a -> b, the triangle whose edge runs b -> a. The same edge twice
  // (in input order, so the later triangle is named) is no manifold.
  across_.assign(n, {kNone, kNone, kNone});
  closed_ = true;
  std::uint32_t worst = kNone;  // the first triangle that repeats an edge
  std::uint32_t worst_other = kNone;
  for (std::uint32_t a = 0; a < num_vertices; ++a) {
    for (auto i = out.begin(a); i + 1 < out.end(a); ++i) {
      if (end_of(i[0]) == end_of(i[1]) && i[1] / 3 < worst) {
        worst = i[1] / 3;
        worst_other = i[0] / 3;
      }
    }
  }
  for (std::uint32_t h = 0; h < 3 * n; ++h) {
    const std::uint32_t t = h / 3;
    const std::uint32_t a = triangles_[t][h % 3];
    const std::uint32_t b = end_of(h);
    const auto back = std::partition_point(out.begin(b), out.end(b),
                                           [&](std::uint32_t g) { return end_of(g) < a; });
    if (back != out.end(b) && end_of(*back) == a) across_[t][h % 3] = *back / 3;
    closed_ = closed_ && across_[t][h % 3] != kNone;
  }
  if (worst != kNone) {
    throw std::invalid_argument(Describe(
        "triangle", worst,
        "has an edge that runs the same way in triangle " + std::to_string(worst_other) +
            ": a non-manifold edge or neighbours wound against each other (repair the mesh "
            "first)"));
  }

  // Round each vertex, one fan: from a triangle at v, across the edge out of v and back
  // across the edge into v, every triangle at v is reached.
  for (std::uint32_t v = 0; v < num_vertices; ++v) {
    const auto count = static_cast<std::uint32_t>(out.end(v) - out.begin(v));
    if (count == 0) continue;
    const std::uint32_t start = *out.begin(v) / 3;
    const auto corner = [this, v](std::uint32_t t) {
      const auto& tri = triangles_[t];
      return tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    };
    std::uint32_t reached = 1;
    std::uint32_t t = start;
    bool open = false;
    while (reached <= count) {
      t = across_[t][corner(t)];  // across the edge out of v
      if (t == kNone) {
        open = true;
        break;
      }
      if (t == start) break;
      ++reached;
    }
    if (open) {
      for (t = start; reached <= count;) {
        t = across_[t][(corner(t) + 2) % 3];  // across the edge into v
        if (t == kNone) break;
        ++reached;
      }
    }
    if (reached != count) {
      throw std::invalid_argument(
          Describe("vertex", v,
                   "its triangles form more than one fan: a non-manifold vertex (repair the mesh "
                   "first)"));
    }
  }
}

Vec3 TriangleMesh::CalcShadingNormal(std::uint32_t t, const Vec3& point_l) const {
  if (corner_normals_.empty()) return face_normals_[t];
  const auto& tri = triangles_[t];
  const Vec3* p = points_.data();
  const Vec3 e1 = p[tri[1]] - p[tri[0]];
  const Vec3 e2 = p[tri[2]] - p[tri[0]];
  const Vec3 w = point_l - p[tri[0]];
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return face_normals_[t];
  // barycentrics of the point's projection, clamped so a point a hair outside blends
  // like the nearest edge
  double u = std::max((d22 * w.dot(e1) - d12 * w.dot(e2)) / det, 0.0);
  double v = std::max((d11 * w.dot(e2) - d12 * w.dot(e1)) / det, 0.0);
  const double sum = u + v;
  if (sum > 1.0) {
    u /= sum;
    v /= sum;
  }
  const Vec3 n =
      (1.0 - u - v) * corner_normal(t, 0) + u * corner_normal(t, 1) + v * corner_normal(t, 2);
  const double len = n.norm();
  return len > 1e-6 ? Vec3(n / len) : face_normals_[t];
}

std::size_t TriangleMesh::CalcMemoryBytes() const {
  std::size_t bytes = points_.capacity() * sizeof(Vec3);
  bytes += triangles_.capacity() * sizeof(triangles_[0]);
  bytes += cad_faces_.capacity() * sizeof(std::int32_t);
  bytes += across_.capacity() * sizeof(across_[0]);
  bytes += face_normals_.capacity() * sizeof(Vec3);
  bytes += corner_normals_.capacity() * sizeof(Eigen::Vector3f);
  return bytes;
}

}  // namespace hapticad
