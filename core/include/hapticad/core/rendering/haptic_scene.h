// SPDX-License-Identifier: GPL-3.0-or-later
// HapticScene: the immutable geometry the servo loop touches — the mesh in a local
// frame, the structures that find contacts on it, and the frame's placement.
//
// Frames and units: the input soup is in model units (FreeCAD: mm); the scene stores it
// in metres relative to a local origin (the centre of the soup's bounding box), so a
// part modelled 1e6 units from the world origin loses no precision. Device positions
// arrive in world metres and are shifted by origin_w() before any geometry runs.
// Tolerances are relative to the scene's size (size_m()), so the same part behaves the
// same in mm, in m, or far away.
//
// Build() runs before the loop starts (it repairs the soup and builds the mesh,
// allocates and can take seconds on large meshes). The contact structures are built on
// first request, BuildTree() and BuildGrid(), since a scene needs only what its users
// ask for: a point proxy sweeps through the grid, a sphere proxy and closest-point
// queries through CGAL's AABB tree, and a point proxy on a 1M-triangle part need never
// pay for the tree. A ForceRenderer builds what its proxy uses when it is made, so the
// servo tick never builds. Everything else is a cheap accessor.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>

#include "hapticad/core/geometry/convex_pieces.h"
#include "hapticad/core/geometry/mesh_refine.h"
#include "hapticad/core/geometry/mesh_repair.h"
#include "hapticad/core/geometry/solid_analysis.h"
#include "hapticad/core/geometry/triangle_grid.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/geometry/triangle_soup.h"
#include "hapticad/core/geometry/triangle_tree.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

// A point on the surface, world frame.
struct SurfaceSample {
  Vec3 point_w;
  Vec3 normal_w;  // unit; from the corner normals where given, else the winding
  std::uint32_t triangle;
  std::int32_t cad_face;
  double distance_m;  // from the query point
};

struct SceneOptions {
  // Run RepairSoup first (a soup known to be clean, e.g. generated, may skip it).
  bool repair = true;
  RepairOptions repair_options;
  // Split edges longer than this (model units) after the repair (mesh_refine.h); 0: no.
  double refine_edge = 0.0;
};

class HapticScene {
 public:
  // `metres_per_unit` > 0 converts the soup's units (1e-3 for mm). Throws
  // std::invalid_argument with a message naming what is wrong with the input (or what
  // the repair could not mend).
  static std::shared_ptr<const HapticScene> Build(const TriangleSoup& soup, double metres_per_unit,
                                                  const SceneOptions& options = {});

  const TriangleMesh& mesh() const { return *mesh_; }
  // The structure, built by the first call (whichever thread makes it; the others
  // wait), the same one returned by every later call. Not for the servo tick.
  const TriangleTree& BuildTree() const;
  const TriangleGrid& BuildGrid() const;
  // Whether the surface bounds solids, and its pieces (solid_analysis.h): what a proxy
  // restarting inside a part needs. Built like the structures, by the first call.
  const SolidAnalysis& BuildSolids() const;
  // The pieces that bound convex solids (convex_pieces.h), where a proxy's sweep is
  // answered from its last contact. Built like the structures, by the first call.
  const ConvexPieces& BuildPieces() const;

  const Vec3& origin_w() const { return origin_w_; }
  double metres_per_unit() const { return metres_per_unit_; }
  // Diagonal of the bounding box, metres.
  double size_m() const { return size_m_; }
  // How far off the surface the proxy rests: 1e-9 of the scene's size, some 1e7
  // rounding steps of the local coordinates, yet a force bias k * offset below 1 uN for
  // a 0.2 m part at 3 N/mm.
  double surface_offset_m() const { return 1e-9 * size_m_; }

  // Closest surface point to `p_w` (world, m). Not for the servo tick (the first call
  // builds the tree, and a point far from the surface visits many boxes); used to set
  // up strokes and to label points. Throws std::invalid_argument if `p_w` is not finite
  // or further than kClosestPointReach sizes (size_m) from the scene's origin.
  static constexpr double kClosestPointReach = 1e6;
  SurfaceSample CalcClosestPoint(const Vec3& p_w) const;

  Vec3 ToLocal(const Vec3& p_w) const { return p_w - origin_w_; }
  Vec3 ToWorld(const Vec3& p_l) const { return p_l + origin_w_; }

  // What the repair did and left undone (all zero when it was skipped).
  const RepairReport& repair_report() const { return repair_report_; }

  // The mesh and the structures built so far.
  std::size_t CalcMemoryBytes() const;

 private:
  HapticScene() = default;

  std::unique_ptr<TriangleMesh> mesh_;
  // declared after mesh_: destroyed first; published through the atomics once built
  mutable std::once_flag tree_once_;
  mutable std::once_flag grid_once_;
  mutable std::once_flag solids_once_;
  mutable std::once_flag pieces_once_;
  mutable SolidAnalysis solids_;
  mutable std::unique_ptr<TriangleTree> tree_;
  mutable std::unique_ptr<TriangleGrid> grid_;
  mutable std::unique_ptr<ConvexPieces> pieces_;
  mutable std::atomic<const TriangleTree*> tree_built_{nullptr};
  mutable std::atomic<const TriangleGrid*> grid_built_{nullptr};
  mutable std::atomic<const ConvexPieces*> pieces_built_{nullptr};
  mutable std::atomic<const SolidAnalysis*> solids_built_{nullptr};
  Vec3 origin_w_ = Vec3::Zero();
  double metres_per_unit_ = 1.0;
  double size_m_ = 0.0;
  RepairReport repair_report_;
};

}  // namespace hapticad
