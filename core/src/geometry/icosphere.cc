// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/icosphere.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace hapticad {
namespace {

const std::array<Vec3, 12>& IcosahedronVertices() {
  static const std::array<Vec3, 12> v = [] {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::array<Vec3, 12> p = {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                              Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                              Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
    for (Vec3& q : p) q.normalize();
    return p;
  }();
  return v;
}

constexpr int kFaces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};

}  // namespace

int IcosphereFrequencyFor(long long triangles) {
  return std::max(1,
                  static_cast<int>(std::lround(std::sqrt(static_cast<double>(triangles) / 20.0))));
}

TriangleSoup MakeIcosphere(int n, double radius, const Vec3& centre, bool with_corner_normals) {
  if (n < 1) throw std::invalid_argument("icosphere: frequency must be >= 1");
  if (!(std::isfinite(radius) && radius > 0.0))
    throw std::invalid_argument("icosphere: radius must be finite and > 0");
  const auto& ico = IcosahedronVertices();
  TriangleSoup soup;
  // a point of the subdivided icosahedron is named by the icosahedron vertices it lies
  // between and its integer barycentrics, written canonically (sorted by vertex) so
  // that faces sharing an edge or a corner name it the same way
  std::map<std::array<int, 6>, std::int32_t> index;
  auto vertex = [&](const int f[3], int i, int j) {
    const int w[3] = {n - i - j, i, j};
    // zero-weight vertices are dropped before sorting, or an edge point would have
    // a different name in each face
    std::array<std::pair<int, int>, 3> terms = {{{f[0], w[0]}, {f[1], w[1]}, {f[2], w[2]}}};
    for (auto& term : terms) {
      if (term.second == 0) term = {1 << 20, 0};
    }
    std::sort(terms.begin(), terms.end());
    std::array<int, 6> key{};
    for (int k = 0; k < 3; ++k) {
      key[2 * k] = terms[k].first;
      key[2 * k + 1] = terms[k].second;
    }
    const auto found = index.find(key);
    if (found != index.end()) return found->second;
    Vec3 p = Vec3::Zero();
    for (const auto& [v, weight] : terms) {
      if (weight != 0) p += weight * ico[v];
    }
    p.normalize();
    const auto id = static_cast<std::int32_t>(soup.vertices.size());
    soup.vertices.push_back(centre + radius * p);
    index.emplace(key, id);
    return id;
  };
  soup.triangles.reserve(20 * static_cast<std::size_t>(n) * n);
  for (const auto& face : kFaces) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        const std::int32_t a = vertex(face, i, j);
        const std::int32_t b = vertex(face, i + 1, j);
        const std::int32_t c = vertex(face, i, j + 1);
        soup.triangles.push_back({a, b, c});
        if (i + j + 1 < n) soup.triangles.push_back({b, vertex(face, i + 1, j + 1), c});
      }
    }
  }
  soup.cad_faces.assign(soup.triangles.size(), 0);
  if (with_corner_normals) {
    soup.corner_normals.reserve(soup.triangles.size());
    for (const auto& t : soup.triangles) {
      soup.corner_normals.push_back({(soup.vertices[t[0]] - centre).normalized(),
                                     (soup.vertices[t[1]] - centre).normalized(),
                                     (soup.vertices[t[2]] - centre).normalized()});
    }
  }
  return soup;
}

}  // namespace hapticad
