// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/icosphere.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "hapticad/core/geometry/triangle_mesh.h"

namespace hapticad {
namespace {

TEST(Icosphere, HasTheReferenceTriangleCountsAndIsClosed) {
  EXPECT_EQ(IcosphereFrequencyFor(9680), 22);
  EXPECT_EQ(IcosphereFrequencyFor(100820), 71);
  EXPECT_EQ(IcosphereFrequencyFor(1003520), 224);
  const TriangleSoup s = MakeIcosphere(22, 50.0);
  EXPECT_EQ(s.triangles.size(), 9680u);
  EXPECT_EQ(s.vertices.size(), 9680u / 2 + 2);  // Euler: V = T/2 + 2 for a closed sphere
  const auto mesh = TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, {});
  EXPECT_TRUE(mesh->closed());
}

TEST(Icosphere, VerticesLieOnTheSphereAndFacesPointOut) {
  const Vec3 centre(1, 2, 3);
  const TriangleSoup s = MakeIcosphere(5, 2.5, centre, true);
  for (const Vec3& v : s.vertices) EXPECT_NEAR((v - centre).norm(), 2.5, 1e-12);
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Vec3& a = s.vertices[s.triangles[t][0]];
    const Vec3 n = (s.vertices[s.triangles[t][1]] - a).cross(s.vertices[s.triangles[t][2]] - a);
    EXPECT_GT(n.dot(a - centre), 0.0) << t;
    EXPECT_NEAR(s.corner_normals[t][0].dot((a - centre).normalized()), 1.0, 1e-12);
  }
}

TEST(Icosphere, RejectsBadArguments) {
  EXPECT_THROW(MakeIcosphere(0, 1.0), std::invalid_argument);
  EXPECT_THROW(MakeIcosphere(3, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad
