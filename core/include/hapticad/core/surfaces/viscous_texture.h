// SPDX-License-Identifier: GPL-3.0-or-later
// Viscous grating texture of seed 001, eq. 2: a lateral force that depends on position
// across the grating and on scanning speed.
//
//   f(x, v) = f_DC + v f_vis + (beta_h + v beta_vis)
//             * sum_{i=1..4} i^-(alpha_h + v alpha_vis) sin(2 pi i x / lambda)
//
// Units, as in the paper: f, f_DC, beta_h, beta_vis are normalised so that 1 is the
// device's full range; v is in units of 400 mm/s (f_vis is "per 400 mm/s"); alpha are
// dimensionless; x and lambda are metres. In newtons the lateral force is
// clamp(f, 0, 1) * full_range_n, opposing the sliding velocity: like the TPad's
// friction it can only resist, never push, nor exceed the device. What full_range_n is
// (a fixed force, or the face's friction times the normal force, as the TPad's levels
// were) is the renderer's choice: TextureScale in surface_properties.h. The paper's
// experiment held beta_h = 0.125, alpha_h = 2.5, beta_vis = alpha_vis = 0, and crossed
// f_DC in {0.325, 0.5, 0.675} with f_vis in {-0.2, 0, 0.2}: PaperPreset(i, j). The
// -0.2 was chosen "to offset the observed positive viscosity inherent on a glass
// surface" (seed 001 §IV), a value the paper does not give: rendered without glass,
// those presets are the net negative viscosity the subjects did not feel.
//
// The grating's ridges run along the stripes, so x is measured across them. Pure and
// servo-tick safe; non-finite inputs give 0.
#pragma once

#include <array>

#include "hapticad/core/vec3.h"

namespace hapticad {

constexpr double kViscousSpeedUnitMps = 0.4;  // "per 400 mm/s"
constexpr int kViscousHarmonics = 4;

struct ViscousTextureParams {
  double f_dc = 0.5;
  double f_vis = 0.0;
  double beta_h = 0.125;
  double beta_vis = 0.0;
  double alpha_h = 2.5;
  double alpha_vis = 0.0;
  double period_m = 2.5e-3;  // lambda; the paper's gratings had a 2.5 mm period
};

// eq. 2 in normalised units: x in metres, speed in m/s (>= 0).
double ViscousTextureLevel(const ViscousTextureParams& params, double x_m, double speed_mps);

constexpr std::array<double, 3> kPaperDcLevels = {0.325, 0.5, 0.675};
constexpr std::array<double, 3> kPaperViscosities = {-0.2, 0.0, 0.2};
// The paper's virtual texture with f_DC = kPaperDcLevels[dc], f_vis = kPaperViscosities[vis].
ViscousTextureParams PaperPreset(int dc, int vis);

// Lateral force (N) for tangential velocity v_t at grating coordinate x: magnitude
// clamp(f, 0, 1) * full_range_n, direction -v_t, with the friction model's static band
// (below `stick_speed_mps` the magnitude grows linearly from 0) so rest is force-free.
Vec3 CalcViscousTextureForce(const ViscousTextureParams& params, double full_range_n, double x_m,
                             const Vec3& v_t, double stick_speed_mps);

}  // namespace hapticad
