// SPDX-License-Identifier: GPL-3.0-or-later
// ForceTravel: how hard a face pushes back against how far it has been pressed in, for
// parts whose give is a mechanism's, not the material's (seed 000 §3): a toothbrush
// head on its bending neck, a push button's switch.
//
// The law is piecewise linear through (0, 0) and up to kMaxPoints points (travel
// increasing, force >= 0, the last segment rising), and continues past the last point
// with the last segment's slope. Segments may fall (a tactile switch's snap): the force
// is a function of travel alone, so a press and release along it gives back what it
// took, and under the device's zero-order hold a falling segment dissipates (Colgate's
// sampled spring with K < 0). A device renders no slope steeper than its stable
// stiffness: ForceClamped() stretches the law's travel until its steepest segment is
// that stiffness, so every force level (a button's operating force, its snap ratio) is
// kept and only the travel grows; the force never steps. A law may end on a stop (a
// button bottoming out on its housing): the stop is not stretched with the mechanism,
// it is felt from where the stretched mechanism ends, as stiff as it is up to the
// device's stiffness (a housing far stiffer than the click must not stretch the click).
// Builders for the two case studies:
//   CantileverStiffness   a beam clamped at one end, loaded at the other:
//                         k = 3 E I / L^3, I = b h^3 / 12 (rectangular neck, bent across h).
//   MakePushButton        a tactile switch: rises to the operating force at the
//                         pretravel, snaps down by the snap ratio over `snap_travel`,
//                         rises again to the operating force at the total travel, then
//                         bottoms out on its housing, a stop of `bottom_stiffness`.
// Units: SI (m, N, N/m, Pa). Force() and ForceClamped() are servo-tick safe.
#pragma once

#include <array>

namespace hapticad {

struct ForceTravel {
  static constexpr int kMaxPoints = 8;
  std::array<double, kMaxPoints> travel_m{};
  std::array<double, kMaxPoints> force_n{};
  int points = 0;
  // The last segment (from the last point but one on) is a stop: see above. Needs 2 points.
  bool ends_on_stop = false;

  // The force (N) at travel x_m (0 and below: 0).
  double Force(double x_m) const { return ForceClamped(x_m, 0.0, nullptr); }
  // The same with the travel stretched so that no slope exceeds max_slope (N/m; 0: no
  // limit): F(x s) with s = min(1, max_slope / StretchSlope()); past the start b of a stop,
  // F(b) + min(k_stop, max_slope) (x - b / s). Sets *clamped when stretched or the stop
  // was softened.
  double ForceClamped(double x_m, double max_slope, bool* clamped) const;
  double MaxSlope() const;      // N/m: the steepest segment, rising or falling, a stop included
  double StretchSlope() const;  // N/m: the steepest the stretch looks at: MaxSlope without a stop
};

// Throws std::invalid_argument saying what is wrong: no point, more than kMaxPoints,
// travel not increasing from > 0, a force < 0, a last segment that does not rise,
// anything not finite, a stop on a law of one point.
void ValidateForceTravel(const ForceTravel& law);

// A straight law of stiffness k (N/m > 0) through one point at 1 mm.
ForceTravel MakeLinearForceTravel(double stiffness_n_per_m);

// N/m. Preconditions: all > 0.
double CantileverStiffness(double youngs_modulus_pa, double width_m, double thickness_m,
                           double length_m);
// Springs in series (the neck bends and the material gives): 1 / (1/a + 1/b).
double SeriesStiffness(double a_n_per_m, double b_n_per_m);

struct PushButtonParams {
  double operating_force_n = 1.47;         // Omron B3F's middle rating
  double pretravel_m = 0.25e-3;            // travel to the operating point
  double snap_ratio = 0.5;                 // (F_op - F_return) / F_op, in (0, 1)
  double snap_travel_m = 0.1e-3;           // over which the force falls to F_return
  double total_travel_m = 0.6e-3;          // where the plunger bottoms out, > pretravel + snap
  double bottom_stiffness_n_per_m = 50e3;  // past the total travel: a plastic housing
};
// Throws std::invalid_argument naming a value out of range.
ForceTravel MakePushButton(const PushButtonParams& params);

}  // namespace hapticad
