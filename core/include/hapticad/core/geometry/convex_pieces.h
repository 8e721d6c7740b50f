// SPDX-License-Identifier: GPL-3.0-or-later
// ConvexPieces: the pieces of the surface that bound a convex solid, and how a sweep
// that starts at its last contact on one of them is answered from the triangles round
// that contact alone, in a time that does not depend on the size of the model.
//
// Why that is exact. Let K be the solid a convex piece bounds, and let nothing else lie
// within the sweep's reach (its segment's box grown by the radius, inside the piece's
// clear box). If no vertex of the piece lies above a plane, neither does K, and a sphere
// (or a point: radius 0) whose centre stays more than its radius above that plane
// touches nothing. So a contact found at s, whose centre is then exactly its radius
// above the plane through the contact point across the contact normal n, and which
// moves toward it (n . d < 0), is the first contact when no vertex rises above that
// plane: a face's own plane is one (seen from outside, the winding's side); for an edge
// or a vertex, the highest vertex along n is found by climbing from vertex to higher
// neighbouring vertex (on a convex polytope a vertex with no higher neighbour is the
// highest). Likewise a sweep that stays its radius above such a plane all along (the
// last contact's face, or a floor from a proven contact) touches nothing at all.
// Settle() tries these proofs on the sweep's hint (the last contact) and, when the
// contact has moved on, on the triangles round it, across its edges first; what it
// cannot prove it leaves to the tree or the grid, which continue the same SweepSearch.
//
// Which pieces qualify (Build, O(n)): a connected piece that is closed, has every edge
// convex or flat seen from the side its triangles' winding faces (within `tolerance`)
// and a single turn of triangles round every vertex: it is locally convex everywhere,
// so it bounds a convex solid (van Heijenoort's theorem: a closed, locally convex
// immersed surface is convex), with the winding's normals pointing out of it. (A
// degenerate triangle, with no normal, fails the turn test.) Other pieces, convex or
// not, bound a piece's room: only sweeps whose reach stays in the box that holds none
// of their boxes are settled here. Up to 1,024 pieces every room is bounded against
// every other piece; beyond, against those in a slab round it, the room cut to the
// slab (20,000 pieces: 3.4 s all against all, 0.14-0.23 s in slabs).
//
// Units and frame: the mesh's. Build allocates (before the loop); Settle is servo-tick
// safe: no allocation, no lock, bounded work.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "hapticad/core/geometry/sweep_query.h"
#include "hapticad/core/geometry/sweep_search.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/huge_page_allocator.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

class ConvexPieces {
 public:
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  // Steps of the climb to the highest vertex along a direction before it gives up.
  static constexpr int kMaxClimb = 16;
  // Triangles round one vertex that a fan walk visits at most.
  static constexpr int kMaxFan = 256;
  // Steps of the walk toward where a sweep meets the surface.
  static constexpr int kMaxWalk = 4;

  // `mesh` must outlive the pieces. `tolerance` (model units, finite, >= 0, above the
  // rounding of the coordinates: the scene's local frame keeps them small): how far a
  // vertex may rise above a neighbouring triangle's plane for their edge to count as
  // flat. Settle's answer may differ from an exhaustive search of every triangle by
  // contacts no deeper than this, and by contacts of no depth at all: a sphere that
  // grazes an edge at exactly its radius, and the strip by which the triangle test
  // widens a triangle (SweepQuery::bary_tol, 1e-9 of it) beyond an edge, where no
  // geometry is. Throws std::invalid_argument for any other tolerance.
  static std::unique_ptr<ConvexPieces> Build(const TriangleMesh& mesh, double tolerance);

  // Tries to settle the sweep `search` runs for `query` (which has tested query.hint):
  // true when the search's answer, a contact or none, is the sweep's first contact with
  // the whole mesh. False leaves the search as it is, possibly with more triangles
  // tested, for an exhaustive walk to continue. Only a query whose hint lies on a convex
  // piece can be settled; its floors (SweepQuery) must hold as stated. Servo-tick safe.
  bool Settle(const SweepQuery& query, SweepSearch* search) const;

  // Warms the caches for the triangles a sweep from triangle t (the last contact) reads
  // when the contact moves on: those across t's edges and those across theirs (pieces,
  // corners, neighbours, normals and vertices), so a contact sliding on finds them loaded. It reads
  // them rather than prefetching (a prefetch may be dropped: the 1M-triangle tail was a
  // fifth shorter with loads), in kWarmUpSteps steps, one a tick, each needing only what
  // the step before loaded: step 0 the triangles across t's edges with their vertices,
  // step 1 those across theirs, step 2 their vertices. A tick then waits for one round
  // of misses, not two in a row (1M p99 point 0.72 against 0.93 us all in one tick,
  // sphere 1.10 against 1.28; BENCHMARKS.md). `step` in [0, kWarmUpSteps). No
  // allocation, no lock: servo-tick safe. Returns whether it warmed anything: not for a
  // triangle off the convex pieces.
  static constexpr int kWarmUpSteps = 3;
  bool WarmUp(std::uint32_t t, int step) const;

  // The convex piece triangle t belongs to, or kNone.
  std::uint32_t piece(std::uint32_t t) const { return t < piece_.size() ? piece_[t] : kNone; }
  std::size_t num_pieces() const { return clear_lo_.size(); }
  // Piece p's room: the open box that holds no other piece's box (infinite along the
  // axes where nothing else lies; it may cut into p's own box where another's overlaps it).
  const Vec3& clear_lo(std::uint32_t p) const { return clear_lo_[p]; }
  const Vec3& clear_hi(std::uint32_t p) const { return clear_hi_[p]; }
  double tolerance() const { return tolerance_; }
  std::size_t CalcMemoryBytes() const;

 private:
  ConvexPieces() = default;
  // Whether no vertex of the piece lies above the plane normal . x = offset (within the
  // tolerance), climbing from vertex `start`. False also when the climb is too long.
  bool BoundsPiece(const Vec3& normal, double offset, std::uint32_t start) const;
  // Whether the search's best contact is provably the first (see above); on an edge or
  // a vertex that takes a climb, done only if `climb`.
  bool IsFirstContact(const SweepQuery& query, const SweepSearch& search, std::uint32_t piece,
                      bool climb) const;
  // Whether the sweep stays its radius above the hint's plane, or above a floor's plane
  // that bounds the piece: then it touches nothing.
  bool IsClear(const SweepQuery& query, std::uint32_t hint) const;
  // Tests triangle u; whether it is then the best contact, on its face, proven first.
  bool IsProvenOnFace(std::uint32_t u, const SweepQuery& query, std::uint32_t piece,
                      SweepSearch* search) const;
  // Walks from triangle t (already tested) toward where the sweep meets the surface,
  // across the edge it passes beyond (up to kMaxWalk steps; not back across the edge it
  // came over), and tests the triangle it lands over: whether that one proved itself on
  // its face. Triangles passed over are not tested, but for the two either side of an
  // edge it would cross back over, and the last if the steps run out: the caller's climb
  // and search round the contact start from them.
  bool Walk(std::uint32_t t, const SweepQuery& query, std::uint32_t piece,
            SweepSearch* search) const;
  // Tests every triangle sharing a vertex with triangle t until one proves itself on
  // its face: returns whether one did.
  bool SearchAround(std::uint32_t t, const SweepQuery& query, std::uint32_t piece,
                    SweepSearch* search) const;
  // The edge of triangle t (0 to 2) the sweep passes furthest beyond where its centre
  // comes within its radius of t's plane (or at its end), or -1 if none.
  int ExitEdge(std::uint32_t t, const SweepQuery& query) const;
  // Whether the triangles round vertex v turn once round it, each counter-clockwise
  // seen from outside: projected on the plane across the sum of their planes' normals
  // (each plane once), or if not every normal leans toward that, across the direction
  // away from the mean of v's neighbours (every normal must lean toward the one taken;
  // either does at a convex vertex), a direction inside the first
  // corner lies inside exactly one corner. A second turn (triangles wrapping round a
  // vertex twice, every edge convex) would make a surface that only looks convex edge
  // by edge. For the build.
  bool TurnsOnce(std::uint32_t v) const;
  // Calls visit(u) for every triangle u round vertex v, starting from triangle t (which
  // holds v); false if the fan is longer than kMaxFan.
  template <class Visit>
  bool ForEachAround(std::uint32_t v, std::uint32_t t, Visit&& visit) const;

  const TriangleMesh* mesh_ = nullptr;
  double tolerance_ = 0.0;
  // read at random by the servo tick: on huge pages, like the mesh's arrays (and none
  // at all when no piece is convex: a scene holds only what it can use)
  HugePageVector<std::uint32_t> piece_;          // per triangle: its convex piece, or kNone
  HugePageVector<std::uint32_t> vertex_corner_;  // per vertex: a triangle holding it
  std::vector<Vec3> clear_lo_;                   // per convex piece
  std::vector<Vec3> clear_hi_;
};

}  // namespace hapticad
