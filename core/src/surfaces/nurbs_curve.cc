// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: NurbsCurve2::Evaluate runs on the servo tick (curve patterns).
#include "hapticad/core/surfaces/nurbs_curve.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace hapticad {

NurbsCurve2::NurbsCurve2(int degree, std::vector<double> knots, std::vector<Vec2> poles,
                         std::vector<double> weights)
    : degree_(degree),
      knots_(std::move(knots)),
      poles_(std::move(poles)),
      weights_(std::move(weights)) {
  if (degree_ < 1 || degree_ > kMaxDegree) {
    throw std::invalid_argument("curve: degree " + std::to_string(degree_) + " is outside 1.." +
                                std::to_string(kMaxDegree));
  }
  if (poles_.size() < static_cast<std::size_t>(degree_) + 1) {
    throw std::invalid_argument("curve: " + std::to_string(poles_.size()) + " poles for degree " +
                                std::to_string(degree_));
  }
  if (weights_.empty()) weights_.assign(poles_.size(), 1.0);
  if (weights_.size() != poles_.size()) throw std::invalid_argument("curve: one weight per pole");
  if (knots_.size() != poles_.size() + degree_ + 1) {
    throw std::invalid_argument("curve: " + std::to_string(knots_.size()) + " knots, expected " +
                                std::to_string(poles_.size() + degree_ + 1));
  }
  for (std::size_t i = 0; i < poles_.size(); ++i) {
    if (!poles_[i].allFinite())
      throw std::invalid_argument("curve: pole " + std::to_string(i) + " is not finite");
    if (!(weights_[i] > 0.0) || !std::isfinite(weights_[i])) {
      throw std::invalid_argument("curve: weight " + std::to_string(i) + " must be finite and > 0");
    }
  }
  for (std::size_t i = 0; i < knots_.size(); ++i) {
    if (!std::isfinite(knots_[i]) || (i > 0 && knots_[i] < knots_[i - 1])) {
      throw std::invalid_argument("curve: knots must be finite and non-decreasing");
    }
  }
  if (!(last_parameter() > first_parameter()))
    throw std::invalid_argument("curve: empty parameter range");
}

int NurbsCurve2::FindSpan(double t) const {
  const int n = static_cast<int>(poles_.size()) - 1;
  if (t >= knots_[n + 1]) return n;
  // last span whose knot is <= t (Piegl and Tiller, A2.1, by bisection)
  const auto it = std::upper_bound(knots_.begin() + degree_, knots_.begin() + n + 1, t);
  return static_cast<int>(it - knots_.begin()) - 1;
}

void NurbsCurve2::Evaluate(double t, Vec2* point, Vec2* derivative) const {
  t = std::clamp(t, first_parameter(), last_parameter());
  const int p = degree_;
  const int span = FindSpan(t);
  // basis functions and their first derivatives (Piegl and Tiller, A2.3), on the stack
  double ndu[kMaxDegree + 1][kMaxDegree + 1];
  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots_[span + 1 - j];
    right[j] = knots_[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  double basis[kMaxDegree + 1];
  double dbasis[kMaxDegree + 1];
  for (int j = 0; j <= p; ++j) basis[j] = ndu[j][p];
  for (int r = 0; r <= p; ++r) {
    // first derivative: p (N_{r-1,p-1} / (u_{i+p} - u_i) - N_{r,p-1} / (...))
    double d = 0.0;
    if (r >= 1) d += ndu[r - 1][p - 1] / ndu[p][r - 1];
    if (r <= p - 1) d -= ndu[r][p - 1] / ndu[p][r];
    dbasis[r] = p * d;
  }
  // rational: C = A / w, C' = (A' - w' C) / w
  Vec2 a = Vec2::Zero();
  Vec2 da = Vec2::Zero();
  double w = 0.0;
  double dw = 0.0;
  for (int j = 0; j <= p; ++j) {
    const int i = span - p + j;
    const double wi = weights_[i];
    a += basis[j] * wi * poles_[i];
    da += dbasis[j] * wi * poles_[i];
    w += basis[j] * wi;
    dw += dbasis[j] * wi;
  }
  *point = a / w;
  *derivative = (da - dw * *point) / w;
}

}  // namespace hapticad
