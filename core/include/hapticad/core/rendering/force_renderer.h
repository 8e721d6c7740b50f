// SPDX-License-Identifier: GPL-3.0-or-later
// ForceRenderer: one servo tick of haptic rendering — device state in, force out.
//
//   proxy      god-object proxy on the scene, a point or a sphere (GodObjectProxy)
//   normal     k (proxy - device), k = the touched face's stiffness capped at the
//              device's maximum stable stiffness. With force shading the spring acts
//              along the shading normal n_s (the CAD's exact normals blended over the
//              triangle) with the depth measured along it, k ((proxy - device) . n_s)
//              n_s: a coarse tessellation of a curved face feels smooth (Morgenbesser
//              and Srinivasan 1996). On an edge or in a corner of the tessellation (two
//              or three constraints) it shades when the triangles' shading normals
//              agree there (one smooth CAD face); at a crease of the CAD model the
//              plain spring acts. With roughness, k (depth + h) along the bump-tilted
//              normal (roughness_texture.h). The face's damping B adds -B v_n along the
//              normal (capped at the device's limit), the sum never below zero. A
//              force-travel law (a stiffness study's mechanism) pushes instead of k.
//              Stiffness, damping and law are felt at the handle (below).
//   lateral    one of
//                seed 000 §2.1 friction, f_t = -mu_eq(|v_t|) F_n v_hat_t, with the
//                face's mu (anisotropic along a pattern, scaled by roughness);
//                the friction cone (FrictionMode::kCone): the proxy sticks to an anchor
//                until the device leaves the static cone, then slides on the dynamic
//                one until it falls back well inside it or comes to rest (slower than
//                the face's stick speed, its anchor no longer dragged), where it sticks
//                again (stick-slip, which the paper's model cannot render);
//                a viscous grating (seed 001 eq. 2) in place of Coulomb friction
//   vibration  the touched part's, while powered, added to the force along its axis; a
//              face only pushes, so the force's component along the contact normal is
//              then held at or above zero: a vibration stronger than the push is felt
//              as the push's half-wave (the push plus the vibration where that pushes,
//              nothing where it would pull the hand into the part), whatever it does
//              across the face is kept; the lateral force follows the load it leaves
//              (scaled by the push with the shake over the push without it), so where
//              the shake takes the push away it takes the drag too
//   total      scaled down to the device's maximum force
// The touched face is the one whose triangle first constrained the proxy this tick.
// A face runs only the effects it compiled into (SurfaceTable::effects).
//
// Felt at the handle: the device's workspace is scaled into the world by
// RenderLimits::workspace_scale = s (world metres per handle metre, WorkspaceMapping),
// and forces are not scaled, so a world spring k_w feels like s k_w at the handle. A
// face's stiffness, damping and force-travel law are what the designer wants the hand to
// feel, so they are rendered against the handle's displacement: in the world a spring of
// k / s, a damper of B / s and the law's F(depth_w / s), each clamped at the device's
// limits, which are felt too. Forces given in newtons (friction, mu times the push, a
// texture's levels, a vibration's amplitude, the force limit) are the same at the handle.
// What belongs to the part stays in the part's frame, scaled with it: a grating's or a
// pattern's period, roughness bumps, the speeds of friction and textures (a 2 mm
// grating under s = 2 passes under the handle every 1 mm of its travel).
//
// Frames and units: world frame, SI (m, m/s, N, N/m, s). Render() is servo-tick safe:
// no allocation, no lock, no I/O. Device input that is not finite, lies over 1 km (or a
// thousand part sizes) from the part or moves over 1 km/s yields zero force and the
// kInputFault flag, and never reaches the proxy; a force that would not be finite is
// replaced by zero with the same flag.
//
// Threads: Render() runs on the servo thread; SetSurfaces() on one control thread
// (a property edit: the new table is taken at the next Render(), under a pressing hand
// its push blended in over ContactOptions::edit_ramp_s; the scene and its tree are not
// rebuilt, the proxy carries on). A new scene means a new renderer
// (ServoLoop::SetRenderer).
#pragma once

#include <cstdint>
#include <memory>

#include "hapticad/core/contact/god_object_proxy.h"
#include "hapticad/core/handoff.h"
#include "hapticad/core/rendering/haptic_scene.h"
#include "hapticad/core/surfaces/surface_properties.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

// The device's limits as the hand feels them (per metre of the handle's travel), and how
// far the world is scaled to it. RenderLimitsFor() (workspace_mapping.h) makes them for a
// device and its mapping.
struct RenderLimits {
  double max_force_n = 3.3;              // > 0; the full range of textures that set none
  double max_stiffness_n_per_m = 400.0;  // > 0, felt: N per m of the handle's travel
  // >= 0, felt: N s per m of the handle's travel. Virtual damping beyond the device's
  // own destabilises a sampled display (Colgate: b > K T / 2 + |B|); 0.5 N s/m is a
  // desktop device's own (field notes).
  double max_damping_n_s_per_m = 0.5;
  // > 0, finite: world metres per metre of the handle's travel, the scale of the
  // WorkspaceMapping the device is seen through (1: the handle moves in the world's
  // metres). A face's stiffness, damping and law are divided by it in the world, so the
  // hand feels them as set. A mapping of another scale needs limits made for it.
  double workspace_scale = 1.0;
};

// How the contact is computed: the shape of the proxy and whether to shade.
struct ContactOptions {
  double proxy_radius_m = 0.0;  // 0: a point proxy; > 0: a sphere (a fingertip) of this radius
  bool force_shading = true;    // needs corner normals in the scene; without them, no effect
  // On the convex pieces of the scene, answer the proxy's sweeps from its last contact
  // (convex_pieces.h): the same contacts, at a cost that does not grow with the model.
  // Off: every sweep walks the grid or the tree (to compare).
  bool convex_pieces = true;
  // A property edit under the hand (a new surface table taken while the proxy presses
  // the same face) does not step the face's push in one tick: the push is the edited
  // face's (its spring or law) times a scale that starts at what was rendered over what
  // the edited face pushes at that depth and goes linearly to 1 over this long, by the
  // session clock (RenderInput::time_s). The scale never makes the push steeper than
  // the device's stable stiffness (where it would, the push steps down, which adds no
  // energy); where the edited face pushes nothing at that depth, its push comes at once,
  // a step down too. Leaving the face
  // or the contact ends the blend. The ramp bounds the force's rate, not the energy an
  // edit stores: a stiffer face held at a depth still holds more (1/2 (k_new - k_old)
  // d^2 for springs), whatever the ramp, once per edit. >= 0, finite; 0: at once.
  double edit_ramp_s = 0.2;
};

struct RenderInput {
  Vec3 position_w = Vec3::Zero();  // device tip, m
  Vec3 velocity_w = Vec3::Zero();  // device tip, m/s (filtered by the device layer)
  double time_s = 0.0;             // session clock, s: vibrations and edit blends run on it
                                   // (a blend waits for it to advance)
};

enum RenderFlags : std::uint32_t {
  kContact = 1u << 0,
  kForceClamped = 1u << 1,
  kStiffnessClamped = 1u << 2,
  kInputFault = 1u << 3,
  kSticking = 1u << 4,  // friction cone: the proxy is stuck to its anchor
  kDampingClamped = 1u << 5,
  kEditBlending = 1u << 6,  // the push blends from before a property edit (edit_ramp_s)
};

struct RenderOutput {
  Vec3 force_w = Vec3::Zero();      // N, to send to the device
  Vec3 proxy_w = Vec3::Zero();      // m
  double normal_force_n = 0.0;      // component of force_w along the contact normal
  double tangential_force_n = 0.0;  // magnitude of the rest
  double friction_force_n = 0.0;    // magnitude of the friction (or cone) part, before clamping
  double texture_force_n = 0.0;     // magnitude of the viscous grating part, before clamping
  double vibration_force_n = 0.0;   // signed vibration along its axis, before clamping
  std::int32_t cad_face = -1;       // touched CAD face, -1 when free
  std::int32_t constraints = 0;     // planes holding the proxy: 1 face, 2 edge, 3 corner
  std::uint32_t flags = 0;          // RenderFlags
};

class ForceRenderer {
 public:
  // Throws std::invalid_argument for null inputs, non-positive limits or workspace scale,
  // a negative or non-finite proxy radius or edit ramp.
  ForceRenderer(std::shared_ptr<const HapticScene> scene,
                std::shared_ptr<const SurfaceTable> surfaces, RenderLimits limits,
                ContactOptions options = {});

  // Control thread: the surface properties to render from the next Render() on (not
  // null; ids beyond it are untagged). Lock-free for the servo thread; tables it no
  // longer uses are freed here, never on the servo thread. Under the hand the face's
  // push blends in (ContactOptions::edit_ramp_s); its damping, friction, texture and
  // vibration, which store no energy, take their new values at once (friction and a
  // friction-level texture still scale with the blended push).
  void SetSurfaces(std::shared_ptr<const SurfaceTable> surfaces);

  // Puts the proxy at `device_w` (or wherever the caller wants it to restart); the next
  // Render() starts from there. A point inside a solid of the scene (a new scene that
  // grew over the old proxy, a session that starts with the device inside a part) is
  // moved just outside, where the part is nearest along six rays, and out of any part
  // touching or overlapping it there (GodObjectProxy::ResetOutside; only where the
  // scene's surface, or each of its pieces, bounds solids: HapticScene::BuildSolids),
  // so the spring pushes the device out instead of holding it in; a sphere that would
  // start sunk into the surface (the device resting on a part), or a point on a face,
  // is moved off it where it can be. No allocation, bounded, but not per-tick work: at most
  // 102 point sweeps across the scene (198 short ones where parts touch), then 5 walks of
  // the tree's boxes within the sphere's radius and 4 short sweeps, or 12 short sweeps for
  // a point (GodObjectProxy::ResetOutside states the bound). The servo loop runs it on the
  // tick that starts a session or takes a new renderer or mapping (servo_loop.h), as
  // does the first Render() after construction. The constructor builds the scene's solid
  // analysis, like its grid or tree.
  void Reset(const Vec3& device_w);

  void Render(const RenderInput& input, RenderOutput* output);

  const HapticScene& scene() const { return *scene_; }
  const RenderLimits& limits() const { return limits_; }
  const ContactOptions& options() const { return options_; }
  const GodObjectProxy& proxy() const { return proxy_; }

 private:
  void RenderContact(const RenderInput& input, RenderOutput* out);
  // The shading normal at the contact, or zero where the constraints' triangles meet at
  // a crease of the CAD model.
  Vec3 SmoothShadingNormal() const;

  // The push's scale at `time_s` after a property edit under the hand (1: none).
  double EditBlendScale(double time_s);

  // Friction cone: returns the point the spring pulls toward (the anchor while sticking).
  // `speed_mps`: the device's speed across the face (a slide that stops sticks again).
  Vec3 ApplyFrictionCone(const SurfaceProperties& surface, double friction_scale,
                         const Vec3& normal, double depth_m, const StripeFrame& stripe,
                         double speed_mps, RenderOutput* out);

  std::shared_ptr<const HapticScene> scene_;
  Handoff<const SurfaceTable> surfaces_handoff_;
  const SurfaceTable* surfaces_ = nullptr;  // the servo thread's
  RenderLimits limits_;
  ContactOptions options_;
  GodObjectProxy proxy_;
  bool started_ = false;
  // friction cone state, local frame
  bool anchored_ = false;
  bool sticking_ = false;
  std::int32_t anchor_face_ = -1;
  Vec3 anchor_l_ = Vec3::Zero();
  // the push as last rendered, to blend from when a property edit comes in under it
  std::int32_t pushed_face_ = -1;  // -1: no contact last tick
  double pushed_depth_m_ = 0.0;
  double pushed_n_ = 0.0;
  double blend_from_ = 1.0;  // the push's scale when the edit came in; 1: no blend
  double blend_start_s_ = 0.0;
};

}  // namespace hapticad
