// SPDX-License-Identifier: GPL-3.0-or-later
// TriangleMesh: the scene's surface as a manifold triangle mesh in flat arrays: per
// triangle its vertex triple, the CAD face it came from, the triangles across its edges,
// its unit normal (doubles: the plane tests of the proxy need them exact) and, when the
// tessellator gave them, the exact surface normal at each corner (floats: they only
// shade, and 1e-7 rad is plenty).
//
// Manifold: every edge runs each way in at most one triangle (so no edge has more than
// two, and neighbours agree on their winding), and the triangles round every vertex
// form one fan, open or closed. That is what the contact engine relies on (a walk
// round a vertex sees all of its triangles) and what RepairSoup produces. The
// connectivity is built here, by a counting sort of the edges, rather than in a
// half-edge library: a 1M-triangle scene then holds 12 bytes per triangle of it, not
// some 70 (BENCHMARKS.md).
//
// Frame and units: the scene's local frame, metres (see HapticScene).
// Built once, before the servo loop; immutable afterwards. Accessors are cheap and
// safe on the servo tick.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "hapticad/core/huge_page_allocator.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

class TriangleMesh {
 public:
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};

  // Builds the mesh. `vertices_l` in the local frame (metres); `triangles`, `cad_faces`
  // and `corner_normals` as in TriangleSoup. Throws std::invalid_argument naming the
  // first offending triangle or vertex: index out of range, a repeated vertex,
  // non-finite coordinate, negative CAD face id, an edge that runs the same way in two
  // triangles (a non-manifold edge, or neighbours wound against each other), a vertex
  // whose triangles form more than one fan (a non-manifold vertex).
  static std::unique_ptr<TriangleMesh> Build(
      const std::vector<Vec3>& vertices_l,
      const std::vector<std::array<std::int32_t, 3>>& triangles,
      const std::vector<std::int32_t>& cad_faces,
      const std::vector<std::array<Vec3, 3>>& corner_normals);

  std::size_t num_triangles() const { return triangles_.size(); }
  std::size_t num_vertices() const { return points_.size(); }

  const Vec3& vertex(std::uint32_t v) const { return points_[v]; }
  const Vec3* points() const { return points_.data(); }
  const std::array<std::uint32_t, 3>& triangle(std::uint32_t t) const { return triangles_[t]; }
  const std::array<std::uint32_t, 3>* triangles() const { return triangles_.data(); }
  std::int32_t cad_face(std::uint32_t t) const { return cad_faces_[t]; }
  const std::int32_t* cad_faces() const { return cad_faces_.data(); }
  std::int32_t num_cad_faces() const { return num_cad_faces_; }
  // The triangles across the edges of triangle t: entry k across edge k, which runs from
  // corner k to corner k + 1 (mod 3); kNone across an open edge.
  const std::array<std::uint32_t, 3>& across(std::uint32_t t) const { return across_[t]; }
  // Whether every edge has two triangles: the surface bounds a volume, so a point is
  // inside or outside it (an odd or even number of crossings on a ray out).
  bool closed() const { return closed_; }
  // The largest distance of a vertex from the local origin (metres): a ray from p
  // longer than |p| plus this has left the mesh.
  double bounding_radius() const { return bounding_radius_; }

  // Unit normal from the winding (v1 - v0) x (v2 - v0); zero for a degenerate triangle.
  const Vec3& face_normal(std::uint32_t t) const { return face_normals_[t]; }

  bool has_corner_normals() const { return !corner_normals_.empty(); }
  // Unit normal at corner `corner` (0..2) of triangle `t`. Precondition: has_corner_normals().
  Vec3 corner_normal(std::uint32_t t, int corner) const {
    return corner_normals_[3 * t + corner].cast<double>();
  }
  // The shading normal at `point_l` (on or near triangle t): the corner normals blended
  // by the point's barycentric coordinates (clamped to the triangle), unit. The face
  // normal when there are no corner normals. Servo-tick safe.
  Vec3 CalcShadingNormal(std::uint32_t t, const Vec3& point_l) const;

  // Cache warming for the servo tick, prefetch instructions only: everything a tick
  // reads of triangle t but its vertices (its corners, normal, CAD face, neighbours and
  // corner normals), and, once its corners are in the cache, its vertices.
  void PrefetchTriangle(std::uint32_t t) const {
    __builtin_prefetch(&triangles_[t]);
    __builtin_prefetch(&face_normals_[t]);
    __builtin_prefetch(&cad_faces_[t]);
    __builtin_prefetch(&across_[t]);
    if (!corner_normals_.empty()) {
      __builtin_prefetch(&corner_normals_[3 * t]);
      __builtin_prefetch(&corner_normals_[3 * t + 2]);
    }
  }
  void PrefetchVertices(std::uint32_t t) const {
    for (const std::uint32_t v : triangles_[t]) __builtin_prefetch(&points_[v]);
  }
  // The same data read, its vertices too if `with_vertices`: the loads wait for memory,
  // but are independent of each other, so they overlap, and unlike a prefetch none is
  // dropped. Returns a word made of what was read; pass it to KeepLoads so the compiler
  // keeps the loads. Servo-tick safe.
  std::uint32_t LoadTriangle(std::uint32_t t, bool with_vertices) const {
    const auto& tri = triangles_[t];
    std::uint32_t word = tri[0] ^ static_cast<std::uint32_t>(cad_faces_[t]) ^ across_[t][0];
    word ^= static_cast<std::uint32_t>(face_normals_[t].x() > 0.0);
    if (!corner_normals_.empty()) {
      word ^= static_cast<std::uint32_t>(corner_normals_[3 * t].x() > 0.0f);
      word ^= static_cast<std::uint32_t>(corner_normals_[3 * t + 2].z() > 0.0f);
    }
    if (with_vertices) {
      for (const std::uint32_t v : tri) word ^= static_cast<std::uint32_t>(points_[v].x() > 0.0);
    }
    return word;
  }
  // Its vertices only: quick once the triangle's corners are in the cache.
  std::uint32_t LoadVertices(std::uint32_t t) const {
    std::uint32_t word = 0;
    for (const std::uint32_t v : triangles_[t]) {
      word ^= static_cast<std::uint32_t>(points_[v].x() > 0.0);
    }
    return word;
  }
  static void KeepLoads(std::uint32_t word) { asm volatile("" : : "r"(word)); }

  // Bytes held by the mesh's arrays.
  std::size_t CalcMemoryBytes() const;

  TriangleMesh(const TriangleMesh&) = delete;
  TriangleMesh& operator=(const TriangleMesh&) = delete;
  ~TriangleMesh();

 private:
  TriangleMesh();
  // Fills across_ and closed_ from triangles_; throws for a non-manifold edge or vertex.
  void BuildConnectivity();

  // Read at random by the servo tick: on huge pages (huge_page_allocator.h).
  HugePageVector<Vec3> points_;
  HugePageVector<std::array<std::uint32_t, 3>> triangles_;
  HugePageVector<std::int32_t> cad_faces_;
  HugePageVector<std::array<std::uint32_t, 3>> across_;
  HugePageVector<Vec3> face_normals_;
  HugePageVector<Eigen::Vector3f> corner_normals_;  // 3 per triangle, or none
  std::int32_t num_cad_faces_ = 0;
  bool closed_ = false;
  double bounding_radius_ = 0.0;
};

}  // namespace hapticad
