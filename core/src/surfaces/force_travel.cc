// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ForceTravel::ForceClamped, MaxSlope and StretchSlope run on the servo tick.
#include "hapticad/core/surfaces/force_travel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hapticad {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// N/m: the steepest of the law's first `segments` segments, rising or falling.
double SteepestOf(const ForceTravel& law, int segments) {
  double x0 = 0.0;
  double f0 = 0.0;
  double steepest = 0.0;
  for (int i = 0; i < segments; ++i) {
    steepest = std::max(steepest, std::abs(law.force_n[i] - f0) / (law.travel_m[i] - x0));
    x0 = law.travel_m[i];
    f0 = law.force_n[i];
  }
  return steepest;
}

}  // namespace

double ForceTravel::ForceClamped(double x_m, double max_slope, bool* clamped) const {
  if (!(x_m > 0.0) || points <= 0) return 0.0;
  double stretch = 1.0;  // law travel per handle travel
  if (max_slope > 0.0) {
    const double steepest = StretchSlope();
    if (steepest > max_slope) {
      // stretch the travel, keep the forces: the operating force and the snap ratio stay
      stretch = max_slope / steepest;
      if (clamped != nullptr) *clamped = true;
    }
  }
  const int b = points - 2;  // where a stop starts
  if (ends_on_stop && b >= 0 && x_m * stretch > travel_m[b]) {
    double k = (force_n[b + 1] - force_n[b]) / (travel_m[b + 1] - travel_m[b]);
    if (max_slope > 0.0 && k > max_slope) {
      k = max_slope;
      if (clamped != nullptr) *clamped = true;
    }
    return force_n[b] + k * (x_m - travel_m[b] / stretch);
  }
  x_m *= stretch;
  double x0 = 0.0;
  double f0 = 0.0;
  for (int i = 0; i < points; ++i) {
    const double x1 = travel_m[i];
    if (x_m <= x1 || i + 1 == points) {
      return std::max(f0 + (force_n[i] - f0) / (x1 - x0) * (x_m - x0), 0.0);
    }
    x0 = x1;
    f0 = force_n[i];
  }
  return 0.0;
}

double ForceTravel::MaxSlope() const { return SteepestOf(*this, points); }

double ForceTravel::StretchSlope() const {
  return SteepestOf(*this, ends_on_stop ? points - 1 : points);
}

void ValidateForceTravel(const ForceTravel& law) {
  Require(law.points >= 1 && law.points <= ForceTravel::kMaxPoints,
          "force-travel law: 1 to " + std::to_string(ForceTravel::kMaxPoints) + " points, got " +
              std::to_string(law.points));
  double previous = 0.0;
  for (int i = 0; i < law.points; ++i) {
    const std::string at = "force-travel law, point " + std::to_string(i + 1) + ": ";
    Require(std::isfinite(law.travel_m[i]) && std::isfinite(law.force_n[i]), at + "not finite");
    Require(law.travel_m[i] > previous, at + "travel must increase from > 0");
    Require(law.force_n[i] >= 0.0, at + "force must be >= 0");
    previous = law.travel_m[i];
  }
  Require(!law.ends_on_stop || law.points >= 2,
          "force-travel law: a stop needs a point before it (where the mechanism ends)");
  const int last = law.points - 1;
  const double before = last > 0 ? law.force_n[last - 1] : 0.0;
  Require(law.force_n[last] > before,
          "force-travel law: the last segment must rise (past it the law goes on with its "
          "slope; a face that gave way for good would let the finger through)");
}

ForceTravel MakeLinearForceTravel(double stiffness_n_per_m) {
  Require(std::isfinite(stiffness_n_per_m) && stiffness_n_per_m > 0.0,
          "stiffness must be finite and > 0 N/m");
  ForceTravel law;
  law.points = 1;
  law.travel_m[0] = 1e-3;
  law.force_n[0] = stiffness_n_per_m * 1e-3;
  return law;
}

double CantileverStiffness(double youngs_modulus_pa, double width_m, double thickness_m,
                           double length_m) {
  for (double v : {youngs_modulus_pa, width_m, thickness_m, length_m}) {
    Require(std::isfinite(v) && v > 0.0,
            "cantilever: modulus, width, thickness and length must be finite and > 0");
  }
  const double second_moment = width_m * thickness_m * thickness_m * thickness_m / 12.0;
  return 3.0 * youngs_modulus_pa * second_moment / (length_m * length_m * length_m);
}

double SeriesStiffness(double a_n_per_m, double b_n_per_m) {
  return 1.0 / (1.0 / a_n_per_m + 1.0 / b_n_per_m);
}

ForceTravel MakePushButton(const PushButtonParams& p) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  Require(positive(p.operating_force_n), "push button: operating force must be > 0 N");
  Require(positive(p.pretravel_m), "push button: pretravel must be > 0");
  Require(std::isfinite(p.snap_ratio) && p.snap_ratio > 0.0 && p.snap_ratio < 1.0,
          "push button: snap ratio must lie between 0 and 1");
  Require(positive(p.snap_travel_m), "push button: snap travel must be > 0");
  Require(std::isfinite(p.total_travel_m) && p.total_travel_m > p.pretravel_m + p.snap_travel_m,
          "push button: total travel must exceed pretravel plus snap travel");
  Require(positive(p.bottom_stiffness_n_per_m), "push button: bottom stiffness must be > 0 N/m");
  ForceTravel law;
  law.points = 4;
  law.ends_on_stop = true;
  const double bottom = p.total_travel_m;
  law.travel_m = {p.pretravel_m, p.pretravel_m + p.snap_travel_m, bottom, bottom + 1e-3};
  law.force_n = {p.operating_force_n, p.operating_force_n * (1.0 - p.snap_ratio),
                 p.operating_force_n, p.operating_force_n + p.bottom_stiffness_n_per_m * 1e-3};
  return law;
}

}  // namespace hapticad
