// SPDX-License-Identifier: GPL-3.0-or-later
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

ProxyConfig MakeProxyConfig(const HapticScene& scene) {
  ProxyConfig config;
  config.surface_offset_m = scene.surface_offset_m();
  return config;
}

}  // namespace

ForceRenderer::ForceRenderer(std::shared_ptr<const HapticScene> scene,
                             std::shared_ptr<const SurfaceTable> surfaces, RenderLimits limits)
    : scene_(std::move(scene)),
      surfaces_(std::move(surfaces)),
      limits_(limits),
      proxy_(Checked(scene_).mesh(), scene_->tree(), MakeProxyConfig(*scene_)) {
  if (!surfaces_) throw std::invalid_argument("force renderer: no surface table");
  if (!(limits_.max_force_n > 0.0) || !(limits_.max_stiffness_n_per_m > 0.0)) {
    throw std::invalid_argument("force renderer: device limits must be > 0");
  }
}

void ForceRenderer::Reset(const Vec3& device_w) {
  proxy_.Reset(scene_->ToLocal(device_w));
  started_ = true;
}

void ForceRenderer::Render(const RenderInput& input, RenderOutput* out) {
  *out = RenderOutput{};
  if (!input.position_w.allFinite() || !input.velocity_w.allFinite()) {
    out->flags = kInputFault;
    out->proxy_w = scene_->ToWorld(proxy_.position());
    return;
  }
  if (!started_) Reset(input.position_w);

  const Vec3 goal_l = scene_->ToLocal(input.position_w);
  proxy_.Update(goal_l);
  out->proxy_w = scene_->ToWorld(proxy_.position());
  if (!proxy_.in_contact()) return;

  const std::uint32_t triangle = proxy_.constraints().plane(0).triangle;
  out->cad_face = scene_->mesh().cad_face(triangle);
  const SurfaceProperties& surface = surfaces_->surface(out->cad_face);
  out->flags |= kContact;

  double k = surface.stiffness_n_per_m;
  if (k > limits_.max_stiffness_n_per_m) {
    k = limits_.max_stiffness_n_per_m;
    out->flags |= kStiffnessClamped;
  }
  // spring from the device to the proxy; its direction is the contact normal
  const Vec3 spring = k * (proxy_.position() - goal_l);
  const double f_n = spring.norm();
  const Vec3 normal = f_n > 0.0 ? Vec3(spring / f_n) : proxy_.constraints().plane(0).normal;
  const Vec3 v_t = input.velocity_w - input.velocity_w.dot(normal) * normal;
  Vec3 force = spring + CalcFrictionForce(surface.friction, f_n, v_t);

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
