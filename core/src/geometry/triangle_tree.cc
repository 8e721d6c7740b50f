// SPDX-License-Identifier: GPL-3.0-or-later
// The only translation unit of the core that includes CGAL's AABB tree.
#include "hapticad/core/geometry/triangle_tree.h"

#include <limits>
#include <utility>

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

using Traits = CGAL::AABB_traits<Kernel, TrianglePrimitive>;
using Tree = CGAL::AABB_tree<Traits>;

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

}  // namespace

struct TriangleTree::Impl {
  const TriangleMesh* mesh = nullptr;
  double pad = 0.0;
  Tree tree;
};

TriangleTree::TriangleTree(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TriangleTree::~TriangleTree() = default;

std::unique_ptr<TriangleTree> TriangleTree::Build(const TriangleMesh& mesh, double pad) {
  auto impl = std::make_unique<Impl>();
  impl->mesh = &mesh;
  impl->pad = pad;
  const auto n = static_cast<std::uint32_t>(mesh.num_triangles());
  impl->tree.insert(boost::counting_iterator<std::uint32_t>(0),
                    boost::counting_iterator<std::uint32_t>(n), &mesh);
  // CGAL defers both to the first query: do them now, off the servo thread
  impl->tree.build();
  impl->tree.accelerate_distance_queries();
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
