// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: GodObjectProxy::Update and FirstHit run on the servo thread every tick.
#include "hapticad/core/contact/god_object_proxy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hapticad {
namespace {

bool FiniteNonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

void CheckConfig(const ProxyConfig& config) {
  if (!FiniteNonNegative(config.radius_m) || !(config.surface_offset_m > 0.0) ||
      !std::isfinite(config.surface_offset_m)) {
    throw std::invalid_argument("proxy: the radius must be finite and >= 0, the offset > 0");
  }
}

}  // namespace

GodObjectProxy::GodObjectProxy(const TriangleMesh& mesh, const TriangleTree& tree,
                               ProxyConfig config)
    : mesh_(mesh), tree_(&tree), config_(config) {
  CheckConfig(config_);
}

GodObjectProxy::GodObjectProxy(const TriangleMesh& mesh, const TriangleGrid& grid,
                               ProxyConfig config)
    : mesh_(mesh), grid_(&grid), config_(config) {
  CheckConfig(config_);
  if (config_.radius_m != 0.0) {
    throw std::invalid_argument(
        "proxy: the grid answers a point proxy only; a sphere needs the tree");
  }
}

void GodObjectProxy::Reset(const Vec3& position_l) {
  position_ = position_l;
  constraints_.Clear();
  last_triangle_ = -1;
  warmed_triangle_ = kNoTriangle;
  warm_step_ = 0;
}

namespace {

// three orthonormal directions (15 times the rows of a rotation) and their opposites,
// askew to every axis and axis plane, so no ray runs along an axis-aligned CAD model's
// faces
constexpr double kAxes[3][3] = {{-11.0, -2.0, 10.0}, {10.0, -5.0, 10.0}, {2.0, 14.0, 5.0}};

Vec3 ExitRay(int ray) {
  const double* axis = kAxes[ray / 2];
  return (ray % 2 == 0 ? 1.0 : -1.0) / 15.0 * Vec3(axis[0], axis[1], axis[2]);
}

// Where the ray p + t u (t >= 0) is inside the box [lo, hi]: false if nowhere.
bool ClipRayToBox(const Vec3& p, const Vec3& u, const Vec3& lo, const Vec3& hi, double* enter,
                  double* leave) {
  double t0 = 0.0;
  double t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (u[k] == 0.0) {
      if (p[k] < lo[k] || p[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - p[k]) / u[k];
    double b = (hi[k] - p[k]) / u[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  *enter = t0;
  *leave = t1;
  return t0 <= t1;
}

}  // namespace

bool GodObjectProxy::ResetOutside(const Vec3& position_l) {
  switch (MoveOutOfSolids(position_l)) {
    case SolidExit::kUnknown:      // nothing is known of inside: as documented, a Reset
    case SolidExit::kStuckInside:  // pushing it off the nearest face would push it in
      return false;
    case SolidExit::kMovedOut:
      ClearSurface();
      return true;
    case SolidExit::kNotInside:
      break;
  }
  return ClearSurface();
}

bool GodObjectProxy::OnOpenPiece(std::uint32_t triangle) const {
  const SolidAnalysis* solids = config_.solids;
  if (solids == nullptr || solids->piece_of_vertex.empty()) return false;  // all closed
  const std::uint32_t piece = solids->piece_of_vertex[mesh_.triangle(triangle)[0]];
  return solids->piece_winding[piece] == 0;
}

bool GodObjectProxy::ClearSurface() {
  return config_.radius_m > 0.0 ? ClearSphere() : ClearPoint();
}

bool GodObjectProxy::ClearPoint() {
  const double offset = config_.surface_offset_m;
  bool moved = false;
  for (int step = 0; step < kMaxClearSteps; ++step) {
    // a face within the offset is met by a short segment through the point along one
    // of three skew directions (a point on the face: by all three)
    bool near = false;
    for (int ray = 0; ray < kExitRays && !near; ray += 2) {
      const Vec3 u = ExitRay(ray);
      SweepHit hit;
      if (!PointHit(position_ - offset * u, position_ + offset * u, &hit)) continue;
      if (OnOpenPiece(hit.triangle)) continue;          // a sheet has no outside to go to
      const Vec3& n = mesh_.face_normal(hit.triangle);  // the winding's: away from a solid
      const double height = n.dot(position_ - hit.point);
      if (std::abs(height) >= 0.5 * offset) continue;
      Reset(position_ + (offset - height) * n);
      near = moved = true;
    }
    if (!near) break;
  }
  return moved;
}

bool GodObjectProxy::ClearSphere() {
  if (tree_ == nullptr) return false;
  const double r = config_.radius_m;
  const Vec3 start = position_;
  for (int step = 0; step <= kMaxClearSteps; ++step) {
    SurfacePoint nearest;
    if (!tree_->FindClosestPointWithin(position_, r, &nearest)) return step > 0;  // clear
    if (step == kMaxClearSteps || OnOpenPiece(nearest.triangle)) break;
    // straight away from the nearest point (round an edge or a corner too); from a centre
    // on the surface itself, along the face's winding normal
    Vec3 out = position_ - nearest.point;
    const double length = out.norm();
    out = length > 0.0 ? Vec3(out / length) : mesh_.face_normal(nearest.triangle);
    const Vec3 next = nearest.point + (r + config_.surface_offset_m) * out;
    // never through the surface: in a slot narrower than the sphere, the far wall
    SweepHit blocked;
    if (PointHit(position_, next, &blocked)) break;
    Reset(next);
  }
  Reset(start);  // no way off the surface: left where it was
  return false;
}

GodObjectProxy::SolidExit GodObjectProxy::MoveOutOfSolids(const Vec3& position_l) {
  Reset(position_l);
  const SolidAnalysis* solids = config_.solids;
  if (solids == nullptr || !solids->pieces_bound_solids || !position_l.allFinite()) {
    return SolidExit::kUnknown;
  }
  // outside every piece's box: outside every solid
  if (!solids->InAnySolidPiece(position_l)) return SolidExit::kNotInside;
  Exit exits[kExitRays];
  const int found = solids->bounds_solids ? FindExitsByParity(position_l, exits)
                                          : FindExitsByWinding(position_l, exits);
  if (found == 0) return SolidExit::kNotInside;
  // nearest first; an insertion sort of at most six (std::sort's path for more than 16,
  // dead here, draws GCC 12's -Warray-bounds)
  for (int i = 1; i < found; ++i) {
    for (int j = i; j > 0 && exits[j].distance < exits[j - 1].distance; --j) {
      std::swap(exits[j], exits[j - 1]);
    }
  }
  const double r = config_.radius_m;
  const double offset = config_.surface_offset_m;
  for (int i = 0; i < found; ++i) {
    // off the face it crossed, on the far side (the hit's normal faces the inside)
    const Vec3& face = exits[i].hit.point;
    const Vec3 out = -exits[i].hit.normal;
    SweepHit blocked;
    if (r > 0.0 && PointHit(face + offset * out, face + (2.0 * r + offset) * out, &blocked)) {
      continue;  // a sphere there would stick into something else
    }
    Reset(face + (r + offset) * out);
    return SolidExit::kMovedOut;
  }
  return SolidExit::kStuckInside;
}

int GodObjectProxy::FindExitsByParity(const Vec3& p, Exit* exits) const {
  int inside = 0;
  int outside = 0;
  SweepHit hits[kMaxCrossings];
  for (int ray = 0; ray < kExitRays; ++ray) {
    const Vec3 u = ExitRay(ray);
    const Vec3 end = p + (p.norm() + mesh_.bounding_radius()) * u;  // beyond every vertex
    const int crossings = WalkCrossings(p, end, u, nullptr, 0, hits);
    if (crossings < 0) continue;
    if (crossings % 2 == 0) {
      ++outside;
      continue;
    }
    exits[inside++] = {(hits[0].point - p).norm(), hits[0]};
  }
  return inside > outside ? inside : 0;
}

int GodObjectProxy::FindExitsByWinding(const Vec3& p, Exit* exits) const {
  const SolidAnalysis& solids = *config_.solids;
  const std::uint32_t* of_vertex = solids.piece_of_vertex.data();
  const auto num_pieces = static_cast<std::uint32_t>(solids.piece_lo.size());
  // where a piece's crossings start: this far before its box, so a face in the box's
  // side is not missed at the sweep's very start
  const double margin = 1e3 * config_.surface_offset_m;
  int sweeps_left = kMaxWindingSweeps;
  int inside = 0;
  int outside = 0;
  int found = 0;
  for (int ray = 0; ray < kExitRays; ++ray) {
    const Vec3 u = ExitRay(ray);
    // the pieces whose boxes the ray meets, nearest first; beyond the first one left
    // out (`horizon`) the ray knows nothing
    struct Piece {
      std::uint32_t id;
      double enter;
      double leave;
    } pieces[kMaxRayPieces];
    int count = 0;
    double horizon = std::numeric_limits<double>::infinity();
    for (std::uint32_t c = 0; c < num_pieces; ++c) {
      if (solids.piece_winding[c] == 0) continue;  // open: bounds nothing
      double enter = 0.0;
      double leave = 0.0;
      if (!ClipRayToBox(p, u, solids.piece_lo[c], solids.piece_hi[c], &enter, &leave)) continue;
      int j = count < kMaxRayPieces ? count++ : kMaxRayPieces;
      if (j == kMaxRayPieces) {
        if (enter >= pieces[kMaxRayPieces - 1].enter) {
          horizon = std::min(horizon, enter);
          continue;
        }
        horizon = std::min(horizon, pieces[--j].enter);
      }
      for (; j > 0 && pieces[j - 1].enter > enter; --j) pieces[j] = pieces[j - 1];
      pieces[j] = {c, enter, leave};
    }
    if (horizon <= 0.0) continue;  // more pieces round p than the ray can hold
    // every crossing of each piece alone, in one list
    struct Crossing {
      double t;
      int slot;
      SweepHit hit;
    } crossings[kMaxRayPieces * kMaxCrossings];
    int num_crossings = 0;
    int winding = 0;  // of the pieces round p, by this ray
    int piece_inside[kMaxRayPieces];
    bool known = true;
    for (int k = 0; k < count && known; ++k) {
      SweepHit hits[kMaxCrossings];
      const double t0 = std::max(0.0, pieces[k].enter - margin);
      // a walk takes at most kMaxCrossings + 1 sweeps: start one only if they are left
      const int n = sweeps_left <= kMaxCrossings
                        ? -1
                        : WalkCrossings(p + t0 * u, p + (pieces[k].leave + margin) * u, u,
                                        of_vertex, pieces[k].id, hits);
      if (n < 0) {
        known = false;
        break;
      }
      sweeps_left -= n + 1;
      piece_inside[k] = n % 2;
      winding += piece_inside[k] * solids.piece_winding[pieces[k].id];
      for (int i = 0; i < n; ++i) {
        Crossing c{(hits[i].point - p).dot(u), k, hits[i]};
        int j = num_crossings++;
        for (; j > 0 && crossings[j - 1].t > c.t; --j) crossings[j] = crossings[j - 1];
        crossings[j] = c;
      }
    }
    if (!known) continue;
    if (winding <= 0) {
      ++outside;
      continue;
    }
    ++inside;
    // along the ray until the pieces wind round it no more; crossings within the
    // surface offset of each other (two parts touching face to face there) count as
    // one place
    const double step = config_.surface_offset_m;
    for (int i = 0; i < num_crossings && crossings[i].t < horizon; ++i) {
      const int k = crossings[i].slot;
      piece_inside[k] ^= 1;
      winding += (piece_inside[k] != 0 ? 1 : -1) * solids.piece_winding[pieces[k].id];
      const bool together = i + 1 < num_crossings && crossings[i + 1].t <= crossings[i].t + step;
      if (!together && winding <= 0) {
        exits[found++] = {(crossings[i].hit.point - p).norm(), crossings[i].hit};
        break;
      }
    }
  }
  return inside > outside ? found : 0;
}

int GodObjectProxy::WalkCrossings(const Vec3& a0, const Vec3& end, const Vec3& u,
                                  const std::uint32_t* piece_of_vertex, std::uint32_t piece,
                                  SweepHit* hits) const {
  // past each crossing by the surface offset, so the next sweep does not meet it (or
  // its neighbour across an edge it went through) again
  const double step = config_.surface_offset_m;
  Vec3 a = a0;
  for (int crossings = 0; crossings <= kMaxCrossings; ++crossings) {
    SweepHit hit;
    if (!PointHit(a, end, &hit, piece_of_vertex, piece)) return crossings;
    if (crossings == kMaxCrossings) break;
    hits[crossings] = hit;
    a = hit.point + step * u;
    if ((end - a).dot(u) <= 0.0) return crossings + 1;
  }
  return -1;
}

bool GodObjectProxy::Sweep(const Vec3& a, const Vec3& b, double radius, const SweepFloors* floors,
                           std::int64_t hint, SweepHit* hit, const std::uint32_t* piece_of_vertex,
                           std::uint32_t piece) const {
  SweepQuery query;
  query.piece_of_vertex = piece_of_vertex;
  query.piece = piece;
  query.radius = radius;
  query.bary_tol = config_.bary_tolerance;
  query.floors = floors;
  query.hint = hint;
  query.a = a;
  query.b = b;
  SweepSearch search(mesh_, query);
  ++sweeps_;
  if (config_.pieces != nullptr && config_.pieces->Settle(query, &search)) {
    ++settled_sweeps_;
  } else {
    if (grid_ != nullptr) {
      grid_->Search(&search);
    } else {
      tree_->Search(&search);
    }
  }
  if (!search.found()) return false;
  search.Report(hit);
  return true;
}

bool GodObjectProxy::PointHit(const Vec3& a, const Vec3& b, SweepHit* hit,
                              const std::uint32_t* piece_of_vertex, std::uint32_t piece) const {
  return Sweep(a, b, 0.0, nullptr, -1, hit, piece_of_vertex, piece);
}

bool GodObjectProxy::FirstHit(const Vec3& a, const Vec3& b, SweepHit* hit,
                              const SweepFloors* floors, std::int64_t hint) {
  return Sweep(a, b, config_.radius_m, floors, hint, hit);
}

void GodObjectProxy::Update(const Vec3& goal_l) {
  const double offset = config_.surface_offset_m;
  // feasibility slack: well below the offset, well above rounding at scene scale
  const double slack = 0.25 * offset;
  const Vec3 start = position_;
  constraints_.Clear();
  Vec3 target = goal_l;
  // the sweeps after the first stay on the constraint planes: whatever lies r and half
  // the offset below them cannot be touched
  SweepFloors floors;
  std::int64_t hint = last_triangle_;  // the last contact: the likeliest to be hit
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const Vec3 d = target - position_;
    if (d.squaredNorm() <= slack * slack) break;
    floors.count = constraints_.count();
    for (int i = 0; i < floors.count; ++i) {
      floors.normal[i] = constraints_.plane(i).normal;
      floors.offset[i] = constraints_.plane(i).offset - config_.radius_m - 0.5 * offset;
    }
    // The sweep looks one offset past the target. A target on a face's plane (a goal
    // there, from a CAD model's round coordinates) ends the sweep on the plane, where
    // rounding decides whether it touched: missed, the proxy would rest on the face with
    // no offset, and a sweep that starts exactly on a plane cannot tell which side it
    // comes from (a fuzzed run took one leaving the face for one entering it, and held
    // the proxy inside the part). Seen from here, the face is a contact like any other.
    const double reach = 1.0 + offset / std::sqrt(d.squaredNorm());
    SweepHit hit;
    if (!FirstHit(position_, position_ + reach * d, &hit, &floors, hint)) {
      position_ = target;
      break;
    }
    const double hit_s = reach * hit.s;  // along d
    // the plane through the centre at contact, facing where the proxy came from
    const Vec3& n = hit.normal;
    const double plane_offset = n.dot(hit.point) + offset;
    // stop where the sweep meets the offset plane, never beyond the contact itself nor
    // the target
    const double n_dot_d = n.dot(d);
    double s = n_dot_d < 0.0 ? (plane_offset - n.dot(position_)) / n_dot_d : 0.0;
    s = std::clamp(s, 0.0, std::min(hit_s, 1.0));
    position_ += s * d;
    if (constraints_.full()) break;
    hint = hit.triangle;
    constraints_.Add({n, plane_offset, hit.triangle}, slack);
    target = constraints_.Project(goal_l, position_, slack);
  }
  // kept through a lift-off: a sweep that stays above it is proven free (ConvexPieces)
  if (in_contact()) last_triangle_ = constraints_.plane(0).triangle;
  // Load what the next ticks will read: on a convex piece the triangles round the
  // contact (once per contact triangle, a step a tick over its first three ticks), else
  // the grid's cells the proxy is heading for.
  if (config_.pieces != nullptr && in_contact()) {
    const std::uint32_t t = constraints_.plane(0).triangle;
    if (t == warmed_triangle_) {
      if (warm_step_ < ConvexPieces::kWarmUpSteps) config_.pieces->WarmUp(t, warm_step_++);
      return;
    }
    if (config_.pieces->WarmUp(t, 0)) {
      warmed_triangle_ = t;
      warm_step_ = 1;
      return;
    }
  }
  // The cells ahead, while they are still a few ticks away (at 0.05-0.1 mm a tick on a
  // 1M-triangle model a new cell comes every 5 ticks or so): every cell on the next
  // 0.75 cell of its path.
  const Vec3 step = position_ - start;
  const double length = step.norm();
  if (grid_ != nullptr && length > 0.0) {
    grid_->WarmUp(position_, position_ + (0.75 * grid_->cell_size() / length) * step, &warm_up_);
  }
}

}  // namespace hapticad
