// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/contact/god_object_proxy.h"

#include <random>

#include <gtest/gtest.h>

#include "test_meshes.h"

namespace hapticad {
namespace {

// Every test runs twice: the point proxy sweeping CGAL's tree, then the grid (a sphere
// always sweeps the tree).
class ProxyOnBox : public ::testing::TestWithParam<bool> {
 protected:
  void Make(const TriangleSoup& s, double radius = 0.0) {
    proxy_.reset();
    mesh_ = TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
    tree_ = TriangleTree::Build(*mesh_, 1e-12);
    grid_ = TriangleGrid::Build(*mesh_, 1e-12);
    ProxyConfig config;
    config.surface_offset_m = kOffset;
    config.radius_m = radius;
    if (GetParam() && radius == 0.0) {
      proxy_ = std::make_unique<GodObjectProxy>(*mesh_, *grid_, config);
    } else {
      proxy_ = std::make_unique<GodObjectProxy>(*mesh_, *tree_, config);
    }
  }
  static constexpr double kOffset = 1e-8;
  std::unique_ptr<TriangleMesh> mesh_;
  std::unique_ptr<TriangleTree> tree_;
  std::unique_ptr<TriangleGrid> grid_;
  std::unique_ptr<GodObjectProxy> proxy_;
};

INSTANTIATE_TEST_SUITE_P(TreeAndGrid, ProxyOnBox, ::testing::Values(false, true),
                         [](const auto& test) { return test.param ? "Grid" : "Tree"; });

TEST(GodObjectProxy, TheGridAnswersAPointProxyOnly) {
  const TriangleSoup s = testing::MakeBoxSoup(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  const auto mesh = TriangleMesh::Build(s.vertices, s.triangles, s.cad_faces, s.corner_normals);
  const auto grid = TriangleGrid::Build(*mesh, 1e-12);
  ProxyConfig config;
  config.radius_m = 0.01;
  EXPECT_THROW(GodObjectProxy(*mesh, *grid, config), std::invalid_argument);
  config.radius_m = 0.0;
  EXPECT_NO_THROW(GodObjectProxy(*mesh, *grid, config));
}

TEST_P(ProxyOnBox, FollowsTheDeviceInFreeSpace) {
  Make(testing::MakeBoxSoup(Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05)));
  proxy_->Reset(Vec3(0, 0, 0.2));
  proxy_->Update(Vec3(0.01, 0.02, 0.1));
  EXPECT_FALSE(proxy_->in_contact());
  EXPECT_EQ(proxy_->position(), Vec3(0.01, 0.02, 0.1));
}

TEST_P(ProxyOnBox, StaysOnTheSurfaceWhileTheDevicePressesAndSlides) {
  Make(testing::MakeBoxSoup(Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05)));
  proxy_->Reset(Vec3(0, 0, 0.06));
  // press 2 mm into the top, then slide across it in 1 ms steps at 50 mm/s
  for (int i = 0; i <= 20; ++i) proxy_->Update(Vec3(0, 0, 0.05 - 0.0001 * i));
  for (int i = 0; i < 1000; ++i) {
    const Vec3 goal(-0.04 + 0.00005 * i, 0.01, 0.048);
    proxy_->Update(goal);
    ASSERT_TRUE(proxy_->in_contact()) << i;
    EXPECT_NEAR(proxy_->position().z(), 0.05 + kOffset, 1e-12) << i;
    EXPECT_NEAR(proxy_->position().x(), goal.x(), 1e-12) << i;
    EXPECT_NEAR(proxy_->position().y(), goal.y(), 1e-12) << i;
  }
}

TEST_P(ProxyOnBox, ReleasesWhenTheDeviceLeaves) {
  Make(testing::MakeBoxSoup(Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05)));
  proxy_->Reset(Vec3(0, 0, 0.06));
  proxy_->Update(Vec3(0, 0, 0.04));
  ASSERT_TRUE(proxy_->in_contact());
  proxy_->Update(Vec3(0, 0, 0.07));
  EXPECT_FALSE(proxy_->in_contact());
  EXPECT_EQ(proxy_->position(), Vec3(0, 0, 0.07));
}

TEST_P(ProxyOnBox, NeitherAPointNorASphereEverEntersTheBoxUnderRandomMotion) {
  for (double r : {0.0, 0.003}) {
    Make(testing::MakeBoxSoup(Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05)), r);
    std::mt19937 rng(1234);
    std::normal_distribution<double> step(0.0, 0.004);
    proxy_->Reset(Vec3(0, 0, 0.08));
    Vec3 goal(0, 0, 0.08);
    for (int i = 0; i < 20000; ++i) {
      goal += Vec3(step(rng), step(rng), step(rng));
      goal = goal.cwiseMax(Vec3::Constant(-0.09)).cwiseMin(Vec3::Constant(0.09));
      proxy_->Update(goal);
      // distance from the centre to the solid box: at least the radius and half the offset
      const Vec3 outside = (proxy_->position().cwiseAbs() - Vec3::Constant(0.05)).cwiseMax(0.0);
      ASSERT_GE(outside.norm(), r + 0.5 * kOffset) << "radius " << r << " step " << i;
    }
  }
}

TEST_P(ProxyOnBox, ResolvesAConcaveCornerWithThreePlanes) {
  // inside a box every wall faces the proxy: pushing past a corner binds three walls
  Make(testing::MakeBoxSoup(Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05)));
  proxy_->Reset(Vec3(0, 0, 0));
  proxy_->Update(Vec3(0.06, 0.07, 0.08));
  EXPECT_EQ(proxy_->constraints().count(), 3);
  EXPECT_NEAR((proxy_->position() - Vec3::Constant(0.05 - kOffset)).norm(), 0.0, 1e-12);
  // two walls: along the edge
  proxy_->Update(Vec3(0.06, 0.07, 0.01));
  EXPECT_NEAR((proxy_->position() - Vec3(0.05 - kOffset, 0.05 - kOffset, 0.01)).norm(), 0.0, 1e-12);
}

TEST_P(ProxyOnBox, FeelsAZeroThicknessSheetFromBothSides) {
  Make(testing::MakeSheetSoup(0.05, 0.0));
  proxy_->Reset(Vec3(0, 0, 0.01));
  proxy_->Update(Vec3(0.001, 0, -0.003));
  EXPECT_NEAR(proxy_->position().z(), kOffset, 1e-15);
  proxy_->Reset(Vec3(0, 0, -0.01));
  proxy_->Update(Vec3(0.001, 0, 0.003));
  EXPECT_NEAR(proxy_->position().z(), -kOffset, 1e-15);
}

TEST_P(ProxyOnBox, ASphereRestsOneRadiusAboveTheFaceAndRollsOverTheEdge) {
  const double r = 0.004;
  Make(testing::MakeBoxSoup(Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05)), r);
  proxy_->Reset(Vec3(0, 0, 0.07));
  proxy_->Update(Vec3(0.01, 0.0, 0.05));  // centre goal 4 mm into the top (r above it)
  ASSERT_TRUE(proxy_->in_contact());
  EXPECT_NEAR(proxy_->position().z(), 0.05 + r + kOffset, 1e-12);
  EXPECT_NEAR((proxy_->contact_point() - Vec3(0.01, 0, 0.05 + kOffset)).norm(), 0.0, 1e-12);
  // slide off the +x edge, pressing down: beyond it the ball rolls round the edge, its
  // centre always r from it, and ends on the side
  for (int i = 0; i <= 400; ++i) {
    const Vec3 goal(0.03 + 0.0001 * i, 0.0, 0.05 - 0.002);
    proxy_->Update(goal);
    const Vec3& c = proxy_->position();
    const Vec3 nearest(std::min(c.x(), 0.05), c.y(), std::min(c.z(), 0.05));
    ASSERT_GE((c - nearest).norm(), r - 1e-12) << i << " " << c.transpose();
  }
  EXPECT_GT(proxy_->position().x(), 0.05 + r - 1e-9);
}

}  // namespace
}  // namespace hapticad
