// SPDX-License-Identifier: GPL-3.0-or-later
// SurfaceFrame: a tangent frame fixed to a CAD face, in which face-bound effects (the
// roughness grid, the viscous grating) lay out their coordinates.
//
// The plugin takes it at the face's centre: e1 = the parametric u direction (dS/du)
// turned by the pattern angle about the outward normal, e2 = normal x e1.
//
// Planar (radius_m = 0): a point maps to (x, y) = ((p - origin) . e1, (p - origin) . e2),
// exact on planar faces and a projection on other curved ones (a grid period felt
// 1/cos(angle) longer where the face turns away from the frame's normal).
//
// Cylindrical (radius_m > 0): the face lies on the cylinder of that radius round the line
// through axis_point_w along axis_w, and the frame is unrolled on it: a point maps to
// its arc length round the cylinder from the origin (s, in (-pi R, pi R]) and its length
// along the axis (t), turned into (x, y) as (s, t) lie in the origin's tangent plane; the
// frame vectors at the point are e1 and e2 rolled round the axis with it. A grid or a
// grating keeps its period all round a handle (the seam is opposite the origin).
//
// World frame, metres.
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad {

struct SurfaceFrame {
  Vec3 origin_w = Vec3::Zero();  // on the face
  Vec3 e1_w = Vec3::UnitX();     // unit, tangent at the origin
  Vec3 e2_w = Vec3::UnitY();     // unit, orthogonal to e1_w
  // Cylindrical faces only (radius_m > 0): e1 and e2 span the axis and the direction
  // round it at the origin, which lies radius_m from the axis.
  double radius_m = 0.0;
  Vec3 axis_point_w = Vec3::Zero();
  Vec3 axis_w = Vec3::UnitZ();  // unit
};

// A point's coordinates in a SurfaceFrame and the frame's vectors there.
struct FrameCoordinates {
  double x = 0.0;  // along e1, m
  double y = 0.0;  // along e2, m
  Vec3 e1_w = Vec3::UnitX();
  Vec3 e2_w = Vec3::UnitY();
};

// Where `point_w` lies in `frame` (servo-tick safe; a non-finite point gives non-finite
// x and y, which callers treat as no effect).
FrameCoordinates CalcFrameCoordinates(const SurfaceFrame& frame, const Vec3& point_w);

// Why `frame` cannot be used ("" when it can): vectors not unit or not orthogonal, a
// non-finite origin, or a cylinder whose axis is not in the frame's tangent plane or
// whose origin is not radius_m from the axis (relative 1e-6).
const char* DescribeFrameProblem(const SurfaceFrame& frame);

}  // namespace hapticad
