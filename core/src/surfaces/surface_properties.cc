// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: EvaluateStripe and GratingCoordinate run on the servo tick.
#include "hapticad/core/surfaces/surface_properties.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace hapticad {
namespace {

void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) {
    throw std::invalid_argument(std::string("surface: ") + field + " = " + std::to_string(value) +
                                " must be " + rule);
  }
}

void RequireUnit(const Vec3& v, const char* field) {
  if (!v.allFinite() || std::abs(v.norm() - 1.0) > 1e-6) {
    throw std::invalid_argument(std::string("surface: ") + field + " must be a finite unit vector");
  }
}

void ValidateFrame(const SurfaceFrame& f, const char* what) {
  const std::string problem = DescribeFrameProblem(f);
  if (!problem.empty())
    throw std::invalid_argument(std::string("surface: ") + what + ": " + problem);
}

bool NonNegative(double x) { return std::isfinite(x) && x >= 0.0; }
bool Positive(double x) { return std::isfinite(x) && x > 0.0; }

void ValidatePattern(const SurfaceProperties& s) {
  if (const auto* linear = std::get_if<LinearPattern>(&s.pattern)) {
    RequireUnit(linear->direction_w, "linear pattern direction");
    const std::string problem = DescribeLinearCylinderProblem(*linear);
    if (!problem.empty()) throw std::invalid_argument("surface: linear pattern " + problem);
  } else if (const auto* circular = std::get_if<CircularPattern>(&s.pattern)) {
    if (!circular->centre_w.allFinite())
      throw std::invalid_argument("surface: circular pattern centre is not finite");
    RequireUnit(circular->axis_w, "circular pattern axis");
    Require(Positive(circular->blend_radius_m), "circular pattern blend radius",
            circular->blend_radius_m, "> 0 m");
  } else if (const auto* curve = std::get_if<std::shared_ptr<const CurvePattern>>(&s.pattern)) {
    if (!*curve) throw std::invalid_argument("surface: curve pattern is empty");
  }
  Require(NonNegative(s.anisotropy.across_factor), "across friction factor",
          s.anisotropy.across_factor, ">= 0");
  Require(NonNegative(s.anisotropy.backward_factor), "backward friction factor",
          s.anisotropy.backward_factor, ">= 0");
}

}  // namespace

StripeFrame EvaluateStripe(const SurfaceProperties& s, const Vec3& point_w, const Vec3& normal) {
  switch (s.pattern.index()) {
    case 1:
      return EvaluateLinear(std::get<LinearPattern>(s.pattern), point_w, normal);
    case 2:
      return EvaluateCircular(std::get<CircularPattern>(s.pattern), point_w, normal);
    case 3:
      return std::get<std::shared_ptr<const CurvePattern>>(s.pattern)->Evaluate(point_w, normal);
    default:
      return ProjectStripe(Vec3::Zero(), normal);
  }
}

double GratingCoordinate(const SurfaceProperties& s, const Vec3& point_w) {
  if (const auto* circular = std::get_if<CircularPattern>(&s.pattern)) {
    const Vec3 offset = point_w - circular->centre_w;
    return (offset - offset.dot(circular->axis_w) * circular->axis_w).norm();
  }
  if (const auto* curve = std::get_if<std::shared_ptr<const CurvePattern>>(&s.pattern)) {
    return (*curve)->MemberOffset(point_w);
  }
  return CalcFrameCoordinates(s.texture->frame, point_w).y;
}

void ValidateSurfaceProperties(const SurfaceProperties& s) {
  const FrictionParams& f = s.friction;
  Require(NonNegative(f.static_coefficient), "static friction", f.static_coefficient,
          "finite and >= 0");
  Require(NonNegative(f.dynamic_coefficient), "dynamic friction", f.dynamic_coefficient,
          "finite and >= 0");
  Require(Positive(f.stick_speed_mps), "stick speed", f.stick_speed_mps, "finite and > 0 m/s");
  Require(NonNegative(f.transition_speed_mps), "transition speed", f.transition_speed_mps,
          "finite and >= 0 m/s");
  Require(NonNegative(f.stribeck_speed_mps), "Stribeck speed", f.stribeck_speed_mps,
          "finite and >= 0 m/s");
  Require(Positive(s.stiffness_n_per_m), "stiffness", s.stiffness_n_per_m, "finite and > 0 N/m");
  Require(NonNegative(s.damping_n_s_per_m), "damping", s.damping_n_s_per_m,
          "finite and >= 0 N s/m");
  ValidatePattern(s);
  if (s.roughness) {
    ValidateFrame(s.roughness->frame, "roughness frame");
    Require(Positive(s.roughness->spacing_m), "roughness grid spacing", s.roughness->spacing_m,
            "> 0 m");
    Require(NonNegative(s.roughness->amplitude_m), "roughness amplitude", s.roughness->amplitude_m,
            ">= 0 m");
    Require(
        NonNegative(s.roughness->friction_modulation) && s.roughness->friction_modulation <= 1.0,
        "roughness friction modulation", s.roughness->friction_modulation, "in 0..1");
  }
  if (s.texture) {
    const ViscousTextureParams& t = s.texture->params;
    ValidateFrame(s.texture->frame, "texture frame");
    for (double x : {t.f_dc, t.f_vis, t.beta_h, t.beta_vis, t.alpha_h, t.alpha_vis}) {
      Require(std::isfinite(x), "texture parameter", x, "finite");
    }
    Require(Positive(t.period_m), "texture period", t.period_m, "> 0 m");
    Require(NonNegative(s.texture->full_range_n), "texture full range", s.texture->full_range_n,
            ">= 0 N");
  }
  if (s.force_travel) ValidateForceTravel(*s.force_travel);
}

SurfaceTable::SurfaceTable(std::vector<SurfaceProperties> by_face,
                           std::vector<Vibration> vibrations)
    : by_face_(std::move(by_face)), vibrations_(std::move(vibrations)) {
  for (std::size_t i = 0; i < vibrations_.size(); ++i) {
    const Vibration& v = vibrations_[i];
    if (!Positive(v.frequency_hz) || !NonNegative(v.amplitude_n) || !v.axis_w.allFinite() ||
        std::abs(v.axis_w.norm() - 1.0) > 1e-6) {
      throw std::invalid_argument("vibration " + std::to_string(i) +
                                  ": frequency must be > 0, amplitude >= 0, axis a unit vector");
    }
  }
  effects_.resize(by_face_.size(), 0u);
  for (std::size_t i = 0; i < by_face_.size(); ++i) {
    const SurfaceProperties& s = by_face_[i];
    try {
      ValidateSurfaceProperties(s);
      if (s.vibration >= static_cast<int>(vibrations_.size())) {
        throw std::invalid_argument("surface: vibration index " + std::to_string(s.vibration) +
                                    " beyond the " + std::to_string(vibrations_.size()) +
                                    " vibrations");
      }
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("CAD face " + std::to_string(i) + ": " + e.what());
    }
    std::uint32_t mask = 0;
    if (!std::holds_alternative<std::monostate>(s.pattern)) mask |= kEffectPattern;
    if (s.roughness) mask |= kEffectRoughness;
    if (s.texture) mask |= kEffectTexture;
    if (s.vibration >= 0) mask |= kEffectVibration;
    if (s.friction_mode == FrictionMode::kCone) mask |= kEffectCone;
    if (s.force_travel) mask |= kEffectForceTravel;
    effects_[i] = mask;
  }
}

}  // namespace hapticad
