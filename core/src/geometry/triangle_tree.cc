// SPDX-License-Identifier: GPL-3.0-or-later
// The only translation unit of the core that includes CGAL's AABB tree.
#include "hapticad/core/geometry/triangle_tree.h"

#include <limits>
#include <new>
#include <utility>
#include <vector>

#include <boost/property_map/property_map.hpp>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <boost/iterator/counting_iterator.hpp>

#include "hapticad/core/geometry/segment_triangle.h"
#include "hapticad/core/geometry/sphere_triangle.h"

namespace hapticad {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;

// A primitive is a triangle index (4 bytes); the geometry is read from the mesh, which
// the tree holds once as shared data instead of a Triangle_3 copy per primitive.
class TrianglePrimitive {
 public:
  using Id = std::uint32_t;
  using Point = Kernel::Point_3;
  using Datum = Kernel::Triangle_3;
  using Shared_data = const TriangleMesh*;

  TrianglePrimitive() = default;
  template <class Iterator>
  TrianglePrimitive(Iterator it, Shared_data) : id_(*it) {}

  static Shared_data construct_shared_data(Shared_data mesh) { return mesh; }

  Id id() const { return id_; }
  Datum datum(Shared_data mesh) const {
    const auto& t = mesh->triangle(id_);
    return Datum(ToPoint(mesh->vertex(t[0])), ToPoint(mesh->vertex(t[1])),
                 ToPoint(mesh->vertex(t[2])));
  }
  Point reference_point(Shared_data mesh) const {
    return ToPoint(mesh->vertex(mesh->triangle(id_)[0]));
  }

 private:
  static Point ToPoint(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }
  Id id_ = 0;
};

// Bounding boxes straight from the vertex array: CGAL's default builds a Triangle_3
// for every box it computes, and it computes one per primitive per tree level.
struct TriangleBboxMap {
  using key_type = std::uint32_t;
  using value_type = CGAL::Bbox_3;
  using reference = CGAL::Bbox_3;
  using category = boost::readable_property_map_tag;
  const TriangleMesh* mesh = nullptr;

  friend CGAL::Bbox_3 get(const TriangleBboxMap& map, std::uint32_t id) {
    const auto& t = map.mesh->triangle(id);
    const Vec3& a = map.mesh->vertex(t[0]);
    const Vec3& b = map.mesh->vertex(t[1]);
    const Vec3& c = map.mesh->vertex(t[2]);
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c);
    const Vec3 hi = a.cwiseMax(b).cwiseMax(c);
    return CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
  }
};

using Traits = CGAL::AABB_traits<Kernel, TrianglePrimitive, TriangleBboxMap>;
using Tree = CGAL::AABB_tree<Traits>;

// Traversal that keeps the nearest contact so far and prunes every box entered beyond
// it. Children are visited nearest entry first (CGAL's traversal_with_priority). A
// sphere query grows every box by its radius: the swept sphere meets a box only if its
// centre's segment meets the box grown by r. Triangles inside a floor are skipped; so
// are those behind the best contact so far: until it, the query stays at least r in
// front of the plane through the contact point across the contact normal. (Testing the
// boxes against the floors too was measured slower: it costs every box, and the boxes
// it would prune are mostly pruned by the segment already.)
class FirstHitTraversal {
 public:
  using Priority = double;

  FirstHitTraversal(const TriangleMesh& mesh, const SweepQuery& q, double pad)
      : mesh_(mesh),
        a_(q.a),
        d_(q.b - q.a),
        ray_(q.a, q.b - q.a),
        radius_(q.radius),
        pad_(pad + q.radius),
        bary_tol_(q.bary_tol) {
    if (q.floors != nullptr) {
      for (int i = 0; i < q.floors->count; ++i) AddFloor(q.floors->normal[i], q.floors->offset[i]);
    }
    given_floors_ = floor_count_;
    if (q.hint >= 0 && static_cast<std::size_t>(q.hint) < mesh.num_triangles()) {
      Test(static_cast<std::uint32_t>(q.hint));
    }
  }

  bool go_further() const { return true; }

  void intersection(const Vec3&, const TrianglePrimitive& primitive) { Test(primitive.id()); }

  void Test(std::uint32_t id) {
    const auto& t = mesh_.triangle(id);
    const Vec3& v0 = mesh_.vertex(t[0]);
    const Vec3& v1 = mesh_.vertex(t[1]);
    const Vec3& v2 = mesh_.vertex(t[2]);
    for (int i = 0; i < floor_count_; ++i) {
      const Vec3& f = floor_normal_[i];
      if (f.dot(v0) <= floor_offset_[i] && f.dot(v1) <= floor_offset_[i] &&
          f.dot(v2) <= floor_offset_[i]) {
        return;
      }
    }
    const Vec3& n = mesh_.face_normal(id);
    if (radius_ > 0.0) {
      SphereTriangleHit hit;
      if (SweepSphereTriangle(a_, d_, best_s_, radius_, v0, v1, v2, n, bary_tol_, &hit)) {
        Keep(id, hit.s, hit.normal);
      }
      return;
    }
    SegmentTriangleHit hit;
    if (IntersectSegmentTriangle(a_, d_, best_s_, v0, v1, v2, bary_tol_, &hit)) {
      // a point meets the side it comes from
      Keep(id, hit.s, n.dot(d_) > 0.0 ? Vec3(-n) : n);
    }
  }

  template <class Node>
  bool do_intersect(const Vec3&, const Node& node) const {
    double entry;
    return Enter(node.bbox(), &entry);
  }

  template <class Node>
  std::pair<bool, Priority> do_intersect_with_priority(const Vec3&, const Node& node) const {
    double entry = 0.0;
    const bool hit = Enter(node.bbox(), &entry);
    return {hit, -entry};
  }

  bool found() const { return found_; }
  void Report(SweepHit* hit) const {
    hit->triangle = best_triangle_;
    hit->s = best_s_;
    hit->point = a_ + best_s_ * d_;
    hit->normal = best_normal_;
  }

 private:
  void Keep(std::uint32_t id, double s, const Vec3& normal) {
    // equal s on a shared edge: keep the first found, so the result is deterministic
    if (!found_ || s < best_s_) {
      best_s_ = s;
      best_triangle_ = id;
      best_normal_ = normal;
      found_ = true;
      // the plane through the contact point, across the contact normal: before s the
      // query is at least r in front of it
      const Vec3 contact = a_ + s * d_ - radius_ * normal;
      floor_count_ = given_floors_;  // the new contact's plane replaces the last one's
      AddFloor(normal, normal.dot(contact));
    }
  }

  void AddFloor(const Vec3& normal, double offset) {
    if (floor_count_ == kMaxFloors) return;
    floor_normal_[floor_count_] = normal;
    floor_offset_[floor_count_] = offset;
    ++floor_count_;
  }

  bool Enter(const CGAL::Bbox_3& box, double* entry) const {
    const double lo[3] = {box.xmin(), box.ymin(), box.zmin()};
    const double hi[3] = {box.xmax(), box.ymax(), box.zmax()};
    return IntersectSegmentBox(ray_, best_s_, lo, hi, pad_, entry);
  }

  static constexpr int kMaxFloors = SweepFloors::kMax + 1;

  const TriangleMesh& mesh_;
  const Vec3 a_;
  const Vec3 d_;
  const SegmentRay ray_;
  const double radius_;
  const double pad_;
  const double bary_tol_;
  double best_s_ = 1.0;
  std::uint32_t best_triangle_ = 0;
  Vec3 best_normal_ = Vec3::Zero();
  bool found_ = false;
  Vec3 floor_normal_[kMaxFloors];
  double floor_offset_[kMaxFloors];
  int floor_count_ = 0;
  int given_floors_ = 0;
};

}  // namespace

struct TriangleTree::Impl {
  const TriangleMesh* mesh = nullptr;
  double pad = 0.0;
  TriangleBboxMap boxes;
  Tree tree;
};

TriangleTree::TriangleTree(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TriangleTree::~TriangleTree() = default;

std::unique_ptr<TriangleTree> TriangleTree::Build(const TriangleMesh& mesh, double pad) {
  auto impl = std::make_unique<Impl>();
  impl->mesh = &mesh;
  impl->pad = pad;
  impl->boxes.mesh = &mesh;
  impl->tree.~Tree();
  new (&impl->tree) Tree(Traits(impl->boxes));
  const auto n = static_cast<std::uint32_t>(mesh.num_triangles());
  impl->tree.insert(boost::counting_iterator<std::uint32_t>(0),
                    boost::counting_iterator<std::uint32_t>(n), &mesh);
  // CGAL defers both to the first query: do them now, off the servo thread
  impl->tree.build();
  // The kd-tree only supplies starting hints for closest-point searches (never on the
  // servo tick): one vertex in 8 is plenty and builds 8 times faster.
  std::vector<Kernel::Point_3> hints;
  hints.reserve(mesh.num_vertices() / 8 + 1);
  for (std::size_t v = 0; v < mesh.num_vertices(); v += 8) {
    const Vec3& p = mesh.vertex(static_cast<std::uint32_t>(v));
    hints.emplace_back(p.x(), p.y(), p.z());
  }
  impl->tree.accelerate_distance_queries(hints.begin(), hints.end());
  return std::unique_ptr<TriangleTree>(new TriangleTree(std::move(impl)));
}

bool TriangleTree::FirstHit(const SweepQuery& query, SweepHit* hit) const {
  FirstHitTraversal traversal(*impl_->mesh, query, impl_->pad);
  impl_->tree.traversal_with_priority(query.a, traversal);
  if (!traversal.found()) return false;
  traversal.Report(hit);
  return true;
}

double TriangleTree::pad() const { return impl_->pad; }

SurfacePoint TriangleTree::CalcClosestPoint(const Vec3& p) const {
  const auto result = impl_->tree.closest_point_and_primitive(Kernel::Point_3(p.x(), p.y(), p.z()));
  SurfacePoint out;
  out.triangle = result.second;
  out.point = Vec3(result.first.x(), result.first.y(), result.first.z());
  out.distance = (out.point - p).norm();
  return out;
}

std::size_t TriangleTree::num_triangles() const { return impl_->tree.size(); }

std::size_t TriangleTree::CalcMemoryBytes() const {
  const std::size_t n = impl_->tree.size();
  // CGAL keeps n - 1 nodes (a Bbox_3 and two child pointers each) and n primitives
  return (n > 0 ? n - 1 : 0) * (sizeof(CGAL::Bbox_3) + 2 * sizeof(void*)) +
         n * sizeof(TrianglePrimitive);
}

}  // namespace hapticad
