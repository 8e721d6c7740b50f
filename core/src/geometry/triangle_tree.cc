// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: TriangleTree::FirstHit and Search run on the servo thread every tick (a sphere
// proxy's sweeps); FindClosestPointWithin on a restart tick. Build does not.
// The only translation unit of the core that includes CGAL's AABB tree.
#include "hapticad/core/geometry/triangle_tree.h"

#include <cmath>
#include <limits>
#include <new>
#include <utility>
#include <vector>

#include <boost/property_map/property_map.hpp>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <boost/iterator/counting_iterator.hpp>

#include "hapticad/core/geometry/median_select.h"
#include "hapticad/core/geometry/segment_triangle.h"
#include "hapticad/core/geometry/sweep_search.h"
#include "hapticad/core/huge_page_allocator.h"

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
  // The reference point (the first vertex, in floats: it only chooses the splits) is
  // kept here: the build compares it n log n times, and reading it through the mesh
  // costs two cache misses each time.
  template <class Iterator>
  TrianglePrimitive(Iterator it, Shared_data mesh) : id_(*it) {
    const Vec3& p = mesh->vertex(mesh->triangle(id_)[0]);
    for (int k = 0; k < 3; ++k) reference_[k] = static_cast<float>(p[k]);
  }

  static Shared_data construct_shared_data(Shared_data mesh) { return mesh; }

  Id id() const { return id_; }
  Datum datum(Shared_data mesh) const {
    const auto& t = mesh->triangle(id_);
    return Datum(ToPoint(mesh->vertex(t[0])), ToPoint(mesh->vertex(t[1])),
                 ToPoint(mesh->vertex(t[2])));
  }
  Point reference_point(Shared_data) const {
    return Point(reference_[0], reference_[1], reference_[2]);
  }
  float reference(int axis) const { return reference_[axis]; }

 private:
  static Point ToPoint(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }
  Id id_ = 0;
  float reference_[3] = {0.0f, 0.0f, 0.0f};
};

// Bounding boxes straight from the vertex array: CGAL's default builds a Triangle_3
// for every box it computes. The build computes one per triangle per tree level, so
// while it runs they are read from `cached`, computed once per triangle, in floats
// rounded outward (a box a rounding step larger culls no less truly) on huge pages:
// half the memory of doubles, and on a VM where the first touch of a page is dear,
// under half the time (48 MB of double boxes on 4 KiB pages took 130 ms of a 1M-triangle
// build).
struct FloatBox {
  float lo[3];
  float hi[3];
};

FloatBox ToFloatBox(const Vec3& lo, const Vec3& hi) {
  FloatBox box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = static_cast<float>(lo[k]);
    if (box.lo[k] > lo[k]) box.lo[k] = std::nextafter(box.lo[k], -INFINITY);
    box.hi[k] = static_cast<float>(hi[k]);
    if (box.hi[k] < hi[k]) box.hi[k] = std::nextafter(box.hi[k], INFINITY);
  }
  return box;
}

CGAL::Bbox_3 CalcTriangleBox(const TriangleMesh& mesh, std::uint32_t id) {
  const auto& t = mesh.triangle(id);
  const Vec3& a = mesh.vertex(t[0]);
  const Vec3& b = mesh.vertex(t[1]);
  const Vec3& c = mesh.vertex(t[2]);
  const Vec3 lo = a.cwiseMin(b).cwiseMin(c);
  const Vec3 hi = a.cwiseMax(b).cwiseMax(c);
  return CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
}

struct TriangleBboxMap {
  using key_type = std::uint32_t;
  using value_type = CGAL::Bbox_3;
  using reference = CGAL::Bbox_3;
  using category = boost::readable_property_map_tag;
  const TriangleMesh* mesh = nullptr;
  const HugePageVector<FloatBox>* cached = nullptr;  // empty but during the build

  friend CGAL::Bbox_3 get(const TriangleBboxMap& map, std::uint32_t id) {
    if (!map.cached->empty()) {
      const FloatBox& b = (*map.cached)[id];
      return CGAL::Bbox_3(b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]);
    }
    return CalcTriangleBox(*map.mesh, id);
  }
};

using Traits = CGAL::AABB_traits<Kernel, TrianglePrimitive, TriangleBboxMap>;

using TreeNode = CGAL::AABB_node<Traits>;

}  // namespace
}  // namespace hapticad

// CGAL keeps the tree's nodes (64 bytes a triangle) and primitives (16) in std::vectors
// with the default allocator; these two specializations put them on huge pages, as the
// mesh's arrays are: on this VM the first touch of ordinary pages was half of a 1M-triangle
// tree's build (530 -> 270 ms alone in a process), and a walk of the tree needs fewer TLB
// entries. Both types live in this file's unnamed namespace, so no other translation unit
// can instantiate the primary std::allocator for them.
namespace std {
template <>
struct allocator<hapticad::TreeNode> : hapticad::HugePageStdAllocator<hapticad::TreeNode> {
  using HugePageStdAllocator::HugePageStdAllocator;
};
template <>
struct allocator<hapticad::TrianglePrimitive>
    : hapticad::HugePageStdAllocator<hapticad::TrianglePrimitive> {
  using HugePageStdAllocator::HugePageStdAllocator;
};
}  // namespace std

namespace hapticad {
namespace {

using Tree = CGAL::AABB_tree<Traits>;

// CGAL's split (the median of the reference points along the box's longest axis), with
// a selection that does not branch on its comparisons (median_select.h). Any
// permutation of the range makes a correct tree; this one makes CGAL's up to the order
// of equal keys.
struct MedianSplit {
  template <class Iterator>
  void operator()(Iterator first, Iterator beyond, const CGAL::Bbox_3& box) const {
    const int axis = static_cast<int>(Traits::longest_axis(box));
    const auto n = static_cast<std::size_t>(beyond - first);
    SelectNth(&*first, n, n / 2, [axis](const TrianglePrimitive& p) { return p.reference(axis); });
  }
};

// CGAL's walk over the boxes, nearest entry first (traversal_with_priority), feeding the
// triangles to a SweepSearch and pruning every box entered beyond its nearest contact
// so far. A sphere query grows every box by its radius: the swept sphere meets a box
// only if its centre's segment meets the box grown by r. (Testing the boxes against the
// floors too was measured slower: it costs every box, and the boxes it would prune are
// mostly pruned by the segment already.)
class FirstHitTraversal {
 public:
  using Priority = double;

  FirstHitTraversal(SweepSearch* search, double pad)
      : search_(*search), ray_(search->a(), search->d()), pad_(pad + search->radius()) {}

  bool go_further() const { return true; }

  void intersection(const Vec3&, const TrianglePrimitive& primitive) {
    search_.Test(primitive.id());
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

 private:
  bool Enter(const CGAL::Bbox_3& box, double* entry) const {
    const double lo[3] = {box.xmin(), box.ymin(), box.zmin()};
    const double hi[3] = {box.xmax(), box.ymax(), box.zmax()};
    return IntersectSegmentBox(ray_, search_.best_s(), lo, hi, pad_, entry);
  }

  SweepSearch& search_;
  const SegmentRay ray_;
  const double pad_;
};

// The closest point: the nearest box first, every box farther than the nearest point
// so far pruned. CGAL's own query walks the boxes in a fixed order from a starting hint
// it looks up in a kd-tree of vertices; this walk needs no hint, so the tree keeps
// nothing but its nodes and primitives.
class ClosestPointTraversal {
 public:
  using Priority = double;

  // Only triangles closer than `max_distance` are looked for (inf: the nearest of all).
  ClosestPointTraversal(const TriangleMesh& mesh, const Vec3& p,
                        double max_distance = std::numeric_limits<double>::infinity())
      : mesh_(mesh), p_(p), best_d2_(max_distance * max_distance) {}

  bool go_further() const { return true; }

  void intersection(const Vec3&, const TrianglePrimitive& primitive) {
    const auto& t = mesh_.triangle(primitive.id());
    const Kernel::Triangle_3 triangle(ToPoint(mesh_.vertex(t[0])), ToPoint(mesh_.vertex(t[1])),
                                      ToPoint(mesh_.vertex(t[2])));
    const Kernel::Point_3 c = Kernel::Construct_projected_point_3()(triangle, ToPoint(p_));
    const Vec3 point(c.x(), c.y(), c.z());
    const double d2 = (point - p_).squaredNorm();
    if (d2 < best_d2_) {
      best_d2_ = d2;
      best_.point = point;
      best_.triangle = primitive.id();
      found_ = true;
    }
  }

  template <class Node>
  bool do_intersect(const Vec3&, const Node& node) const {
    return CalcBoxDistance2(node.bbox()) <= best_d2_;
  }

  template <class Node>
  std::pair<bool, Priority> do_intersect_with_priority(const Vec3&, const Node& node) const {
    const double d2 = CalcBoxDistance2(node.bbox());
    return {d2 <= best_d2_, -d2};
  }

  // Whether a triangle was found (always, with no distance bound and a triangle).
  bool found() const { return found_; }
  // Meaningful once a triangle was found.
  SurfacePoint Result() const {
    SurfacePoint out = best_;
    out.distance = std::sqrt(best_d2_);
    return out;
  }

 private:
  static Kernel::Point_3 ToPoint(const Vec3& p) { return Kernel::Point_3(p.x(), p.y(), p.z()); }

  double CalcBoxDistance2(const CGAL::Bbox_3& box) const {
    const double lo[3] = {box.xmin(), box.ymin(), box.zmin()};
    const double hi[3] = {box.xmax(), box.ymax(), box.zmax()};
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double gap = std::max({lo[k] - p_[k], p_[k] - hi[k], 0.0});
      d2 += gap * gap;
    }
    return d2;
  }

  const TriangleMesh& mesh_;
  const Vec3 p_;
  double best_d2_;
  bool found_ = false;
  SurfacePoint best_{0, Vec3::Zero(), 0.0};
};

}  // namespace

struct TriangleTree::Impl {
  const TriangleMesh* mesh = nullptr;
  double pad = 0.0;
  HugePageVector<FloatBox> build_boxes;  // only while building
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
  impl->boxes.cached = &impl->build_boxes;
  impl->tree.~Tree();
  new (&impl->tree) Tree(Traits(impl->boxes));
  const auto n = static_cast<std::uint32_t>(mesh.num_triangles());
  impl->tree.insert(boost::counting_iterator<std::uint32_t>(0),
                    boost::counting_iterator<std::uint32_t>(n), &mesh);
  impl->build_boxes.resize(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const CGAL::Bbox_3 box = CalcTriangleBox(mesh, t);
    impl->build_boxes[t] = ToFloatBox(Vec3(box.xmin(), box.ymin(), box.zmin()),
                                      Vec3(box.xmax(), box.ymax(), box.zmax()));
  }
  // CGAL defers both to the first query: do them now, off the servo thread. custom_build
  // (public in CGAL 5.5, though not in its manual) is build() with the split given.
  impl->tree.custom_build(impl->tree.traits().compute_bbox_object(), MedianSplit());
  impl->build_boxes.clear();
  impl->build_boxes.shrink_to_fit();
  // CGAL would build a kd-tree of starting hints for its closest-point query on first
  // use; CalcClosestPoint walks the boxes nearest first instead and needs none.
  impl->tree.do_not_accelerate_distance_queries();
  return std::unique_ptr<TriangleTree>(new TriangleTree(std::move(impl)));
}

bool TriangleTree::FirstHit(const SweepQuery& query, SweepHit* hit) const {
  SweepSearch search(*impl_->mesh, query);
  Search(&search);
  if (!search.found()) return false;
  search.Report(hit);
  return true;
}

void TriangleTree::Search(SweepSearch* search) const {
  FirstHitTraversal traversal(search, impl_->pad);
  impl_->tree.traversal_with_priority(search->a(), traversal);
}

double TriangleTree::pad() const { return impl_->pad; }

SurfacePoint TriangleTree::CalcClosestPoint(const Vec3& p) const {
  ClosestPointTraversal traversal(*impl_->mesh, p);
  impl_->tree.traversal_with_priority(p, traversal);
  return traversal.Result();
}

bool TriangleTree::FindClosestPointWithin(const Vec3& p, double max_distance,
                                          SurfacePoint* out) const {
  if (!(max_distance > 0.0)) return false;  // nothing is closer than 0 (or NaN)
  ClosestPointTraversal traversal(*impl_->mesh, p, max_distance);
  impl_->tree.traversal_with_priority(p, traversal);
  if (!traversal.found()) return false;
  *out = traversal.Result();
  return true;
}

std::size_t TriangleTree::num_triangles() const { return impl_->tree.size(); }

std::size_t TriangleTree::CalcMemoryBytes() const {
  const std::size_t n = impl_->tree.size();
  // CGAL keeps n - 1 nodes (a Bbox_3 and two child pointers each) and n primitives
  return (n > 0 ? n - 1 : 0) * (sizeof(CGAL::Bbox_3) + 2 * sizeof(void*)) +
         n * sizeof(TrianglePrimitive);
}

}  // namespace hapticad
