// SPDX-License-Identifier: GPL-3.0-or-later
// Segment against triangle and against box: the leaf and node tests of the proxy's
// first-hit query. Header-only, branch-light, no allocation: safe on the servo tick.
//
// The segment is p(s) = a + s d for s in [0, s_max]. Units: any, consistently.
#pragma once

#include <cmath>
#include <utility>

#include "hapticad/core/vec3.h"

namespace hapticad {

// Hit of a segment with a triangle: s along the segment, (u, w) barycentrics of v1, v2.
struct SegmentTriangleHit {
  double s;
  double u;
  double w;
};

// Möller–Trumbore with an inclusive barycentric tolerance `bary_tol` (dimensionless),
// so a segment through the shared edge of two triangles hits at least one of them.
// Returns false for a segment parallel to the triangle's plane or a degenerate triangle.
inline bool IntersectSegmentTriangle(const Vec3& a, const Vec3& d, double s_max, const Vec3& v0,
                                     const Vec3& v1, const Vec3& v2, double bary_tol,
                                     SegmentTriangleHit* hit) {
  const Vec3 e1 = v1 - v0;
  const Vec3 e2 = v2 - v0;
  const Vec3 pvec = d.cross(e2);
  const double det = e1.dot(pvec);
  // parallel test relative to the sizes involved, so it is unit-free
  const double scale = d.norm() * e1.norm() * e2.norm();
  if (!(std::abs(det) > 1e-14 * scale)) return false;
  const double inv_det = 1.0 / det;
  const Vec3 tvec = a - v0;
  const double u = tvec.dot(pvec) * inv_det;
  if (u < -bary_tol || u > 1.0 + bary_tol) return false;
  const Vec3 qvec = tvec.cross(e1);
  const double w = d.dot(qvec) * inv_det;
  if (w < -bary_tol || u + w > 1.0 + bary_tol) return false;
  const double s = e2.dot(qvec) * inv_det;
  if (s < 0.0 || s > s_max) return false;
  hit->s = s;
  hit->u = u;
  hit->w = w;
  return true;
}

// A segment prepared for many box tests: its start and the inverse of its direction
// (the divisions done once per query, not once per box).
struct SegmentRay {
  SegmentRay(const Vec3& a_in, const Vec3& d) : a(a_in) {
    for (int k = 0; k < 3; ++k) {
      parallel[k] = d[k] == 0.0;
      inv_d[k] = parallel[k] ? 0.0 : 1.0 / d[k];
    }
  }
  Vec3 a;
  double inv_d[3];
  bool parallel[3];
};

// Slab test of the segment against the box [lo, hi] grown by `pad` on every side, for
// s in [0, s_max]. Returns the entry parameter in *s_entry. A zero component of the
// direction is handled without dividing by it.
inline bool IntersectSegmentBox(const SegmentRay& ray, double s_max, const double lo[3],
                                const double hi[3], double pad, double* s_entry) {
  double s0 = 0.0;
  double s1 = s_max;
  for (int k = 0; k < 3; ++k) {
    const double l = lo[k] - pad;
    const double h = hi[k] + pad;
    if (ray.parallel[k]) {
      if (ray.a[k] < l || ray.a[k] > h) return false;
      continue;
    }
    double t0 = (l - ray.a[k]) * ray.inv_d[k];
    double t1 = (h - ray.a[k]) * ray.inv_d[k];
    if (t0 > t1) std::swap(t0, t1);
    s0 = t0 > s0 ? t0 : s0;
    s1 = t1 < s1 ? t1 : s1;
    if (s0 > s1) return false;
  }
  *s_entry = s0;
  return true;
}

}  // namespace hapticad
