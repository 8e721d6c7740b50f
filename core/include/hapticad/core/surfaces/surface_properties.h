// SPDX-License-Identifier: GPL-3.0-or-later
// SurfaceProperties: everything a designer put on one CAD face, in SI units and the
// world frame; SurfaceTable: those properties by CAD face id, compiled for the tick.
//
// A face has a friction model and a contact stiffness, and may add
//   a stripe pattern   linear, circular or curve (seed 000 §2.2) with its anisotropy;
//   roughness          the grid texture of its Table 2 category (seed 000 §2.3);
//   a viscous grating  seed 001 eq. 2 (it replaces Coulomb friction as the lateral force);
//   a vibration        of the part the face belongs to;
//   a force-travel law a mechanism's give (seed 000 §3: a bending neck, a push
//                      button's snap) in place of the contact stiffness.
// SurfaceTable compiles each face into a bit mask of the effects it uses; the renderer
// runs only those, so a plain face pays for none of them.
//
// Untagged faces get kUntaggedSurface: mu_s 0.5, mu_d 0.4 (the low end of hard
// plastics and metals against a dry fingertip, resources/materials/materials.csv) and
// 0.4 N/mm, the largest stiffness the most common desktop device (3D Systems Touch)
// renders stably.
//
// The table is immutable once built; the renderer reads it on every tick (cheap, safe).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "hapticad/core/surfaces/anisotropy.h"
#include "hapticad/core/surfaces/curve_pattern.h"
#include "hapticad/core/surfaces/force_travel.h"
#include "hapticad/core/surfaces/friction.h"
#include "hapticad/core/surfaces/roughness_texture.h"
#include "hapticad/core/surfaces/stripe_pattern.h"
#include "hapticad/core/surfaces/surface_frame.h"
#include "hapticad/core/surfaces/vibration.h"
#include "hapticad/core/surfaces/viscous_texture.h"

namespace hapticad {

enum class FrictionMode {
  kVelocity,  // seed 000 §2.1: mu_eq(v), continuous, no stick-slip
  kCone,      // friction cone on the proxy (static/dynamic angles from mu_s/mu_d): stick-slip
};

using StripePattern = std::variant<std::monostate, LinearPattern, CircularPattern,
                                   std::shared_ptr<const CurvePattern>>;

// What level 1 of a viscous grating stands for.
enum class TextureScale {
  // A force: full_range_n, or the device's full range (issue 3's reading of "1 = the
  // hardware's full range"), whatever the press: on a strong device several times a
  // light touch's normal force.
  kDeviceForce,
  // A friction level, as on seed 001's TPad, whose levels set its glass's friction:
  // level 1 is the face's static friction (times the roughness's scale), and the
  // lateral force is the level times that mu times the normal force. A texture then
  // drags harder the harder one presses, as a real one does.
  kFrictionLevel,
};

struct ViscousGrating {
  ViscousTextureParams params;
  SurfaceFrame frame;  // x across the ridges: e2 of the frame unless a pattern says otherwise
  // kDeviceForce: newtons that level 1 stands for; 0 takes the device's full range.
  double full_range_n = 0.0;
  TextureScale scale = TextureScale::kDeviceForce;
};

struct SurfaceProperties {
  FrictionParams friction;           // with a pattern: along the stripes (mu_a)
  double stiffness_n_per_m = 400.0;  // contact stiffness asked for, N/m (> 0)
  // Viscous damping of the normal motion while in contact, N s/m (>= 0): resists
  // pressing in and springing back, never pulls (the normal force stays >= 0).
  double damping_n_s_per_m = 0.0;
  FrictionMode friction_mode = FrictionMode::kVelocity;
  StripePattern pattern;
  AnisotropicFriction anisotropy;  // used with a pattern
  std::optional<RoughnessGrid> roughness;
  std::optional<ViscousGrating> texture;
  int vibration = -1;  // index into the table's vibrations, -1 for none
  // The normal force against the depth pressed in, instead of stiffness x depth.
  std::optional<ForceTravel> force_travel;
};

inline const SurfaceProperties kUntaggedSurface{};

// Stripe frame of a surface's pattern at a contact point (weight 0 without a pattern).
StripeFrame EvaluateStripe(const SurfaceProperties& surface, const Vec3& point_w,
                           const Vec3& normal);

// Coordinate across a surface's grating ridges, m: the distance from the axis for a
// circular pattern, the family member's offset for a curve pattern, else e2 of the
// texture frame. Precondition: surface.texture is set.
double GratingCoordinate(const SurfaceProperties& surface, const Vec3& point_w);

// Throws std::invalid_argument naming the field if a value is negative, zero where it
// must be positive, or not finite.
void ValidateSurfaceProperties(const SurfaceProperties& surface);

enum EffectBits : std::uint32_t {
  kEffectPattern = 1u << 0,
  kEffectRoughness = 1u << 1,
  kEffectTexture = 1u << 2,
  kEffectVibration = 1u << 3,
  kEffectCone = 1u << 4,
  kEffectForceTravel = 1u << 5,
};

class SurfaceTable {
 public:
  // `by_face[i]` belongs to CAD face i; faces beyond the vector are untagged.
  // `vibrations` are the parts' vibrations that surfaces point to. Validates every entry.
  explicit SurfaceTable(std::vector<SurfaceProperties> by_face = {},
                        std::vector<Vibration> vibrations = {});

  const SurfaceProperties& surface(std::int32_t face) const {
    return InRange(face) ? by_face_[face] : kUntaggedSurface;
  }
  // The effects a face uses (EffectBits); 0 for a plain or untagged face.
  std::uint32_t effects(std::int32_t face) const { return InRange(face) ? effects_[face] : 0u; }
  const Vibration& vibration(int index) const { return vibrations_[index]; }
  std::size_t size() const { return by_face_.size(); }

 private:
  bool InRange(std::int32_t face) const {
    return face >= 0 && static_cast<std::size_t>(face) < by_face_.size();
  }

  std::vector<SurfaceProperties> by_face_;
  std::vector<std::uint32_t> effects_;
  std::vector<Vibration> vibrations_;
};

}  // namespace hapticad
