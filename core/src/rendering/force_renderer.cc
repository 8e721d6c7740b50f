// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ForceRenderer::Render runs on the servo thread every tick. No allocation,
// no lock, no I/O (see force_renderer.h).
#include "hapticad/core/rendering/force_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "hapticad/core/surfaces/friction.h"

namespace hapticad {
namespace {

const HapticScene& Checked(const std::shared_ptr<const HapticScene>& scene) {
  if (!scene) throw std::invalid_argument("force renderer: no scene");
  return *scene;
}

ProxyConfig MakeProxyConfig(const HapticScene& scene, const ContactOptions& options) {
  if (!(std::isfinite(options.proxy_radius_m) && options.proxy_radius_m >= 0.0)) {
    throw std::invalid_argument("force renderer: the proxy radius must be finite and >= 0");
  }
  ProxyConfig config;
  config.radius_m = options.proxy_radius_m;
  config.surface_offset_m = scene.surface_offset_m();
  config.solids = &scene.BuildSolids();
  if (options.convex_pieces) config.pieces = &scene.BuildPieces();
  return config;
}

// Cone re-entry: a sliding proxy sticks again once the device is back inside this
// share of the dynamic cone (CHAI3D uses 0.6 of the dynamic angle), or once it comes to
// rest (ApplyFrictionCone).
constexpr double kStickReentry = 0.6;
// A lag "within" the dynamic cone: the slide set it to the cone's radius, give or take
// the rounding of a few operations.
constexpr double kOnTheCone = 1.0 + 1e-9;

// Shading normals of the triangles holding the proxy that agree this well (2 degrees)
// belong to one smooth CAD surface: the edge between them is the tessellation's (a
// valley where the mesher cut a curved face along the "wrong" diagonal), and the force
// is shaded across it. A CAD crease is not.
constexpr double kSmoothEdgeCos = 0.99939;

// A point proxy sweeps through the grid, a sphere through the tree: the scene builds
// the one asked for now, off the servo thread.
GodObjectProxy MakeProxy(const HapticScene& scene, const ContactOptions& options) {
  const ProxyConfig config = MakeProxyConfig(scene, options);
  if (config.radius_m == 0.0) return GodObjectProxy(scene.mesh(), scene.BuildGrid(), config);
  return GodObjectProxy(scene.mesh(), scene.BuildTree(), config);
}

}  // namespace

ForceRenderer::ForceRenderer(std::shared_ptr<const HapticScene> scene,
                             std::shared_ptr<const SurfaceTable> surfaces, RenderLimits limits,
                             ContactOptions options)
    : scene_(std::move(scene)),
      limits_(limits),
      options_(options),
      proxy_(MakeProxy(Checked(scene_), options)) {
  if (!(limits_.max_force_n > 0.0) || !(limits_.max_stiffness_n_per_m > 0.0) ||
      !(limits_.max_damping_n_s_per_m >= 0.0) || !std::isfinite(limits_.max_force_n) ||
      !std::isfinite(limits_.max_stiffness_n_per_m) ||
      !std::isfinite(limits_.max_damping_n_s_per_m)) {
    throw std::invalid_argument("force renderer: device limits must be finite, > 0 (damping >= 0)");
  }
  if (!(limits_.workspace_scale > 0.0) || !std::isfinite(limits_.workspace_scale)) {
    throw std::invalid_argument("force renderer: the workspace scale must be finite and > 0");
  }
  if (!(options_.edit_ramp_s >= 0.0) || !std::isfinite(options_.edit_ramp_s)) {
    throw std::invalid_argument("force renderer: the edit ramp must be finite and >= 0 s");
  }
  SetSurfaces(std::move(surfaces));
  surfaces_ = surfaces_handoff_.Take();
}

void ForceRenderer::SetSurfaces(std::shared_ptr<const SurfaceTable> surfaces) {
  if (!surfaces) throw std::invalid_argument("force renderer: no surface table");
  surfaces_handoff_.Publish(std::move(surfaces));
}

void ForceRenderer::Reset(const Vec3& device_w) {
  proxy_.ResetOutside(scene_->ToLocal(device_w));
  anchored_ = false;
  started_ = true;
  pushed_face_ = -1;
  blend_from_ = 1.0;
}

double ForceRenderer::EditBlendScale(double time_s) {
  if (blend_from_ == 1.0) return 1.0;
  if (time_s < blend_start_s_) blend_start_s_ = time_s;  // a clock that went back: from now
  const double a = (time_s - blend_start_s_) / options_.edit_ramp_s;
  if (a >= 1.0) {
    blend_from_ = 1.0;
    return 1.0;
  }
  return blend_from_ + std::max(a, 0.0) * (1.0 - blend_from_);
}

Vec3 ForceRenderer::ApplyFrictionCone(const SurfaceProperties& surface, double friction_scale,
                                      const Vec3& normal, double depth_m, const StripeFrame& stripe,
                                      double speed_mps, RenderOutput* out) {
  const Vec3& proxy = proxy_.position();
  // the cone lives on one plane: edges, corners and a new face restart it
  if (proxy_.constraints().count() != 1 || !anchored_ || anchor_face_ != out->cad_face) {
    anchored_ = true;
    sticking_ = true;
    anchor_face_ = out->cad_face;
    anchor_l_ = proxy;
  }
  const ConstraintPlane& plane = proxy_.constraints().plane(0);
  anchor_l_ -= (plane.normal.dot(anchor_l_) - plane.offset) * plane.normal;  // onto the plane
  Vec3 offset = anchor_l_ - proxy;  // where the anchor holds the proxy back
  offset -= offset.dot(normal) * normal;
  const double lag = offset.norm();
  // mu in the direction the proxy is dragged (anchor to proxy), anisotropic on a pattern
  FrictionParams mu = surface.friction;
  if (!std::holds_alternative<std::monostate>(surface.pattern)) {
    mu = DirectionalFriction(mu, surface.anisotropy, stripe.stripe, stripe.weight, -offset);
  }
  const double static_radius = friction_scale * mu.static_coefficient * depth_m;
  const double dynamic_radius = friction_scale * mu.dynamic_coefficient * depth_m;
  if (sticking_ && lag > static_radius) sticking_ = false;
  // Static friction holds again once the sliding stops: a hand come to rest (slower than
  // the face's stick speed) whose anchor no longer trails it (the lag within the dynamic
  // cone) sticks, so setting off again breaks away at mu_s. With the re-entry alone a
  // slide went on through a stop and every restart slid at mu_d.
  if (!sticking_ &&
      (lag < kStickReentry * dynamic_radius ||
       (lag <= kOnTheCone * dynamic_radius && speed_mps < surface.friction.stick_speed_mps))) {
    sticking_ = true;
  }
  if (!sticking_ && lag > dynamic_radius) {
    // slide: the anchor trails the proxy on the dynamic cone
    anchor_l_ = proxy + offset * (dynamic_radius / lag);
  }
  // Never pull the spring's end through geometry between the proxy and the anchor.
  // Both lie on or near the contact plane: whatever is the proxy's radius (and half its
  // offset) below the lower of the two cannot be in the way, and is skipped untested.
  SweepFloors floors;
  floors.count = 1;
  floors.normal[0] = plane.normal;
  floors.offset[0] = std::min(plane.normal.dot(proxy), plane.normal.dot(anchor_l_)) -
                     proxy_.config().radius_m - 0.5 * proxy_.config().surface_offset_m;
  SweepHit hit;
  if (proxy_.FirstHit(proxy, anchor_l_, &hit, &floors, plane.triangle)) anchor_l_ = proxy;
  if (sticking_) out->flags |= kSticking;
  return anchor_l_;
}

Vec3 ForceRenderer::SmoothShadingNormal() const {
  const ConstraintSet& constraints = proxy_.constraints();
  const double r = proxy_.config().radius_m;
  Vec3 first = Vec3::Zero();
  for (int i = 0; i < constraints.count(); ++i) {
    const ConstraintPlane& plane = constraints.plane(i);
    Vec3 n = scene_->mesh().CalcShadingNormal(plane.triangle, proxy_.position() - r * plane.normal);
    // on the side the proxy touches: sheets are felt from both sides, and a CAD normal
    // must never pull the hand into the part
    if (n.dot(plane.normal) < 0.0) n = -n;
    if (i == 0) {
      first = n;
    } else if (n.dot(first) < kSmoothEdgeCos) {
      return Vec3::Zero();  // a crease of the CAD model: the plain spring
    }
  }
  return first;
}

void ForceRenderer::Render(const RenderInput& input, RenderOutput* out) {
  // Farther from the part than any device reaches (1 km, or a thousand times the part),
  // or faster than anything a hand does (1 km/s): not a reading. Finite but absurd input
  // would overflow the spring or the damper.
  const double reach_m = std::max(1e3, 1e3 * scene_->size_m());
  if (input.position_w.allFinite() && input.velocity_w.allFinite() && std::isfinite(input.time_s) &&
      scene_->ToLocal(input.position_w).norm() < reach_m && input.velocity_w.norm() < 1e3) {
    RenderContact(input, out);
    // a backstop for whatever else could overflow: never a NaN or infinite force
    if (out->force_w.allFinite()) return;
  }
  *out = RenderOutput{};
  out->flags = kInputFault;
  out->proxy_w = scene_->ToWorld(proxy_.position());
}

void ForceRenderer::RenderContact(const RenderInput& input, RenderOutput* out) {
  *out = RenderOutput{};
  const SurfaceTable* taken = surfaces_handoff_.Take();
  const bool edited = taken != surfaces_;
  surfaces_ = taken;
  if (!started_) Reset(input.position_w);

  const Vec3 goal_l = scene_->ToLocal(input.position_w);
  proxy_.Update(goal_l);
  out->proxy_w = scene_->ToWorld(proxy_.position());
  if (!proxy_.in_contact()) {
    anchored_ = false;
    pushed_face_ = -1;
    blend_from_ = 1.0;  // a new touch starts from nothing: no step to blend
    return;
  }

  const std::uint32_t triangle = proxy_.constraints().plane(0).triangle;
  out->constraints = proxy_.constraints().count();
  out->cad_face = scene_->mesh().cad_face(triangle);
  const SurfaceProperties& surface = surfaces_->surface(out->cad_face);
  const std::uint32_t effects = surfaces_->effects(out->cad_face);
  out->flags |= kContact;

  const bool law = (effects & kEffectForceTravel) != 0u;
  // The face's stiffness, damping and law are felt at the handle: in the world, where the
  // handle's travel is workspace_scale times longer, a spring k / workspace_scale
  const double world_per_handle = limits_.workspace_scale;
  double k_felt = surface.stiffness_n_per_m;
  if (k_felt > limits_.max_stiffness_n_per_m) {
    k_felt = limits_.max_stiffness_n_per_m;
    if (!law) out->flags |= kStiffnessClamped;  // a law's own slopes are clamped below
  }
  const double k_w = k_felt / world_per_handle;
  // spring from the device to the proxy; its direction is the contact normal, or the
  // shading normal on a face
  Vec3 spring = k_w * (proxy_.position() - goal_l);
  if (options_.force_shading && scene_->mesh().has_corner_normals()) {
    const Vec3 shaded = SmoothShadingNormal();
    if (shaded.squaredNorm() > 0.0) spring = std::max(spring.dot(shaded), 0.0) * shaded;
  }
  double spring_only_n = spring.norm();
  const Vec3 normal =
      spring_only_n > 0.0 ? Vec3(spring / spring_only_n) : proxy_.constraints().plane(0).normal;
  const double depth = spring_only_n / k_w;
  // the force the face pushes back with at a world depth: its law's at the handle's
  // depth, or stiffness x depth
  const auto law_press = [&](double d) {
    if (!law) return k_w * d;
    bool clamped = false;
    const double f = surface.force_travel->ForceClamped(d / world_per_handle,
                                                        limits_.max_stiffness_n_per_m, &clamped);
    if (clamped) out->flags |= kStiffnessClamped;
    return f;
  };
  // a property edit under the hand: the push goes on from what was rendered, at the
  // depth it was rendered at, and blends into the edited face's. The scale is held to
  // the device's stable stiffness over the edited face's steepest slope (a law nearly
  // flat where the hand is and steep beyond would be felt stiffer than the device
  // renders): then, or where the edited face pushes nothing, the push steps down, which
  // adds no energy.
  if (edited && out->cad_face == pushed_face_ && options_.edit_ramp_s > 0.0) {
    const double edited_push = law_press(pushed_depth_m_);
    const double steepest =
        law ? std::min(surface.force_travel->MaxSlope(), limits_.max_stiffness_n_per_m) : k_felt;
    const double most = limits_.max_stiffness_n_per_m / steepest;  // >= 1
    blend_from_ = edited_push > 0.0 ? std::min(pushed_n_ / edited_push, most) : 1.0;
    if (std::abs(blend_from_ - 1.0) < 1e-9) blend_from_ = 1.0;  // the edit left this push
    blend_start_s_ = input.time_s;
  } else if (out->cad_face != pushed_face_) {
    blend_from_ = 1.0;  // on to another face: its own push, not the edited one's blend
  }
  const double blend = EditBlendScale(input.time_s);
  const auto press = [&](double d) { return blend * law_press(d); };
  if (law || blend != 1.0) spring_only_n = press(depth);
  if (blend != 1.0) out->flags |= kEditBlending;
  pushed_face_ = out->cad_face;
  pushed_depth_m_ = depth;
  pushed_n_ = spring_only_n;
  // the face's damping on the normal motion: resists, never pulls
  double b_felt = surface.damping_n_s_per_m;
  if (b_felt > limits_.max_damping_n_s_per_m) {
    b_felt = limits_.max_damping_n_s_per_m;
    out->flags |= kDampingClamped;
  }
  const double damper = -(b_felt / world_per_handle) * input.velocity_w.dot(normal);
  const double spring_n = std::max(spring_only_n + damper, 0.0);
  spring = spring_n * normal;
  const Vec3 v_t = input.velocity_w - input.velocity_w.dot(normal) * normal;

  // plain faces stop here: normal spring plus seed 000 friction
  if (effects == 0u) {
    Vec3 force = spring;
    const Vec3 friction = CalcFrictionForce(surface.friction, spring_n, v_t);
    out->friction_force_n = friction.norm();
    force += friction;
    const double magnitude = force.norm();
    if (magnitude > limits_.max_force_n) {
      force *= limits_.max_force_n / magnitude;
      out->flags |= kForceClamped;
    }
    out->force_w = force;
    out->normal_force_n = force.dot(normal);
    out->tangential_force_n = (force - out->normal_force_n * normal).norm();
    anchored_ = false;
    return;
  }

  const Vec3 contact_w = scene_->ToWorld(proxy_.contact_point());
  // roughness: deeper on a ball, normal tilted by its slope, mu scaled
  double normal_force = spring_n;
  Vec3 normal_direction = normal;
  double friction_scale = 1.0;
  if (effects & kEffectRoughness) {
    const RoughnessSample r = SampleRoughness(*surface.roughness, contact_w);
    normal_force = std::max(press(depth + r.height_m) + damper, 0.0);
    const Vec3 slope = r.gradient_w - r.gradient_w.dot(normal) * normal;
    normal_direction = (normal - slope).normalized();
    friction_scale = r.friction_scale;
  }

  // the friction coefficients at this point and in the direction of sliding
  FrictionParams mu = surface.friction;
  StripeFrame stripe{Vec3::Zero(), 0.0};
  double directional = 1.0;  // the pattern's mu in the direction of sliding over the face's own
  if (effects & kEffectPattern) {
    stripe = EvaluateStripe(surface, contact_w, normal);
    mu = DirectionalFriction(mu, surface.anisotropy, stripe.stripe, stripe.weight, v_t);
    if (surface.friction.static_coefficient > 0.0) {
      directional = mu.static_coefficient / surface.friction.static_coefficient;
    }
  }
  mu.static_coefficient *= friction_scale;
  mu.dynamic_coefficient *= friction_scale;

  Vec3 force = normal_force * normal_direction;
  if (effects & kEffectTexture) {
    const ViscousGrating& grating = *surface.texture;
    // in place of the face's friction, so a pattern's anisotropy scales it as it scales
    // friction (a grating across stripes of twice the friction drags twice as hard)
    const double full_range =
        grating.scale == TextureScale::kFrictionLevel
            ? mu.static_coefficient * normal_force
            : directional *
                  (grating.full_range_n > 0.0 ? grating.full_range_n : limits_.max_force_n);
    const Vec3 texture = CalcViscousTextureForce(surface.texture->params, full_range,
                                                 GratingCoordinate(surface, contact_w), v_t,
                                                 surface.friction.stick_speed_mps);
    out->texture_force_n = texture.norm();
    force += texture;
    anchored_ = false;
  } else if (effects & kEffectCone) {
    const Vec3 anchor = ApplyFrictionCone(surface, friction_scale, normal, normal_force / k_w,
                                          stripe, v_t.norm(), out);
    const Vec3 pull = k_w * (anchor - proxy_.position());
    out->friction_force_n = pull.norm();
    force += pull;
  } else {
    const Vec3 friction = CalcFrictionForce(mu, normal_force, v_t);
    out->friction_force_n = friction.norm();
    force += friction;
    anchored_ = false;
  }

  if (effects & kEffectVibration) {
    const Vibration& vibration = surfaces_->vibration(surface.vibration);
    const Vec3 shake = CalcVibrationForce(vibration, input.time_s);
    out->vibration_force_n = shake.dot(vibration.axis_w);
    // The shake loads and unloads the contact, and what acts across the face (friction,
    // a texture, a bump's tilt) follows the load, as seed 000's f_t = mu f_n: a shake that
    // takes the push away takes the drag with it. A face only pushes: the shake may take
    // its push away, never pull the hand in.
    const double before = force.dot(normal);
    const Vec3 across = force - before * normal;
    const double pushed = std::max(before + shake.dot(normal), 0.0);
    const double load = before > 0.0 ? pushed / before : 0.0;
    force = pushed * normal + load * across + (shake - shake.dot(normal) * normal);
  }

  const double magnitude = force.norm();
  if (magnitude > limits_.max_force_n) {
    force *= limits_.max_force_n / magnitude;
    out->flags |= kForceClamped;
  }
  out->force_w = force;
  out->normal_force_n = force.dot(normal);
  out->tangential_force_n = (force - out->normal_force_n * normal).norm();
}

}  // namespace hapticad
