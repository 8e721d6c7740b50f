// SPDX-License-Identifier: GPL-3.0-or-later
// SweepSearch: the state of one first-contact query while candidate triangles are fed
// to it, whatever chooses them (ConvexPieces' look round the last contact, then, if that
// proves nothing, TriangleTree's or TriangleGrid's walk).
//
// It keeps the nearest contact so far and what that proves: hits beyond it are not
// looked for (`best_s`), and triangles entirely under a floor are skipped without a
// contact test. The floors are the query's own (the proxy's constraint planes lowered by
// its radius) and the plane through the best contact so far, across its normal: until
// that contact the query stays at least its radius in front of that plane.
//
// Header-only, no allocation: servo-tick safe. Units: the mesh's.
#pragma once

#include <cstdint>

#include "hapticad/core/geometry/segment_triangle.h"
#include "hapticad/core/geometry/sphere_triangle.h"
#include "hapticad/core/geometry/sweep_query.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

class SweepSearch {
 public:
  // Looks for contacts with s in [0, s_max] only (s_max <= 1: the part of the sweep a
  // caller has covered). Tests the query's hint first.
  SweepSearch(const TriangleMesh& mesh, const SweepQuery& q, double s_max = 1.0)
      : mesh_(mesh),
        a_(q.a),
        d_(q.b - q.a),
        radius_(q.radius),
        bary_tol_(q.bary_tol),
        piece_of_vertex_(q.piece_of_vertex),
        piece_(q.piece),
        best_s_(s_max) {
    if (q.floors != nullptr) {
      for (int i = 0; i < q.floors->count; ++i) AddFloor(q.floors->normal[i], q.floors->offset[i]);
    }
    given_floors_ = floor_count_;
    if (q.hint >= 0 && static_cast<std::size_t>(q.hint) < mesh.num_triangles()) {
      Test(static_cast<std::uint32_t>(q.hint));
    }
  }

  // The exact contact test of one triangle (two-sided), unless a floor rules it out
  // or it lies outside the query's piece.
  void Test(std::uint32_t id) {
    const auto& t = mesh_.triangle(id);
    const Vec3& v0 = mesh_.vertex(t[0]);
    const Vec3& v1 = mesh_.vertex(t[1]);
    const Vec3& v2 = mesh_.vertex(t[2]);
    for (int i = 0; i < floor_count_; ++i) {
      const Vec3& f = floor_normal_[i];
      if (f.dot(v0) <= floor_offset_[i] && f.dot(v1) <= floor_offset_[i] &&
          f.dot(v2) <= floor_offset_[i]) {
        return;
      }
    }
    // (after the floors: the servo tick's sweeps pay this branch only on the triangles
    // that reach the exact test)
    if (piece_of_vertex_ != nullptr && piece_of_vertex_[t[0]] != piece_) return;
    const Vec3& n = mesh_.face_normal(id);
    if (radius_ > 0.0) {
      SphereTriangleHit hit;
      if (SweepSphereTriangle(a_, d_, best_s_, radius_, v0, v1, v2, n, bary_tol_, &hit)) {
        Keep(id, hit.s, hit.normal);
      }
      return;
    }
    SegmentTriangleHit hit;
    if (IntersectSegmentTriangle(a_, d_, best_s_, v0, v1, v2, bary_tol_, &hit)) {
      // a point meets the side it comes from
      Keep(id, hit.s, n.dot(d_) > 0.0 ? Vec3(-n) : n);
    }
  }

  const Vec3& a() const { return a_; }
  const Vec3& d() const { return d_; }
  double radius() const { return radius_; }
  // No contact is looked for beyond this (the nearest so far, or s_max).
  double best_s() const { return best_s_; }
  bool found() const { return found_; }
  // The nearest contact so far (meaningful when found()).
  std::uint32_t best_triangle() const { return best_triangle_; }
  const Vec3& best_normal() const { return best_normal_; }
  void Report(SweepHit* hit) const {
    hit->triangle = best_triangle_;
    hit->s = best_s_;
    hit->point = a_ + best_s_ * d_;
    hit->normal = best_normal_;
  }

 private:
  void Keep(std::uint32_t id, double s, const Vec3& normal) {
    // equal s on a shared edge: keep the first found, so the result is deterministic
    if (!found_ || s < best_s_) {
      best_s_ = s;
      best_triangle_ = id;
      best_normal_ = normal;
      found_ = true;
      const Vec3 contact = a_ + s * d_ - radius_ * normal;
      floor_count_ = given_floors_;  // the new contact's plane replaces the last one's
      AddFloor(normal, normal.dot(contact));
    }
  }

  void AddFloor(const Vec3& normal, double offset) {
    if (floor_count_ == kMaxFloors) return;
    floor_normal_[floor_count_] = normal;
    floor_offset_[floor_count_] = offset;
    ++floor_count_;
  }

  static constexpr int kMaxFloors = SweepFloors::kMax + 1;

  const TriangleMesh& mesh_;
  const Vec3 a_;
  const Vec3 d_;
  const double radius_;
  const double bary_tol_;
  const std::uint32_t* const piece_of_vertex_;
  const std::uint32_t piece_;
  double best_s_;
  std::uint32_t best_triangle_ = 0;
  Vec3 best_normal_ = Vec3::Zero();
  bool found_ = false;
  Vec3 floor_normal_[kMaxFloors];
  double floor_offset_[kMaxFloors];
  int floor_count_ = 0;
  int given_floors_ = 0;
};

}  // namespace hapticad
