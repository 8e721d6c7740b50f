// SPDX-License-Identifier: GPL-3.0-or-later
// The only translation unit of the core that includes CGAL's AABB tree.
#include "hapticad/core/geometry/triangle_tree.h"

#include <limits>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include <boost/property_map/property_map.hpp>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <boost/iterator/counting_iterator.hpp>

#include "hapticad/core/geometry/segment_triangle.h"

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
using Node =
    std::remove_cv_t<std::remove_pointer_t<decltype(std::declval<const Tree&>().root_node())>>;

// Traversal that keeps the nearest hit so far and prunes every box entered beyond it.
// Children are visited nearest entry first (CGAL's traversal_with_priority).
class FirstHitTraversal {
 public:
  using Priority = double;

  FirstHitTraversal(const TriangleMesh& mesh, const Vec3& a, const Vec3& d, double pad,
                    double bary_tol)
      : mesh_(mesh), a_(a), d_(d), pad_(pad), bary_tol_(bary_tol) {}

  bool go_further() const { return true; }

  void intersection(const Vec3&, const TrianglePrimitive& primitive) {
    const auto& t = mesh_.triangle(primitive.id());
    SegmentTriangleHit hit;
    if (IntersectSegmentTriangle(a_, d_, best_s_, mesh_.vertex(t[0]), mesh_.vertex(t[1]),
                                 mesh_.vertex(t[2]), bary_tol_, &hit)) {
      // equal s on a shared edge: keep the first found, so the result is deterministic
      if (!found_ || hit.s < best_s_) {
        best_s_ = hit.s;
        best_triangle_ = primitive.id();
        found_ = true;
      }
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
  double best_s() const { return best_s_; }
  std::uint32_t best_triangle() const { return best_triangle_; }

 private:
  bool Enter(const CGAL::Bbox_3& box, double* entry) const {
    const double lo[3] = {box.xmin(), box.ymin(), box.zmin()};
    const double hi[3] = {box.xmax(), box.ymax(), box.zmax()};
    return IntersectSegmentBox(a_, d_, best_s_, lo, hi, pad_, entry);
  }

  const TriangleMesh& mesh_;
  const Vec3 a_;
  const Vec3 d_;
  const double pad_;
  const double bary_tol_;
  double best_s_ = 1.0;
  std::uint32_t best_triangle_ = 0;
  bool found_ = false;
};

bool BoxesMeet(const CGAL::Bbox_3& box, const Vec3& lo, const Vec3& hi) {
  return box.xmin() <= hi.x() && box.xmax() >= lo.x() && box.ymin() <= hi.y() &&
         box.ymax() >= lo.y() && box.zmin() <= hi.z() && box.zmax() >= lo.z();
}

// The children of a node of `n` primitives, as CGAL lays them out (AABB_node.h):
// n = 2: two primitives; n = 3: a primitive and a node of 2; else nodes of n/2, n - n/2.
void Gather(const Node& node, std::uint32_t n, const TriangleBboxMap& boxes, const Vec3& lo,
            const Vec3& hi, TriangleTree::Neighbourhood* out, bool* overflow) {
  auto push = [&](const void* subtree, std::uint32_t size) {
    if (out->count == TriangleTree::Neighbourhood::kCapacity) {
      *overflow = true;
      return;
    }
    out->subtree[out->count] = subtree;
    out->size[out->count] = size;
    ++out->count;
  };
  if (*overflow) return;
  if (n <= TriangleTree::Neighbourhood::kSubtreeSize) {
    push(&node, n);
    return;
  }
  // n > kSubtreeSize >= 4: both children are nodes
  const std::uint32_t left = n / 2;
  if (BoxesMeet(node.left_child().bbox(), lo, hi))
    Gather(node.left_child(), left, boxes, lo, hi, out, overflow);
  if (BoxesMeet(node.right_child().bbox(), lo, hi)) {
    Gather(node.right_child(), n - left, boxes, lo, hi, out, overflow);
  }
}

// CGAL's traversal_with_priority, over a subtree of n primitives.
void Traverse(const Node& node, std::uint32_t n, FirstHitTraversal& t) {
  const Vec3 unused;
  switch (n) {
    case 2:
      t.intersection(unused, node.left_data());
      t.intersection(unused, node.right_data());
      return;
    case 3:
      t.intersection(unused, node.left_data());
      if (t.do_intersect(unused, node.right_child())) Traverse(node.right_child(), 2, t);
      return;
    default: {
      const auto [hit_left, p_left] = t.do_intersect_with_priority(unused, node.left_child());
      const auto [hit_right, p_right] = t.do_intersect_with_priority(unused, node.right_child());
      const std::uint32_t left = n / 2;
      if (hit_left && hit_right) {
        if (p_left >= p_right) {
          Traverse(node.left_child(), left, t);
          if (t.do_intersect(unused, node.right_child())) Traverse(node.right_child(), n - left, t);
        } else {
          Traverse(node.right_child(), n - left, t);
          if (t.do_intersect(unused, node.left_child())) Traverse(node.left_child(), left, t);
        }
      } else if (hit_left) {
        Traverse(node.left_child(), left, t);
      } else if (hit_right) {
        Traverse(node.right_child(), n - left, t);
      }
    }
  }
}

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

bool TriangleTree::FirstHit(const Vec3& a, const Vec3& b, double bary_tol, SegmentHit* hit) const {
  const Vec3 d = b - a;
  FirstHitTraversal traversal(*impl_->mesh, a, d, impl_->pad, bary_tol);
  impl_->tree.traversal_with_priority(a, traversal);
  if (!traversal.found()) return false;
  hit->triangle = traversal.best_triangle();
  hit->s = traversal.best_s();
  hit->point = a + hit->s * d;
  return true;
}

bool TriangleTree::GatherNeighbourhood(const Vec3& lo, const Vec3& hi, Neighbourhood* out) const {
  out->lo = lo;
  out->hi = hi;
  out->count = 0;
  out->valid = false;
  const auto n = static_cast<std::uint32_t>(impl_->tree.size());
  if (n < 2) return false;  // a one-triangle scene: the plain query is as cheap
  bool overflow = false;
  if (BoxesMeet(impl_->tree.bbox(), lo, hi)) {
    Gather(*impl_->tree.root_node(), n, impl_->boxes, lo, hi, out, &overflow);
  }
  out->valid = !overflow;
  return out->valid;
}

bool TriangleTree::FirstHitIn(const Neighbourhood& nb, const Vec3& a, const Vec3& b,
                              double bary_tol, SegmentHit* hit) const {
  const Vec3 d = b - a;
  FirstHitTraversal traversal(*impl_->mesh, a, d, impl_->pad, bary_tol);
  const Vec3 unused;
  for (int i = 0; i < nb.count; ++i) {
    const Node& node = *static_cast<const Node*>(nb.subtree[i]);
    if (traversal.do_intersect(unused, node)) Traverse(node, nb.size[i], traversal);
  }
  if (!traversal.found()) return false;
  hit->triangle = traversal.best_triangle();
  hit->s = traversal.best_s();
  hit->point = a + hit->s * d;
  return true;
}

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
