// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: SampleRoughness runs on the servo tick.
#include "hapticad/core/surfaces/roughness_texture.h"

#include <cmath>

#include "hapticad/core/surfaces/roughness.h"

namespace hapticad {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

RoughnessGrid MakeRoughnessGrid(int category, const SurfaceFrame& frame, double amplitude_ratio,
                                double friction_modulation) {
  RoughnessGrid grid;
  grid.frame = frame;
  grid.spacing_m = GetRoughnessCategory(category).grid_size_mm * 1e-3;
  grid.amplitude_m = amplitude_ratio * grid.spacing_m;
  grid.friction_modulation = friction_modulation;
  return grid;
}

RoughnessSample SampleRoughness(const RoughnessGrid& grid, const Vec3& point_w) {
  const FrameCoordinates at = CalcFrameCoordinates(grid.frame, point_w);
  const double x = at.x;
  const double y = at.y;
  if (!std::isfinite(x) || !std::isfinite(y)) return {0.0, Vec3::Zero(), 1.0};
  const double k = 2.0 * kPi / grid.spacing_m;
  // fmod keeps the phase accurate far from the frame's origin
  const double cx = std::cos(k * std::fmod(x, grid.spacing_m));
  const double sx = std::sin(k * std::fmod(x, grid.spacing_m));
  const double cy = std::cos(k * std::fmod(y, grid.spacing_m));
  const double sy = std::sin(k * std::fmod(y, grid.spacing_m));
  const double bx = 0.5 * (1.0 + cx);
  const double by = 0.5 * (1.0 + cy);
  const double a = grid.amplitude_m;
  RoughnessSample s;
  s.height_m = a * (bx * by - 0.25);
  const double dhdx = -0.5 * a * k * sx * by;
  const double dhdy = -0.5 * a * k * sy * bx;
  s.gradient_w = dhdx * at.e1_w + dhdy * at.e2_w;
  s.friction_scale = 1.0 + grid.friction_modulation * (bx * by - 0.25) * (4.0 / 3.0);
  return s;
}

}  // namespace hapticad
