// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: swept sphere against a triangle, the leaf test of the sphere proxy's
// first-contact query. Header-only, no allocation: safe on the servo tick.
//
// The sphere's centre moves along c(s) = a + s d, s in [0, s_max]; it has radius r > 0.
// The earliest s at which the sphere touches the triangle is found exactly: on the face
// (the centre reaches the plane's slab |h| = r above the triangle's interior), on an
// edge (a capsule of radius r around it) or on a vertex (a ball of radius r).
// Triangles are two-sided: the side is the one the centre starts on.
// Units: any, consistently (the scene's local metres).
#pragma once

#include <algorithm>
#include <cmath>

#include "hapticad/core/vec3.h"

namespace hapticad {

struct SphereTriangleHit {
  double s;     // contact parameter along the sweep, in [0, s_max]
  Vec3 normal;  // unit, from the contact point on the triangle toward the centre
};

namespace sphere_sweep_detail {

// Earliest s in [0, s_max] at which |c(s) - p| = r, starting outside (|a - p| > r).
inline bool SweepPoint(const Vec3& m, const Vec3& d, double dd, double s_max, double r, double* s) {
  // |m + s d|^2 = r^2 with m = a - p
  const double b = m.dot(d);
  if (b >= 0.0) return false;  // not approaching
  const double c = m.squaredNorm() - r * r;
  const double disc = b * b - dd * c;
  if (disc < 0.0) return false;
  const double root = (-b - std::sqrt(disc)) / dd;
  if (root > s_max) return false;
  *s = std::max(root, 0.0);
  return true;
}

// Earliest s at which the sphere touches segment [p, q]. Returns the contact normal.
inline bool SweepEdge(const Vec3& a, const Vec3& d, double dd, double s_max, double r,
                      const Vec3& p, const Vec3& q, double* s_out, Vec3* normal) {
  const Vec3 e = q - p;
  const double ee = e.squaredNorm();
  const Vec3 m = a - p;
  const double me = m.dot(e);
  const double de = d.dot(e);
  // the part of m and d perpendicular to the edge: distance to the edge's line
  const Vec3 mp = m - (me / ee) * e;
  const Vec3 dp = d - (de / ee) * e;
  const double aa = dp.squaredNorm();
  const double bb = mp.dot(dp);
  const double cc = mp.squaredNorm() - r * r;
  double best = s_max;
  bool found = false;
  // the cylinder's side, when the centre approaches the line
  if (aa > 1e-30 * dd && bb < 0.0) {
    const double disc = bb * bb - aa * cc;
    if (disc >= 0.0) {
      const double s = std::max((-bb - std::sqrt(disc)) / aa, 0.0);
      const double t = (me + s * de) / ee;  // where along the edge
      if (s <= best && t >= 0.0 && t <= 1.0) {
        best = s;
        found = true;
      }
    }
  }
  // the end balls (each vertex is shared by two of the triangle's edges; cheap enough)
  double s;
  if (SweepPoint(m, d, dd, best, r, &s)) {
    best = s;
    found = true;
  }
  if (SweepPoint(a - q, d, dd, best, r, &s)) {
    best = s;
    found = true;
  }
  if (!found) return false;
  // the contact normal: from the closest point of the edge to the centre at contact
  const Vec3 c = a + best * d;
  const double t = std::clamp((c - p).dot(e) / ee, 0.0, 1.0);
  const Vec3 to_centre = c - (p + t * e);
  const double len = to_centre.norm();
  if (!(len > 0.0)) return false;
  *s_out = best;
  *normal = to_centre / len;
  return true;
}

}  // namespace sphere_sweep_detail

// Earliest contact of the swept sphere with triangle (v0, v1, v2) whose unit normal is
// `n`, for s in [0, s_max]. A sphere that already overlaps the triangle at s = 0 hits at
// s = 0 if it moves deeper, and is let go if it moves out (so a proxy that rounding put
// a hair inside can always leave). `bary_tol` widens the face test as in
// IntersectSegmentTriangle. Returns false for a degenerate triangle or no contact.
inline bool SweepSphereTriangle(const Vec3& a, const Vec3& d, double s_max, double r,
                                const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& n,
                                double bary_tol, SphereTriangleHit* hit) {
  const double dd = d.squaredNorm();
  if (!(dd > 0.0) || n.squaredNorm() == 0.0) return false;
  double h0 = n.dot(a - v0);
  const double dn = n.dot(d);
  // the side the centre starts on; exactly on the plane: the side it comes from
  const double side = h0 > 0.0 ? 1.0 : (h0 < 0.0 ? -1.0 : (dn > 0.0 ? -1.0 : 1.0));
  h0 *= side;
  const double h1 = h0 + side * dn * s_max;
  if (h0 >= r && h1 >= r) return false;  // never within r of the plane
  const Vec3 n_side = side * n;

  // the face: the centre enters the slab above the triangle's interior
  const Vec3 e1 = v1 - v0;
  const Vec3 e2 = v2 - v0;
  // Barycentrics from cross products along n: for a sliver the Gram determinant
  // |e1|^2 |e2|^2 - (e1.e2)^2 cancels to a relative error of eps / sin^2 of its angle
  // (1e-4 for a triangle a million times longer than wide), the cross product to eps / sin.
  const double area = n.dot(e1.cross(e2));  // twice the area, signed by n
  if (!(std::abs(area) > 0.0)) return false;
  auto inside = [&](const Vec3& c) {
    const Vec3 w = c - v0;  // the in-plane part decides; the normal part is orthogonal
    const double u = n.dot(w.cross(e2)) / area;
    const double v = n.dot(e1.cross(w)) / area;
    return u >= -bary_tol && v >= -bary_tol && u + v <= 1.0 + bary_tol;
  };
  const double slope = side * dn;  // dh/ds
  if (h0 >= r) {
    const double s = (h0 - r) / -slope;  // h(s) = h0 + slope s reaches r; slope < 0 here
    if (s > s_max) return false;
    const Vec3 c = a + s * d;
    if (inside(c)) {
      hit->s = s;
      hit->normal = n_side;
      return true;
    }
  } else if (inside(a)) {
    // overlapping the face already
    if (slope >= 0.0) return false;
    hit->s = 0.0;
    hit->normal = n_side;
    return true;
  }

  // the edges and vertices
  bool found = false;
  double best = s_max;
  const Vec3* v[3] = {&v0, &v1, &v2};
  for (int k = 0; k < 3; ++k) {
    double s;
    Vec3 normal;
    if (sphere_sweep_detail::SweepEdge(a, d, dd, best, r, *v[k], *v[(k + 1) % 3], &s, &normal)) {
      best = s;
      hit->s = s;
      hit->normal = normal;
      found = true;
    }
  }
  return found;
}

}  // namespace hapticad
