// SPDX-License-Identifier: GPL-3.0-or-later
// User-defined curve pattern of seed 000 §2.2.3: a family of parallel curves drawn by
// the designer (a FreeCAD sketch or edge); the stripes follow the curves.
//
// The family is the base curve translated along the pattern frame's x axis, as in the
// paper's Fig. 7: every member has, at height y, the direction the base curve has at
// height y. Hence the paper's lookup table "along y": index by the contact point's y,
// read the curve's direction. HaptiCAD offers both
//   kLookupTable  the paper's table of unit tangents at `lut_size` heights, linearly
//                 interpolated and renormalised (O(1) per tick, no trigonometry);
//   kExact        the exact member through the point: solve y(t) = y_p on the NURBS
//                 (bracketed Newton; the closest point of the base curve along x).
// BENCHMARKS.md publishes table size against angle error and time.
//
// Preconditions, checked by Build() with a clear error: the curve is not degenerate
// (it spans a height) and y strictly increases or decreases along it. A curve that
// turns back or touches itself in y gives members that cross each other, so the
// stripe direction would be ambiguous: it is rejected, never evaluated.
// Outside the curve's height range the end tangents continue: every member goes on
// straight along them, stripes and grating alike (an end tangent parallel to x, which
// would make every member there one line, keeps the grating's bars along y instead).
//
// Frame and units: pattern frame (origin, x, y) in world metres; the curve in that
// frame's (x, y) coordinates, metres. Evaluate() is servo-tick safe.
#pragma once

#include <vector>

#include "hapticad/core/surfaces/nurbs_curve.h"
#include "hapticad/core/surfaces/stripe_pattern.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct PatternPlane {
  Vec3 origin_w;
  Vec3 x_w;  // unit: the family's translation axis
  Vec3 y_w;  // unit, orthogonal to x_w: the lookup axis
};

class CurvePattern {
 public:
  enum class Evaluation { kLookupTable, kExact };

  // Throws std::invalid_argument for a degenerate or non-monotone curve, a bad frame or
  // lut_size < 2.
  static CurvePattern Build(const PatternPlane& plane, NurbsCurve2 curve, int lut_size,
                            Evaluation evaluation);

  StripeFrame Evaluate(const Vec3& point_w, const Vec3& normal) const;

  // Tangent angle (radians, in the pattern plane, from x) of the family at height y (m),
  // by the table and exactly. For tests, the size/accuracy benchmark and plots.
  double LookupAngle(double y) const;
  double ExactAngle(double y) const;

  // Translation of the family member through a point (m along x): the grating
  // coordinate across the curves. Constant along Evaluate()'s stripe direction (but beyond an
  // end whose tangent is parallel to x: see above).
  double MemberOffset(const Vec3& point_w) const;

  double y_min() const { return y_min_; }
  double y_max() const { return y_max_; }
  int lut_size() const { return static_cast<int>(tangents_.size()); }
  Evaluation evaluation() const { return evaluation_; }

 private:
  CurvePattern(const PatternPlane& plane, NurbsCurve2 curve);
  double SolveParameter(double y) const;  // t with y(t) = y, y clamped to the range
  Vec2 LookupTangent(double y) const;     // interpolated table entry, unit
  Vec2 ExactTangent(double y) const;      // unit

  PatternPlane plane_;
  NurbsCurve2 curve_;
  Evaluation evaluation_ = Evaluation::kLookupTable;
  bool increasing_ = true;
  double y_min_ = 0.0;
  double y_max_ = 0.0;
  std::vector<Vec2> tangents_;  // unit tangent at evenly spaced heights
};

}  // namespace hapticad
