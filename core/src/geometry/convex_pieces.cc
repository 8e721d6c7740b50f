// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ConvexPieces::Settle runs on the servo thread every tick (Build does not).
#include "hapticad/core/geometry/convex_pieces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hapticad/core/geometry/connected_pieces.h"

namespace hapticad {

namespace {

// Which other pieces a piece's room is bounded against. With up to kAllPairs pieces,
// every other one. With more (all against all took 3.4 s for 20,000 pieces), only
// those that reach into a slab round the piece along the axis where the pieces spread
// most, the slab as wide again as the piece or twice the median piece on either side;
// the room is then cut to the slab wherever a piece lies beyond it, which keeps every
// piece outside the slab outside the room. The pieces are found by their start along
// the axis, in classes of length (each within a factor of two), so a scan starts at
// most two of its class's longest before the slab: a few long pieces among many short
// ones do not make every scan start far back.
class Slabs {
 public:
  static constexpr std::size_t kAllPairs = 1024;

  static Slabs Build(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi) {
    Slabs s;
    s.lo_ = &lo;
    s.hi_ = &hi;
    const std::size_t count = lo.size();
    if (count <= kAllPairs) return s;
    s.sliced_ = true;
    Vec3 c_lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 c_hi = -c_lo;
    for (std::size_t j = 0; j < count; ++j) {
      const Vec3 c = 0.5 * (lo[j] + hi[j]);
      c_lo = c_lo.cwiseMin(c);
      c_hi = c_hi.cwiseMax(c);
    }
    (c_hi - c_lo).maxCoeff(&s.axis_);
    std::vector<double> extents(count);
    for (std::size_t j = 0; j < count; ++j) extents[j] = hi[j][s.axis_] - lo[j][s.axis_];
    std::vector<double> sorted = extents;
    std::nth_element(sorted.begin(), sorted.begin() + count / 2, sorted.end());
    s.median_ = sorted[count / 2];
    s.lowest_hi_ = std::numeric_limits<double>::infinity();
    s.highest_lo_ = -s.lowest_hi_;
    std::vector<int> class_of_exponent;  // index into classes_ by frexp exponent + offset
    for (std::uint32_t j = 0; j < count; ++j) {
      s.lowest_hi_ = std::min(s.lowest_hi_, hi[j][s.axis_]);
      s.highest_lo_ = std::max(s.highest_lo_, lo[j][s.axis_]);
      int exponent = 0;
      std::frexp(extents[j], &exponent);                           // 0 for a zero extent
      const auto key = static_cast<std::size_t>(exponent + 1100);  // doubles: -1074..1024
      if (key >= class_of_exponent.size()) class_of_exponent.resize(key + 1, -1);
      if (class_of_exponent[key] < 0) {
        class_of_exponent[key] = static_cast<int>(s.classes_.size());
        s.classes_.emplace_back();
      }
      SizeClass& c = s.classes_[static_cast<std::size_t>(class_of_exponent[key])];
      c.order.push_back(j);
      c.longest = std::max(c.longest, extents[j]);
    }
    for (SizeClass& c : s.classes_) {
      std::sort(c.order.begin(), c.order.end(),
                [&](std::uint32_t x, std::uint32_t y) { return lo[x][s.axis_] < lo[y][s.axis_]; });
      c.order_lo.reserve(c.order.size());
      for (const std::uint32_t j : c.order) c.order_lo.push_back(lo[j][s.axis_]);
    }
    return s;
  }

  // Calls visit(j) for every other piece j that piece i's room must be bounded against,
  // and cuts the room (*room_lo, *room_hi) to the slab where pieces lie beyond it.
  template <class Visit>
  void ForEachNear(std::uint32_t i, Vec3* room_lo, Vec3* room_hi, Visit&& visit) const {
    const std::vector<Vec3>& lo = *lo_;
    const std::vector<Vec3>& hi = *hi_;
    if (!sliced_) {
      for (std::uint32_t j = 0; j < lo.size(); ++j) {
        if (j != i) visit(j);
      }
      return;
    }
    const int a = axis_;
    const double margin = std::max(2.0 * median_, hi[i][a] - lo[i][a]);
    const double slab_lo = lo[i][a] - margin;
    const double slab_hi = hi[i][a] + margin;
    for (const SizeClass& c : classes_) {
      // a piece that starts before slab_lo - its length ends before slab_lo (twice the
      // class's longest, so rounding cannot lose one that ends exactly there)
      const auto it =
          std::lower_bound(c.order_lo.begin(), c.order_lo.end(), slab_lo - 2.0 * c.longest);
      for (auto k = static_cast<std::size_t>(it - c.order_lo.begin());
           k < c.order.size() && c.order_lo[k] <= slab_hi; ++k) {
        const std::uint32_t j = c.order[k];
        if (j != i && hi[j][a] >= slab_lo) visit(j);
      }
    }
    if (lowest_hi_ < slab_lo) (*room_lo)[a] = std::max((*room_lo)[a], slab_lo);
    if (highest_lo_ > slab_hi) (*room_hi)[a] = std::min((*room_hi)[a], slab_hi);
  }

 private:
  struct SizeClass {
    double longest = 0.0;              // extent along the axis
    std::vector<std::uint32_t> order;  // by lo along the axis
    std::vector<double> order_lo;
  };
  const std::vector<Vec3>* lo_ = nullptr;
  const std::vector<Vec3>* hi_ = nullptr;
  bool sliced_ = false;
  int axis_ = 0;
  double median_ = 0.0;  // extent along the axis
  double lowest_hi_ = 0.0;
  double highest_lo_ = 0.0;
  std::vector<SizeClass> classes_;
};

}  // namespace

std::unique_ptr<ConvexPieces> ConvexPieces::Build(const TriangleMesh& mesh, double tolerance) {
  if (!(std::isfinite(tolerance) && tolerance >= 0.0)) {
    throw std::invalid_argument("ConvexPieces: the tolerance must be finite and >= 0");
  }
  std::unique_ptr<ConvexPieces> out(new ConvexPieces());
  out->mesh_ = &mesh;
  out->tolerance_ = tolerance;
  const auto n = static_cast<std::uint32_t>(mesh.num_triangles());
  const auto num_vertices = static_cast<std::uint32_t>(mesh.num_vertices());

  // every connected piece is convex until shown otherwise
  const ConnectedPieces pieces = FindConnectedPieces(mesh);
  const std::vector<std::uint32_t>& piece_of_vertex = pieces.of_vertex;
  std::vector<char> convex(pieces.lo.size(), 1);
  out->vertex_corner_.assign(num_vertices, kNone);
  for (std::uint32_t t = 0; t < n; ++t) {
    for (const std::uint32_t v : mesh.triangle(t)) out->vertex_corner_[v] = t;
  }

  // every edge shared by two triangles, and convex or flat from the winding's side; the
  // triangles across each edge (an open edge leaves the fans of its ends open: TurnsOnce
  // refuses them)
  for (std::uint32_t t = 0; t < n; ++t) {
    const auto& tri = mesh.triangle(t);
    const auto& across = mesh.across(t);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = across[k];
      if (u == TriangleMesh::kNone || u < t) continue;  // each shared edge once
      // edge k runs a -> b in t, so b -> a in u; w and w_u are the corners off the edge
      const std::uint32_t a = tri[k];
      const auto& tri_u = mesh.triangle(u);
      const int k_u = tri_u[0] == a ? 2 : (tri_u[1] == a ? 0 : 1);  // u's edge b -> a
      const Vec3& w = mesh.vertex(tri[(k + 2) % 3]);
      const Vec3& w_u = mesh.vertex(tri_u[(k_u + 2) % 3]);
      const Vec3& p = mesh.vertex(a);
      if (mesh.face_normal(t).dot(w_u - p) > tolerance ||
          mesh.face_normal(u).dot(w - p) > tolerance) {
        convex[piece_of_vertex[a]] = 0;
      }
    }
  }
  for (std::uint32_t v = 0; v < num_vertices; ++v) {
    if (piece_of_vertex[v] == kNone || !convex[piece_of_vertex[v]]) continue;
    if (!out->TurnsOnce(v)) convex[piece_of_vertex[v]] = 0;
  }

  // Number the convex pieces, and give each its room: the box that holds no other
  // piece's box, bounded on one side for each other piece (the side along which their
  // boxes lie furthest apart, or overlap least).
  const Slabs slabs = Slabs::Build(pieces.lo, pieces.hi);
  std::vector<std::uint32_t> convex_index(pieces.lo.size(), kNone);
  for (std::uint32_t i = 0; i < pieces.lo.size(); ++i) {
    if (!convex[i]) continue;
    convex_index[i] = static_cast<std::uint32_t>(out->clear_lo_.size());
    Vec3 lo = Vec3::Constant(-std::numeric_limits<double>::infinity());
    Vec3 hi = Vec3::Constant(std::numeric_limits<double>::infinity());
    slabs.ForEachNear(i, &lo, &hi, [&](std::uint32_t j) {
      int axis = 0;
      bool above = true;  // the other piece's box lies above this one's along the axis
      double apart = -std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        for (const bool up : {true, false}) {
          const double gap =
              up ? pieces.lo[j][k] - pieces.hi[i][k] : pieces.lo[i][k] - pieces.hi[j][k];
          if (gap > apart) {
            apart = gap;
            axis = k;
            above = up;
          }
        }
      }
      if (above) {
        hi[axis] = std::min(hi[axis], pieces.lo[j][axis]);
      } else {
        lo[axis] = std::max(lo[axis], pieces.hi[j][axis]);
      }
    });
    out->clear_lo_.push_back(lo);
    out->clear_hi_.push_back(hi);
  }
  out->piece_.resize(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    out->piece_[t] = convex_index[piece_of_vertex[mesh.triangle(t)[0]]];
  }
  for (std::uint32_t v = 0; v < num_vertices; ++v) {
    const std::uint32_t t = out->vertex_corner_[v];
    if (t != kNone && out->piece_[t] == kNone) out->vertex_corner_[v] = kNone;
  }
  if (out->clear_lo_.empty()) {
    HugePageVector<std::uint32_t>().swap(out->piece_);
    HugePageVector<std::uint32_t>().swap(out->vertex_corner_);
  }
  return out;
}

bool ConvexPieces::TurnsOnce(std::uint32_t v) const {
  const std::uint32_t first = vertex_corner_[v];
  // a direction inside the vertex's cone of normals: their sum, each plane once (the
  // triangles of one flat face round a vertex come one after another)
  const auto same = [](const Vec3& a, const Vec3& b) { return a.dot(b) > 1.0 - 1e-12; };
  Vec3 m = Vec3::Zero();
  Vec3 last = Vec3::Zero();
  int planes = 0;
  if (!ForEachAround(v, first, [&](std::uint32_t t) {
        const Vec3& n = mesh_->face_normal(t);
        if (!same(n, last)) {
          m += n;
          ++planes;
        }
        last = n;
      })) {
    return false;
  }
  if (planes > 1 && same(mesh_->face_normal(first), last)) m -= last;  // the first plane, twice
  const Vec3& p = mesh_->vertex(v);
  const auto sides = [&](std::uint32_t t, Vec3* e1, Vec3* e2) {
    const auto& tri = mesh_->triangle(t);
    const int k = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    *e1 = mesh_->vertex(tri[(k + 1) % 3]) - p;
    *e2 = mesh_->vertex(tri[(k + 2) % 3]) - p;
  };
  // Projected across the sum, or if not every normal leans toward that, across the
  // direction away from the neighbours' mean: a sharp vertex's planes may not all lean
  // toward their sum (a corner cut off a cube), but at any convex vertex they all lean
  // away from the mean, since each neighbour lies on or under every plane through it,
  // and some under each unless all are flat. Signs of triple products with the
  // direction are those of the sides projected across it.
  Vec3 e1, e2;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt == 1) {
      m = Vec3::Zero();  // each neighbour once: the corner after v in each triangle
      ForEachAround(v, first, [&](std::uint32_t t) {
        sides(t, &e1, &e2);
        m -= e1;
      });
    }
    const double length = m.norm();
    if (!(length > 0.0)) continue;
    const Vec3 across = m / length;
    sides(first, &e1, &e2);
    // inside the first corner (narrower than a half turn), projected across it
    const Vec3 inside = e1 + e2 - (e1 + e2).dot(across) * across;
    bool leaning = true;
    bool ok = true;
    int turns = 0;
    ForEachAround(v, first, [&](std::uint32_t t) {
      sides(t, &e1, &e2);
      // every corner counter-clockwise, so narrower than a half turn: two signs decide
      const double turn = e1.cross(e2).dot(across);
      const double after_first = e1.cross(inside).dot(across);
      const double before_second = inside.cross(e2).dot(across);
      const double scale = 1e-12 * (e1.squaredNorm() + e2.squaredNorm() + inside.squaredNorm());
      leaning = leaning && mesh_->face_normal(t).dot(across) > 1e-6;
      ok = ok && turn > scale &&
           // along a side of a corner (not opposite it; inside is across): ambiguous
           !(std::abs(after_first) <= scale && e1.dot(inside) > 0.0) &&
           !(std::abs(before_second) <= scale && e2.dot(inside) > 0.0);
      turns += after_first > 0.0 && before_second > 0.0;
    });
    if (leaning) return ok && turns == 1;
  }
  return false;
}

bool ConvexPieces::Settle(const SweepQuery& query, SweepSearch* search) const {
  if (query.hint < 0 || static_cast<std::size_t>(query.hint) >= piece_.size()) return false;
  const auto hint = static_cast<std::uint32_t>(query.hint);
  const std::uint32_t piece = piece_[hint];
  if (piece == kNone) return false;
  // nothing but the piece within the sweep's reach (false for a non-finite query too)
  const Vec3 r = Vec3::Constant(query.radius);
  const Vec3 lo = query.a.cwiseMin(query.b) - r;
  const Vec3 hi = query.a.cwiseMax(query.b) + r;
  if (!((lo.array() > clear_lo_[piece].array()).all() &&
        (hi.array() < clear_hi_[piece].array()).all())) {
    return false;
  }
  if (search->found()) {
    if (IsFirstContact(query, *search, piece, false)) return true;  // on the hint's face
  } else if (IsClear(query, hint)) {
    return true;
  }
  // The contact moved on, or lies on an edge or at a vertex: walk toward it, then prove
  // it; failing that, test every triangle round it.
  if (Walk(search->found() ? search->best_triangle() : hint, query, piece, search)) return true;
  if (search->found() && IsFirstContact(query, *search, piece, true)) return true;
  if (SearchAround(search->found() ? search->best_triangle() : hint, query, piece, search)) {
    return true;
  }
  return search->found() && IsFirstContact(query, *search, piece, true);
}

bool ConvexPieces::IsClear(const SweepQuery& query, std::uint32_t hint) const {
  const Vec3& n = mesh_->face_normal(hint);
  const std::uint32_t corner = mesh_->triangle(hint)[0];
  const Vec3& v0 = mesh_->vertex(corner);
  if (n.dot(query.a - v0) > query.radius && n.dot(query.b - v0) > query.radius) return true;
  if (query.floors != nullptr) {
    for (int i = 0; i < query.floors->count; ++i) {
      if (BoundsPiece(query.floors->normal[i], query.floors->offset[i], corner)) return true;
    }
  }
  return false;
}

bool ConvexPieces::IsFirstContact(const SweepQuery& query, const SweepSearch& search,
                                  std::uint32_t piece, bool climb) const {
  const std::uint32_t t = search.best_triangle();
  if (piece_[t] != piece) return false;
  const Vec3& n = search.best_normal();
  const Vec3 d = query.b - query.a;
  if (!(n.dot(d) < 0.0)) return false;  // moving into the solid there
  // Before the contact the centre was more than its radius above the plane through the
  // contact point across n: if no vertex is above that plane, it touched nothing.
  // A face's own plane is such a plane (from outside: the winding's side).
  const Vec3& face = mesh_->face_normal(t);
  if (n == face) return true;
  if (!climb || !(n.dot(face) > 0.0)) return false;  // not asked, or from inside the solid
  const Vec3 contact = query.a + search.best_s() * d - query.radius * n;
  return BoundsPiece(n, n.dot(contact), mesh_->triangle(t)[0]);
}

template <class Visit>
bool ConvexPieces::ForEachAround(std::uint32_t v, std::uint32_t t, Visit&& visit) const {
  std::uint32_t u = t;
  for (int i = 0; i < kMaxFan; ++i) {
    visit(u);
    // across the edge from v to the next corner: the next triangle round v
    const auto& tri = mesh_->triangle(u);
    u = mesh_->across(u)[tri[0] == v ? 0 : (tri[1] == v ? 1 : 2)];
    if (u == t) return true;
    if (u == kNone) return false;
  }
  return false;
}

bool ConvexPieces::BoundsPiece(const Vec3& normal, double offset, std::uint32_t start) const {
  // On a convex polytope a vertex that no neighbour rises above is the highest of all,
  // if the direction points out of the solid there (at a vertex inside a flat face every
  // neighbour ties with it, for the face's normal and for its opposite alike).
  const double top = offset + tolerance_;
  std::uint32_t v = start;
  double height = normal.dot(mesh_->vertex(v));
  if (height > top) return false;
  for (int step = 0; step < kMaxClimb; ++step) {
    std::uint32_t next = v;
    bool above = false;  // one vertex above the plane is enough
    bool outward = false;
    const bool whole = ForEachAround(v, vertex_corner_[v], [&](std::uint32_t u) {
      outward = outward || normal.dot(mesh_->face_normal(u)) > 0.0;
      for (const std::uint32_t w : mesh_->triangle(u)) {
        const double h = normal.dot(mesh_->vertex(w));
        above = above || h > top;
        if (h > height) {
          height = h;
          next = w;
        }
      }
    });
    if (above || !whole) return false;
    if (next == v) return outward;
    v = next;
  }
  return false;
}

int ConvexPieces::ExitEdge(std::uint32_t t, const SweepQuery& query) const {
  // where the sweep reaches its radius above t's plane (or ends), in t's barycentrics
  const auto& tri = mesh_->triangle(t);
  const Vec3& n = mesh_->face_normal(t);
  const Vec3& v0 = mesh_->vertex(tri[0]);
  const Vec3 d = query.b - query.a;
  const double h0 = n.dot(query.a - v0);
  const double dh = n.dot(d);
  const double s = dh < 0.0 ? std::clamp((h0 - query.radius) / -dh, 0.0, 1.0) : 0.0;
  const Vec3 w = query.a + s * d - v0;
  const Vec3 e1 = mesh_->vertex(tri[1]) - v0;
  const Vec3 e2 = mesh_->vertex(tri[2]) - v0;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return -1;
  const double b1 = (d22 * w.dot(e1) - d12 * w.dot(e2)) / det;
  const double b2 = (d11 * w.dot(e2) - d12 * w.dot(e1)) / det;
  const double b0 = 1.0 - b1 - b2;
  // edge k lies opposite corner k + 2
  if (b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0) return -1;
  return b2 <= b0 ? (b2 <= b1 ? 0 : 2) : (b0 <= b1 ? 1 : 2);
}

bool ConvexPieces::IsProvenOnFace(std::uint32_t u, const SweepQuery& query, std::uint32_t piece,
                                  SweepSearch* search) const {
  search->Test(u);
  return search->found() && search->best_triangle() == u &&
         IsFirstContact(query, *search, piece, false);
}

bool ConvexPieces::Walk(std::uint32_t t, const SweepQuery& query, std::uint32_t piece,
                        SweepSearch* search) const {
  // Only the triangle the sweep lands over is tested: the proof needs no other (its
  // plane bounds the piece), and the full test of a triangle passed over is the dearest
  // part of a tick that crosses two.
  std::uint32_t from = kNone;
  for (int step = 0; step < kMaxWalk; ++step) {
    const int k = ExitEdge(t, query);
    if (k < 0) return step > 0 && IsProvenOnFace(t, query, piece, search);
    const std::uint32_t next = mesh_->across(t)[k];
    if (next == from) {
      // back again: the contact is over the edge between the two; test both (the
      // first was tested before the walk), so the caller can prove it with a climb
      search->Test(t);
      if (step > 1) search->Test(from);
      return false;
    }
    from = t;
    t = next;
  }
  search->Test(t);  // where the walk stopped: a start for the caller's search round it
  return false;
}

bool ConvexPieces::SearchAround(std::uint32_t t, const SweepQuery& query, std::uint32_t piece,
                                SweepSearch* search) const {
  for (const std::uint32_t v : mesh_->triangle(t)) {
    bool done = false;
    ForEachAround(v, t, [&](std::uint32_t u) {
      if (!done && u != t) done = IsProvenOnFace(u, query, piece, search);
    });
    if (done) return true;
  }
  return false;
}

bool ConvexPieces::WarmUp(std::uint32_t t, int step) const {
  if (t >= piece_.size() || piece_[t] == kNone) return false;
  std::uint32_t word = 0;
  for (const std::uint32_t u : mesh_->across(t)) {
    if (step == 0) {
      word ^= mesh_->LoadTriangle(u, true);
      continue;
    }
    for (const std::uint32_t w : mesh_->across(u)) {
      word ^= step == 1 ? piece_[w] ^ mesh_->LoadTriangle(w, false) : mesh_->LoadVertices(w);
    }
  }
  TriangleMesh::KeepLoads(word);
  return true;
}

std::size_t ConvexPieces::CalcMemoryBytes() const {
  return piece_.capacity() * sizeof(std::uint32_t) +
         vertex_corner_.capacity() * sizeof(std::uint32_t) +
         2 * clear_lo_.capacity() * sizeof(Vec3);
}

}  // namespace hapticad
