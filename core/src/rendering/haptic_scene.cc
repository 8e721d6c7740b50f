// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/rendering/haptic_scene.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hapticad {

std::shared_ptr<const HapticScene> HapticScene::Build(const TriangleSoup& input,
                                                      double metres_per_unit,
                                                      const SceneOptions& options) {
  if (!(std::isfinite(metres_per_unit) && metres_per_unit > 0.0)) {
    throw std::invalid_argument("haptic scene: metres per unit must be finite and > 0, got " +
                                std::to_string(metres_per_unit));
  }
  if (input.vertices.empty()) throw std::invalid_argument("haptic scene: no vertices");
  if (!(std::isfinite(options.refine_edge) && options.refine_edge >= 0.0)) {
    throw std::invalid_argument("haptic scene: the refinement edge length must be finite and >= 0");
  }
  RepairReport report;
  TriangleSoup prepared;
  const TriangleSoup* source = &input;
  if (options.repair) {
    prepared = RepairSoup(input, options.repair_options, &report);
    source = &prepared;
  }
  if (options.refine_edge > 0.0) {
    prepared = RefineSoup(*source, options.refine_edge);
    source = &prepared;
  }
  const TriangleSoup& soup = *source;
  // the local origin is taken in model units, before scaling, so far-away parts keep
  // their digits
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) {
    const Vec3& p = soup.vertices[v];
    if (!p.allFinite()) {
      throw std::invalid_argument("haptic scene: vertex " + std::to_string(v) + " is not finite");
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 origin_model = 0.5 * (lo + hi);
  std::vector<Vec3> local(soup.vertices.size());
  for (std::size_t v = 0; v < local.size(); ++v) {
    local[v] = (soup.vertices[v] - origin_model) * metres_per_unit;
  }
  std::shared_ptr<HapticScene> scene(new HapticScene());
  scene->metres_per_unit_ = metres_per_unit;
  scene->origin_w_ = origin_model * metres_per_unit;
  scene->size_m_ = (hi - lo).norm() * metres_per_unit;
  scene->repair_report_ = report;
  if (!(scene->size_m_ > 0.0)) throw std::invalid_argument("haptic scene: all vertices coincide");
  scene->mesh_ = TriangleMesh::Build(local, soup.triangles, soup.cad_faces, soup.corner_normals);
  return scene;
}

// Boxes and cells grow by a hair (relative to the scene), so a segment along a box face
// or a cell wall is not lost to rounding.
const TriangleTree& HapticScene::BuildTree() const {
  std::call_once(tree_once_, [this] {
    tree_ = TriangleTree::Build(*mesh_, 1e-9 * size_m_);
    tree_built_.store(tree_.get(), std::memory_order_release);
  });
  return *tree_;
}

const TriangleGrid& HapticScene::BuildGrid() const {
  std::call_once(grid_once_, [this] {
    grid_ = TriangleGrid::Build(*mesh_, 1e-9 * size_m_);
    grid_built_.store(grid_.get(), std::memory_order_release);
  });
  return *grid_;
}

// Convex within 1e-13 of the scene: a ten-thousandth of the resting offset
// (surface_offset_m), some thousand rounding steps of the local coordinates.
const ConvexPieces& HapticScene::BuildPieces() const {
  std::call_once(pieces_once_, [this] {
    pieces_ = ConvexPieces::Build(*mesh_, 1e-13 * size_m_);
    pieces_built_.store(pieces_.get(), std::memory_order_release);
  });
  return *pieces_;
}

const SolidAnalysis& HapticScene::BuildSolids() const {
  std::call_once(solids_once_, [this] {
    solids_ = AnalyseSolids(*mesh_);
    solids_built_.store(&solids_, std::memory_order_release);
  });
  return solids_;
}

std::size_t HapticScene::CalcMemoryBytes() const {
  std::size_t bytes = mesh_->CalcMemoryBytes();
  if (const TriangleTree* tree = tree_built_.load(std::memory_order_acquire)) {
    bytes += tree->CalcMemoryBytes();
  }
  if (const TriangleGrid* grid = grid_built_.load(std::memory_order_acquire)) {
    bytes += grid->CalcMemoryBytes();
  }
  if (const ConvexPieces* pieces = pieces_built_.load(std::memory_order_acquire)) {
    bytes += pieces->CalcMemoryBytes();
  }
  if (const SolidAnalysis* solids = solids_built_.load(std::memory_order_acquire)) {
    bytes += solids->CalcMemoryBytes();
  }
  return bytes;
}

SurfaceSample HapticScene::CalcClosestPoint(const Vec3& p_w) const {
  // (beyond a million sizes the answer means nothing, and far enough the projection's
  // squares overflow)
  const Vec3 p_l = ToLocal(p_w);
  if (!(p_l.norm() <= kClosestPointReach * size_m_)) {
    throw std::invalid_argument(
        "haptic scene: the point to find the closest surface point to is not finite, or "
        "more than a million times the part's size from it");
  }
  const SurfacePoint closest = BuildTree().CalcClosestPoint(p_l);
  SurfaceSample out;
  out.point_w = ToWorld(closest.point);
  out.triangle = closest.triangle;
  out.cad_face = mesh_->cad_face(closest.triangle);
  out.distance_m = closest.distance;
  out.normal_w = mesh_->CalcShadingNormal(closest.triangle, closest.point);
  return out;
}

}  // namespace hapticad
