// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: CurvePattern::Evaluate and MemberOffset run on the servo tick (Build does not).
#include "hapticad/core/surfaces/curve_pattern.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace hapticad {
namespace {

// Unit tangent oriented toward increasing y, so neighbouring table entries never
// point opposite ways (the stripe is an unoriented line).
Vec2 OrientedTangent(const Vec2& d) { return (d.y() < 0.0 ? Vec2(-d) : d).normalized(); }

}  // namespace

CurvePattern::CurvePattern(const PatternPlane& plane, NurbsCurve2 curve)
    : plane_(plane), curve_(std::move(curve)) {}

CurvePattern CurvePattern::Build(const PatternPlane& plane, NurbsCurve2 curve, int lut_size,
                                 Evaluation evaluation) {
  if (lut_size < 2) throw std::invalid_argument("curve pattern: lookup table needs >= 2 entries");
  if (!plane.origin_w.allFinite() || std::abs(plane.x_w.norm() - 1.0) > 1e-9 ||
      std::abs(plane.y_w.norm() - 1.0) > 1e-9 || std::abs(plane.x_w.dot(plane.y_w)) > 1e-9) {
    throw std::invalid_argument("curve pattern: the frame's axes must be orthonormal");
  }
  CurvePattern pattern(plane, std::move(curve));
  pattern.evaluation_ = evaluation;
  const NurbsCurve2& c = pattern.curve_;
  const int samples = 64 * static_cast<int>(c.poles().size());
  const double t0 = c.first_parameter();
  const double t1 = c.last_parameter();
  Vec2 p, d;
  // y must move one way along the whole curve: its derivative keeps one sign
  int direction = 0;
  for (int i = 0; i <= samples; ++i) {
    const double t = t0 + (t1 - t0) * i / samples;
    c.Evaluate(t, &p, &d);
    const double dy = d.y();
    const int sign = dy > 1e-12 * d.norm() ? 1 : (dy < -1e-12 * d.norm() ? -1 : 0);
    if (direction == 0) direction = sign;
    if (sign != 0 && sign != direction) {
      throw std::invalid_argument(
          "curve pattern: the curve turns back or touches itself along the pattern's y axis "
          "(near parameter " +
          std::to_string(t) +
          "); parallel copies of it would cross, so the stripe direction is ambiguous");
    }
  }
  c.Evaluate(t0, &p, &d);
  const double y_start = p.y();
  c.Evaluate(t1, &p, &d);
  const double y_end = p.y();
  double extent = 0.0;
  for (const Vec2& pole : c.poles()) extent = std::max(extent, (pole - c.poles().front()).norm());
  if (direction == 0 || !(std::abs(y_end - y_start) > 1e-9 * std::max(extent, 1e-12))) {
    throw std::invalid_argument(
        "curve pattern: the curve is degenerate (it spans no height along the pattern's y axis)");
  }
  pattern.increasing_ = y_end > y_start;
  // a tangent parallel to x somewhere inside: the family members touch there
  for (int i = 1; i < samples; ++i) {
    c.Evaluate(t0 + (t1 - t0) * i / samples, &p, &d);
    if (!(std::abs(d.y()) > 1e-12 * d.norm())) {
      throw std::invalid_argument(
          "curve pattern: the curve turns back or touches itself along the pattern's y axis "
          "(its tangent is parallel to x near parameter " +
          std::to_string(t0 + (t1 - t0) * i / samples) + ")");
    }
  }
  pattern.y_min_ = std::min(y_start, y_end);
  pattern.y_max_ = std::max(y_start, y_end);
  pattern.tangents_.resize(lut_size);
  for (int i = 0; i < lut_size; ++i) {
    const double y = pattern.y_min_ + (pattern.y_max_ - pattern.y_min_) * i / (lut_size - 1);
    pattern.tangents_[i] = pattern.ExactTangent(y);
  }
  return pattern;
}

double CurvePattern::SolveParameter(double y) const {
  y = std::clamp(y, y_min_, y_max_);
  double lo = curve_.first_parameter();
  double hi = curve_.last_parameter();
  if (!increasing_) std::swap(lo, hi);  // y(lo) <= y <= y(hi)
  double t = 0.5 * (lo + hi);
  Vec2 p, d;
  // Newton steps kept inside the bracket, bisection when they leave it
  for (int iteration = 0; iteration < 100; ++iteration) {
    curve_.Evaluate(t, &p, &d);
    const double f = p.y() - y;
    if (f < 0.0)
      lo = t;
    else
      hi = t;
    if (std::abs(f) <= 1e-15 * std::max(1.0, std::abs(y)) || lo == hi) break;
    double next = t - f / d.y();
    const double a = std::min(lo, hi);
    const double b = std::max(lo, hi);
    if (!(next > a && next < b)) next = 0.5 * (lo + hi);
    if (next == t) break;
    t = next;
  }
  return t;
}

Vec2 CurvePattern::ExactTangent(double y) const {
  Vec2 p, d;
  curve_.Evaluate(SolveParameter(y), &p, &d);
  return OrientedTangent(d);
}

Vec2 CurvePattern::LookupTangent(double y) const {
  const double u = (std::clamp(y, y_min_, y_max_) - y_min_) / (y_max_ - y_min_) *
                   static_cast<double>(tangents_.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(u), tangents_.size() - 2);
  const double f = u - static_cast<double>(i);
  return ((1.0 - f) * tangents_[i] + f * tangents_[i + 1]).normalized();
}

double CurvePattern::ExactAngle(double y) const {
  const Vec2 t = ExactTangent(y);
  return std::atan2(t.y(), t.x());
}

double CurvePattern::LookupAngle(double y) const {
  const Vec2 t = LookupTangent(y);
  return std::atan2(t.y(), t.x());
}

double CurvePattern::MemberOffset(const Vec3& point_w) const {
  const Vec3 local = point_w - plane_.origin_w;
  if (!local.allFinite()) return 0.0;
  const double y = local.dot(plane_.y_w);
  Vec2 p, d;
  curve_.Evaluate(SolveParameter(y), &p, &d);
  // beyond an end the member goes on along the end tangent, as the stripes do; a tangent
  // parallel to x there would make every member one line: the end's x is kept instead
  const double beyond = y - std::clamp(y, y_min_, y_max_);
  const double along =
      beyond != 0.0 && std::abs(d.y()) > 1e-12 * d.norm() ? beyond * d.x() / d.y() : 0.0;
  return local.dot(plane_.x_w) - (p.x() + along);
}

StripeFrame CurvePattern::Evaluate(const Vec3& point_w, const Vec3& normal) const {
  const double y = (point_w - plane_.origin_w).dot(plane_.y_w);
  if (!std::isfinite(y)) return ProjectStripe(Vec3::Zero(), normal);  // weight 0: isotropic
  const Vec2 t = evaluation_ == Evaluation::kLookupTable ? LookupTangent(y) : ExactTangent(y);
  return ProjectStripe(t.x() * plane_.x_w + t.y() * plane_.y_w, normal);
}

}  // namespace hapticad
