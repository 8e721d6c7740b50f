// SPDX-License-Identifier: GPL-3.0-or-later
#include "test_meshes.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace hapticad::testing {

TriangleSoup MakeBoxSoup(const Vec3& lo, const Vec3& hi) {
  TriangleSoup soup;
  for (int i = 0; i < 8; ++i) {
    soup.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                               i & 4 ? hi.z() : lo.z());
  }
  // each quad a, b, c, d counter-clockwise seen from outside
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (int f = 0; f < 6; ++f) {
    const auto& q = quads[f];
    soup.triangles.push_back({q[0], q[1], q[2]});
    soup.triangles.push_back({q[0], q[2], q[3]});
    soup.cad_faces.push_back(f);
    soup.cad_faces.push_back(f);
  }
  return soup;
}

TriangleSoup MakeSheetSoup(double half, double height) {
  TriangleSoup soup;
  soup.vertices = {Vec3(-half, -half, height), Vec3(half, -half, height), Vec3(half, half, height),
                   Vec3(-half, half, height)};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  soup.cad_faces = {0, 0};
  return soup;
}

void AppendBoxSoup(TriangleSoup* soup, const Vec3& lo, const Vec3& hi, bool inward) {
  const TriangleSoup box = MakeBoxSoup(lo, hi);
  const auto base = static_cast<std::int32_t>(soup->vertices.size());
  const std::int32_t faces =
      soup->cad_faces.empty()
          ? 0
          : *std::max_element(soup->cad_faces.begin(), soup->cad_faces.end()) + 1;
  soup->vertices.insert(soup->vertices.end(), box.vertices.begin(), box.vertices.end());
  for (std::size_t t = 0; t < box.triangles.size(); ++t) {
    const auto& c = box.triangles[t];
    soup->triangles.push_back(
        inward ? std::array<std::int32_t, 3>{base + c[0], base + c[2], base + c[1]}
               : std::array<std::int32_t, 3>{base + c[0], base + c[1], base + c[2]});
    soup->cad_faces.push_back(faces + box.cad_faces[t]);
  }
}

}  // namespace hapticad::testing
