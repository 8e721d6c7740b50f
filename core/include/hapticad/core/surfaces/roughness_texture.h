// SPDX-License-Identifier: GPL-3.0-or-later
// Roughness as a grid texture, seed 000 §2.3: "surface roughness is modeled as grids
// where different sizes of grids are related to different surface roughness"; the
// grid spacing is the category's "computer grid ball size" (Table 2, roughness.h).
//
// Height field over the face frame's (x, y), spacing g, amplitude A, with
// b(x, y) = (1 + cos(2 pi x / g)) / 2 * (1 + cos(2 pi y / g)) / 2 in [0, 1] (a ball at
// every grid node, nothing between them; its mean over the grid is 1/4):
//   h(x, y) = A (b - 1/4)
// zero on average, so the face's stiffness times the depth stays the mean normal
// force. It is felt three ways through the proxy:
//   height    the penetration grows by h (k h more normal force on a ball);
//   normal    the force tilts by the slope, n' = normalize(n - grad h) (bump mapping);
//   friction  mu scales by 1 + m (b - 1/4) 4/3, in [1 - m/3, 1 + m]: more on the
//             balls, less between, the material's mu on average over the face.
// The category changes the grid, not the face's mean friction: the paper's Fig. 9
// stripes "represent different surface roughness and therefore different friction",
// but it gives no coefficient per category ("desirable to relate material and surface
// roughness combinations directly to friction coefficient. This can be done through a
// lot of experiments"). So mu stays the material's (measured at mu 0.4: 0.402 a quarter
// spacing off a row for every category) and what the hand feels differs by the grid's
// spatial period (at the default height, 5 % of the spacing, the bumps' steepest slope
// is 0.157 at every category); a measured mu for a material and finish goes in the
// surface's friction values.
// A stroke at speed v therefore carries the spatial period g, i.e. v / g Hz, and more:
// the bumps' tilt doubles that frequency and a diagonal stroke meets lines sqrt(2)
// finer, so at 1 kHz category 1 (0.1 mm) is felt as it is only up to 15 mm/s (the
// plugin's rate note counts it); use 5-10 kHz for the finest categories (field notes:
// textures want 5-10 kHz).
//
// Units: metres. Sampling is pure and servo-tick safe.
#pragma once

#include "hapticad/core/surfaces/surface_frame.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct RoughnessGrid {
  SurfaceFrame frame;
  double spacing_m = 1e-3;            // g, > 0
  double amplitude_m = 5e-5;          // A, >= 0
  double friction_modulation = 0.15;  // m, in [0, 1]
};

// Default height of the balls relative to the spacing: 5 %, so a category 6 grid
// (1.5 mm) has 75 um bumps and category 1 (0.1 mm) 5 um ones.
constexpr double kDefaultRoughnessAmplitudeRatio = 0.05;

// The grid of a Table 2 category on a face. Throws std::out_of_range for a category
// outside 1..7.
RoughnessGrid MakeRoughnessGrid(int category, const SurfaceFrame& frame,
                                double amplitude_ratio = kDefaultRoughnessAmplitudeRatio,
                                double friction_modulation = 0.15);

struct RoughnessSample {
  double height_m;        // h, in [-A/4, 3A/4]
  Vec3 gradient_w;        // grad h in the tangent plane (dimensionless slope, world vector)
  double friction_scale;  // 1 + m (b - 1/4) 4/3
};

// Non-finite points give a flat sample (h = 0, no slope, scale 1).
RoughnessSample SampleRoughness(const RoughnessGrid& grid, const Vec3& point_w);

}  // namespace hapticad
