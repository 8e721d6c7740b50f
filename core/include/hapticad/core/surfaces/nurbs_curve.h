// SPDX-License-Identifier: GPL-3.0-or-later
// NurbsCurve2: a planar rational B-spline, as FreeCAD hands over any edge or sketch
// curve (Part.Edge.toNurbs()), with exact point and first derivative.
//
// Shapes: `poles` #P 2-D points, `weights` #P (> 0), `knots` the full knot vector of
// #P + degree + 1 non-decreasing values (FreeCAD's knots expanded by multiplicity).
// Units: those of the poles (metres in the core). Evaluation does not allocate
// (degree <= kMaxDegree) and is safe on the servo tick.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace hapticad {

using Vec2 = Eigen::Vector2d;

class NurbsCurve2 {
 public:
  static constexpr int kMaxDegree = 9;

  // Throws std::invalid_argument naming the problem (degree, counts, non-finite or
  // non-positive weights, decreasing knots).
  NurbsCurve2(int degree, std::vector<double> knots, std::vector<Vec2> poles,
              std::vector<double> weights);

  int degree() const { return degree_; }
  double first_parameter() const { return knots_[degree_]; }
  double last_parameter() const { return knots_[knots_.size() - degree_ - 1]; }
  const std::vector<Vec2>& poles() const { return poles_; }

  // Point and first derivative at t, clamped to the parameter range.
  void Evaluate(double t, Vec2* point, Vec2* derivative) const;

 private:
  int FindSpan(double t) const;

  int degree_;
  std::vector<double> knots_;
  std::vector<Vec2> poles_;
  std::vector<double> weights_;
};

}  // namespace hapticad
