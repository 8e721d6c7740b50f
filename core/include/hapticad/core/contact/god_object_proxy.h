// SPDX-License-Identifier: GPL-3.0-or-later
// GodObjectProxy: a point or a sphere that follows the device but never crosses the
// surface (Zilles and Salisbury 1995; Ruspini et al. 1997).
//
// Each tick the proxy moves from where it is toward the goal (the device position)
// along a segment, swept as a point (radius 0) or as a sphere. The first triangle the
// sweep touches becomes a constraint plane through the proxy's centre at contact,
// facing the side the proxy came from (surfaces are two-sided: sheets and plates are
// felt from both sides) and offset by `surface_offset` to the free side; the proxy
// stops on that plane and the goal is re-projected onto the constraint set (each sweep
// looks one offset past its target, so a goal on a face's plane still meets the face:
// the proxy never ends a tick on a face, where the next sweep could not tell its side).
// This repeats until the sweep is free or three planes bind (a concave corner), so the
// proxy can never pass through anything, however far the device moves in one tick.
//
// Temporal coherence: each sweep tests the last contact's triangle first (the last
// tick's, then the one the sweep before found), and on a convex piece of the surface
// (ProxyConfig::pieces) that contact, or one round it, usually proves itself the first
// (or the sweep provably free) without walking the tree or the grid at all: the tick then
// costs the same on a thousand triangles as on a million. Elsewhere every sweep carries
// the planes it cannot cross (the constraints found so far, and the plane of the best
// contact so far): triangles under them are skipped without a contact test.
//
// Frame and units: the scene's local frame, metres. Update() is servo-tick safe: no
// allocation, no lock, bounded work (at most kMaxIterations sweeps).
#pragma once

#include "hapticad/core/contact/constraint_set.h"
#include "hapticad/core/geometry/convex_pieces.h"
#include "hapticad/core/geometry/solid_analysis.h"
#include "hapticad/core/geometry/triangle_grid.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/geometry/triangle_tree.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct ProxyConfig {
  double radius_m = 0.0;           // 0: a point proxy; > 0: a sphere of this radius
  double surface_offset_m = 1e-8;  // how far off the surface the proxy rests (> 0)
  double bary_tolerance = 1e-9;    // inclusive edge tolerance of the triangle test
  // Whether (and where) the surface bounds solids, for ResetOutside; must outlive the
  // proxy. Null: it never moves the proxy.
  const SolidAnalysis* solids = nullptr;
  // The mesh's convex pieces (convex_pieces.h), built on the same mesh; must outlive
  // the proxy. On them a sweep is answered from the triangles round the last contact,
  // and the tree or the grid is walked only when that proves nothing. Null: every sweep
  // walks.
  const ConvexPieces* pieces = nullptr;
};

class GodObjectProxy {
 public:
  static constexpr int kMaxIterations = 4;

  // A proxy of any radius whose sweeps walk CGAL's tree. `mesh` and `tree` must outlive
  // the proxy. Throws std::invalid_argument for a negative or non-finite radius or a
  // non-positive offset.
  GodObjectProxy(const TriangleMesh& mesh, const TriangleTree& tree, ProxyConfig config);
  // A point proxy (radius 0) whose sweeps walk the grid's cells: the same contacts, at
  // a cost that does not grow with the model. Throws std::invalid_argument as above and
  // for a radius other than 0.
  GodObjectProxy(const TriangleMesh& mesh, const TriangleGrid& grid, ProxyConfig config);

  // Places the proxy at `position_l` without collision (the caller knows it is free).
  void Reset(const Vec3& position_l);

  // Places the proxy at `position_l` unless that point lies inside a solid of the
  // scene (config.solids; otherwise, or when the point lies in no piece's box, this is
  // Reset): then just outside, off the face where the nearest of six fixed rays leaves
  // the solids. Inside is decided ray by ray, by majority, so a ray through a silhouette
  // edge cannot decide alone: by the parity of its crossings where the whole surface
  // bounds solids, and where parts touch or overlap by how the pieces it meets wind
  // round the point (each piece's crossings counted alone), the ray's exit then being
  // where they stop winding round it (out of both of two parts face to face, not into
  // the second). A sphere goes one radius off the face, and only where a point swept
  // across its diameter from that face meets nothing (else the next nearest ray, else
  // it stays). Then, where inside is known (the point was found outside, or was moved
  // out), a sphere less than a radius from the surface (a device that starts resting on
  // a part) is moved off it, to one radius and the offset from the nearest point,
  // straight away from it, and again from there, up to kMaxClearSteps times (out of a
  // crease); where its centre would pass through the surface on the way (a slot
  // narrower than the sphere), or it still overlaps after the steps, it is left where
  // it was. A point within half the offset of a face's plane (a scripted probe started
  // on a surface point) goes to the offset on the side the face's winding faces (away
  // from a solid): on the plane itself its first sweep could not tell its side, and
  // lifted off it would be held inside. An open piece of the surface (a sheet beside
  // the parts) bounds nothing and is never a reason to move: a sphere whose nearest
  // point is on one is left where it was, and a point on one stays. Returns whether
  // the proxy was moved. No allocation and bounded (at most kExitRays * (kMaxCrossings
  // + 1) + kExitRays point sweeps across the scene, or kMaxWindingSweeps + kExitRays
  // short ones where parts touch; then kMaxClearSteps + 1 walks of the tree's boxes
  // within a radius and kMaxClearSteps point sweeps a radius long, or 3 kMaxClearSteps
  // point sweeps two offsets long), but not per-tick work: for a new scene, or the
  // start of a session, where the device may be anywhere.
  bool ResetOutside(const Vec3& position_l);
  static constexpr int kExitRays = 6;
  static constexpr int kMaxCrossings = 15;  // a ray crossing more abstains
  // Where parts touch: the pieces one ray looks at (a ray meeting more boxes knows
  // nothing beyond the last one's start), and the sweeps all rays may take together.
  static constexpr int kMaxRayPieces = 8;
  static constexpr int kMaxWindingSweeps = 2 * kExitRays * (kMaxCrossings + 1);
  static constexpr int kMaxClearSteps = 4;

  // Moves the proxy toward `goal_l`, constrained by the surface.
  void Update(const Vec3& goal_l);

  // First contact of the proxy's shape swept from a to b. `floors` and `hint` as in
  // SweepQuery. Servo-tick safe.
  bool FirstHit(const Vec3& a, const Vec3& b, SweepHit* hit, const SweepFloors* floors = nullptr,
                std::int64_t hint = -1);

  // Sweeps run so far, and how many of them the convex pieces settled without a walk.
  std::uint64_t sweeps() const { return sweeps_; }
  std::uint64_t settled_sweeps() const { return settled_sweeps_; }

  const Vec3& position() const { return position_; }
  const ConstraintSet& constraints() const { return constraints_; }
  bool in_contact() const { return constraints_.count() > 0; }
  const ProxyConfig& config() const { return config_; }
  // Where the proxy touches the first constraint's triangle: its centre less the radius
  // along the plane's normal. Precondition: in_contact().
  Vec3 contact_point() const { return position_ - config_.radius_m * constraints_.plane(0).normal; }

 private:
  struct Exit {
    double distance;
    SweepHit hit;
  };
  // ResetOutside's two parts: out of the solids, then off the surface (true if it
  // moved): a sphere it overlaps, a point within half the offset of a face.
  enum class SolidExit { kUnknown, kNotInside, kMovedOut, kStuckInside };
  SolidExit MoveOutOfSolids(const Vec3& position_l);
  bool ClearSurface();
  bool ClearSphere();
  bool ClearPoint();
  // Whether the triangle belongs to an open piece of the surface (config.solids).
  bool OnOpenPiece(std::uint32_t triangle) const;
  // ResetOutside's rays where the whole surface bounds solids, and where its pieces do:
  // the exits of the rays that find p inside, or 0 if most find it outside.
  int FindExitsByParity(const Vec3& p, Exit* exits) const;
  int FindExitsByWinding(const Vec3& p, Exit* exits) const;
  // The surface crossings from a0 toward end along unit u (only piece `piece`'s if
  // piece_of_vertex is given), in order in hits[0, kMaxCrossings); -1 for more.
  int WalkCrossings(const Vec3& a0, const Vec3& end, const Vec3& u,
                    const std::uint32_t* piece_of_vertex, std::uint32_t piece,
                    SweepHit* hits) const;
  // A point's first contact on a -> b, through the grid or the tree (one piece's alone
  // if piece_of_vertex is given).
  bool PointHit(const Vec3& a, const Vec3& b, SweepHit* hit,
                const std::uint32_t* piece_of_vertex = nullptr, std::uint32_t piece = 0) const;
  bool Sweep(const Vec3& a, const Vec3& b, double radius, const SweepFloors* floors,
             std::int64_t hint, SweepHit* hit, const std::uint32_t* piece_of_vertex = nullptr,
             std::uint32_t piece = 0) const;

  const TriangleMesh& mesh_;
  const TriangleTree* tree_ = nullptr;  // exactly one of the two
  const TriangleGrid* grid_ = nullptr;
  ProxyConfig config_;
  Vec3 position_ = Vec3::Zero();
  ConstraintSet constraints_;
  std::int64_t last_triangle_ = -1;  // the last first contact (since Reset): tested first
  TriangleGrid::Prefetch warm_up_;   // the cell ahead of the proxy, being loaded
  static constexpr std::uint32_t kNoTriangle = ~std::uint32_t{0};
  std::uint32_t warmed_triangle_ = kNoTriangle;  // ConvexPieces::WarmUp's last triangle
  int warm_step_ = 0;  // its next step (ConvexPieces::kWarmUpSteps: all done)
  mutable std::uint64_t sweeps_ = 0;
  mutable std::uint64_t settled_sweeps_ = 0;
};

}  // namespace hapticad
