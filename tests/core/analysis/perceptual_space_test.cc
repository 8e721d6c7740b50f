// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/analysis/perceptual_space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace hapticad {
namespace {

Eigen::MatrixXd Distances(const Eigen::MatrixXd& points) {
  const Eigen::Index n = points.rows();
  Eigen::MatrixXd d(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) d(i, j) = (points.row(i) - points.row(j)).norm();
  }
  return d;
}

// The paper's nine textures: three DC friction levels by three viscosities, placed in a
// plane with friction along one direction (spread `friction`) and viscosity along another
// at `angle` to it (spread `viscosity`), then moved, turned and given a third, small axis.
struct Grid {
  std::vector<double> dc, vis;
  Eigen::MatrixXd points;
};

Grid PaperGrid(double friction, double viscosity, double angle) {
  Grid grid;
  grid.points.resize(9, 3);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double q_dc = 0.5 * (i - 1), q_vis = 0.5 * (j - 1);
      grid.dc.push_back(0.325 + 0.175 * i);
      grid.vis.push_back(-0.2 + 0.2 * j);
      grid.points.row(3 * i + j) << 100 + friction * q_dc + viscosity * q_vis * std::cos(angle),
          -40 + viscosity * q_vis * std::sin(angle), 7.0;
    }
  }
  return grid;
}

TEST(PerceptualSpace, RecoversTheDistancesOfPointsInAPlane) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-3, 3);
  Eigen::MatrixXd points(9, 2);
  for (Eigen::Index i = 0; i < points.size(); ++i) points.data()[i] = uniform(rng);
  const Eigen::MatrixXd d = Distances(points);
  const PerceptualSpace space = ComputePerceptualSpace(d, 2);
  ASSERT_EQ(space.points.rows(), 9);
  ASSERT_EQ(space.points.cols(), 2);
  EXPECT_LT((Distances(space.points) - d).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(space.stress, 1e-9);
  EXPECT_NEAR(space.explained, 1.0, 1e-12);
  EXPECT_NEAR(space.points.colwise().sum().norm(), 0.0, 1e-9);  // centred
  ASSERT_EQ(space.eigenvalues.size(), 9u);
  EXPECT_DOUBLE_EQ(space.eigenvalues[0], 1.0);
  EXPECT_GE(space.eigenvalues[0], space.eigenvalues[1]);
  for (std::size_t k = 2; k < 9; ++k) EXPECT_NEAR(space.eigenvalues[k], 0.0, 1e-12);
}

TEST(PerceptualSpace, OneAxisKeepsTheLargestSpreadAndSaysWhatIsLost) {
  Eigen::MatrixXd points(4, 2);
  points << -3, 0, 3, 0, 0, -1, 0, 1;  // spread 3 along x, 1 along y
  const PerceptualSpace space = ComputePerceptualSpace(Distances(points), 1);
  EXPECT_NEAR(std::abs(space.points(0, 0)), 3.0, 1e-9);
  EXPECT_NEAR(std::abs(space.points(2, 0)), 0.0, 1e-9);
  EXPECT_NEAR(space.explained, 18.0 / 20.0, 1e-12);  // eigenvalues 18 and 2
  EXPECT_GT(space.stress, 0.05);
}

TEST(PerceptualSpace, AxesAreSignedSoTheSameDataGiveTheSamePicture) {
  const Grid grid = PaperGrid(1.0, 0.6, 1.2);
  const PerceptualSpace a = ComputePerceptualSpace(Distances(grid.points), 2);
  const PerceptualSpace b = ComputePerceptualSpace(Distances(grid.points), 2);
  EXPECT_EQ(a.points, b.points);
  // symmetric about the centre, so each axis's largest coordinates come in +- pairs:
  // the first stimulus is on the positive side of both axes
  EXPECT_GT(a.points(0, 0), 0.0);
  EXPECT_GT(a.points(0, 1), 0.0);
  // the order of the stimuli, not rounding, sets the signs: reversed, the picture flips
  const Eigen::MatrixXd reversed = grid.points.colwise().reverse();
  const PerceptualSpace c = ComputePerceptualSpace(Distances(reversed), 2);
  EXPECT_GT(c.points(0, 0), 0.0);
  EXPECT_LT((c.points.colwise().reverse() + a.points).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(PerceptualSpace, SameShapeAtEveryScale) {
  const Grid grid = PaperGrid(1.0, 0.6, 1.2);
  const Eigen::MatrixXd d = Distances(grid.points);
  const PerceptualSpace unit = ComputePerceptualSpace(d, 2);
  for (double scale : {1e-150, 1e-6, 1e6, 1e150, 1e300}) {
    const PerceptualSpace scaled = ComputePerceptualSpace(d * scale, 2);
    ASSERT_TRUE(scaled.points.allFinite()) << scale;
    EXPECT_LT((scaled.points / scale - unit.points).cwiseAbs().maxCoeff(), 1e-9) << scale;
    EXPECT_NEAR(scaled.stress, unit.stress, 1e-12) << scale;
    EXPECT_NEAR(scaled.explained, unit.explained, 1e-12) << scale;
  }
}

TEST(PerceptualSpace, NotEuclideanGivesNegativeEigenvaluesAndStressButNoNan) {
  // 0-1 and 1-2 close, 0-2 far: the triangle inequality broken
  Eigen::MatrixXd d(4, 4);
  d << 0, 1, 5, 2, 1, 0, 1, 2, 5, 1, 0, 2, 2, 2, 2, 0;
  const PerceptualSpace space = ComputePerceptualSpace(d, 2);
  EXPECT_TRUE(space.points.allFinite());
  EXPECT_LT(space.eigenvalues.back(), -1e-3);
  EXPECT_LT(space.explained, 1.0);
  EXPECT_GT(space.stress, 0.01);
  EXPECT_LT(space.stress, 1.0);
}

TEST(PerceptualSpace, AllAlikePutsEveryStimulusAtTheOrigin) {
  const PerceptualSpace space = ComputePerceptualSpace(Eigen::MatrixXd::Zero(5, 5), 2);
  EXPECT_EQ(space.points, Eigen::MatrixXd::Zero(5, 2));
  EXPECT_EQ(space.stress, 0.0);
  EXPECT_EQ(space.explained, 0.0);
  for (double value : space.eigenvalues) EXPECT_EQ(value, 0.0);
  const PropertyVector vector = FitPropertyVector(space.points, {-0.5, -0.5, 0, 0.5, 0.5});
  EXPECT_EQ(vector.length, 0.0);
  EXPECT_EQ(vector.correlation, 0.0);
}

TEST(PerceptualSpace, RejectsWhatCannotBeScaled) {
  const Eigen::MatrixXd good = Distances(PaperGrid(1, 1, 1).points);
  EXPECT_THROW(ComputePerceptualSpace(Eigen::MatrixXd::Zero(3, 4), 2), std::invalid_argument);
  EXPECT_THROW(ComputePerceptualSpace(Eigen::MatrixXd::Zero(2, 2), 1), std::invalid_argument);
  EXPECT_THROW(ComputePerceptualSpace(good, 0), std::invalid_argument);
  EXPECT_THROW(ComputePerceptualSpace(good, 9), std::invalid_argument);
  Eigen::MatrixXd bad = good;
  bad(1, 2) = bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ComputePerceptualSpace(bad, 2), std::invalid_argument);
  bad = good;
  bad(1, 2) = bad(2, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ComputePerceptualSpace(bad, 2), std::invalid_argument);
  bad = good;
  bad(1, 2) = bad(2, 1) = -0.1;
  EXPECT_THROW(ComputePerceptualSpace(bad, 2), std::invalid_argument);
  bad = good;
  bad(1, 2) += 0.1;
  EXPECT_THROW(ComputePerceptualSpace(bad, 2), std::invalid_argument);
  bad = good;
  bad(4, 4) = 0.1;
  EXPECT_THROW(ComputePerceptualSpace(bad, 2), std::invalid_argument);
  try {
    ComputePerceptualSpace(Eigen::MatrixXd::Zero(2, 2), 1);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("at least 3"), std::string::npos) << e.what();
  }
}

TEST(PropertyVector, Eq3GivesEachParametersSpreadAndDirection) {
  // friction spread 1.0, viscosity 0.6 at 70 degrees to it: eq. 3 on the scaled levels
  // gives vectors of those lengths at that angle, through the scaled space
  const double angle = 70.0 * 3.14159265358979323846 / 180.0;
  const Grid grid = PaperGrid(1.0, 0.6, angle);
  const PerceptualSpace space = ComputePerceptualSpace(Distances(grid.points), 2);
  const std::vector<double> q_dc = ScaleToUnitRange(grid.dc), q_vis = ScaleToUnitRange(grid.vis);
  const PropertyVector dc = FitPropertyVector(space.points, q_dc);
  const PropertyVector vis = FitPropertyVector(space.points, q_vis);
  // a full factorial: each parameter's q is orthogonal to the other's, so eq. 3 reads
  // each one's own spread, but the other's tilt shows in it as cos(angle)
  EXPECT_NEAR(dc.length, 1.0, 1e-9);
  EXPECT_NEAR(vis.length, 0.6, 1e-9);
  EXPECT_NEAR(dc.direction.dot(vis.direction) / (dc.length * vis.length), std::cos(angle), 1e-9);
  // along the vector the points line up by the parameter, but the other parameter
  // spreads them: r = 1 / sqrt(1 + (0.6 cos 70)^2)
  const double along = 0.6 * std::cos(angle);
  EXPECT_NEAR(dc.correlation, 1.0 / std::sqrt(1.0 + along * along), 1e-9);
  // the points projected onto a vector rise with its parameter
  const Eigen::VectorXd projected = space.points * dc.direction;
  EXPECT_LT(projected(0), projected(8));
}

TEST(PropertyVector, ANoisyParameterDrawsAShortVectorWithLowCorrelation) {
  const Grid grid = PaperGrid(1.0, 0.6, 1.5);
  const PerceptualSpace space = ComputePerceptualSpace(Distances(grid.points), 2);
  const std::vector<double> unrelated = {0.5, -0.5, 0.1, -0.3, 0.4, -0.2, 0.0, 0.3, -0.4};
  const PropertyVector vector = FitPropertyVector(space.points, unrelated);
  EXPECT_LT(vector.length, 0.35);
  EXPECT_LT(std::abs(vector.correlation), 0.6);
  EXPECT_GT(FitPropertyVector(space.points, ScaleToUnitRange(grid.dc)).correlation, 0.95);
}

TEST(PropertyVector, RejectsWhatPointsNowhere) {
  const Eigen::MatrixXd points = Eigen::MatrixXd::Identity(3, 2);
  EXPECT_THROW(FitPropertyVector(points, {0.5, -0.5}), std::invalid_argument);
  EXPECT_THROW(FitPropertyVector(points, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(FitPropertyVector(points, {0, std::nan(""), 0}), std::invalid_argument);
  EXPECT_THROW(FitPropertyVector(Eigen::MatrixXd::Zero(1, 2), {0.5}), std::invalid_argument);
}

TEST(ScaleToUnitRange, MapsLowestToMinusHalfAndHighestToPlusHalf) {
  const std::vector<double> levels = ScaleToUnitRange({0.325, 0.5, 0.675, 0.5});
  const std::vector<double> expected = {-0.5, 0.0, 0.5, 0.0};
  ASSERT_EQ(levels.size(), expected.size());
  for (std::size_t i = 0; i < levels.size(); ++i) EXPECT_NEAR(levels[i], expected[i], 1e-15);
  const std::vector<double> uneven = ScaleToUnitRange({-0.2, 0.0, 0.6});
  EXPECT_DOUBLE_EQ(uneven[0], -0.5);
  EXPECT_DOUBLE_EQ(uneven[1], -0.25);
  EXPECT_DOUBLE_EQ(uneven[2], 0.5);
  EXPECT_THROW(ScaleToUnitRange({}), std::invalid_argument);
  EXPECT_THROW(ScaleToUnitRange({0.2, 0.2, 0.2}), std::invalid_argument);
  EXPECT_THROW(ScaleToUnitRange({1.0, 1.0 + 1e-15}),
               std::invalid_argument);  // rounding, not variation
  EXPECT_THROW(ScaleToUnitRange({0.0, std::nan("")}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticad

namespace hapticad {
namespace {

// Nine points in a plane, seeded, away from any symmetry.
Eigen::MatrixXd ScatteredPlane(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-3, 3);
  Eigen::MatrixXd points(9, 2);
  for (Eigen::Index i = 0; i < points.size(); ++i) points.data()[i] = uniform(rng);
  return points;
}

// How far `a` lies from `b` after the best turn, mirror and scale of `a` onto `b`
// (Procrustes), relative to b's spread.
double ShapeMismatch(Eigen::MatrixXd a, Eigen::MatrixXd b) {
  a.rowwise() -= a.colwise().mean();
  b.rowwise() -= b.colwise().mean();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a.transpose() * b,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::MatrixXd turn = svd.matrixU() * svd.matrixV().transpose();
  const double scale = svd.singularValues().sum() / a.squaredNorm();
  return (scale * a * turn - b).norm() / b.norm();
}

Eigen::MatrixXd Warped(const Eigen::MatrixXd& d, double (*warp)(double)) {
  return d.unaryExpr([warp](double v) { return v == 0 ? 0.0 : warp(v); });
}

TEST(OrdinalPerceptualSpace, OnlyTheOrderCountsAScaleUsedUnevenlyBendsNothing) {
  const Eigen::MatrixXd truth = ScatteredPlane(5);
  const Eigen::MatrixXd d = Distances(truth);
  // participants who call everything past middling distance "nothing alike": the
  // dissimilarities are a steep monotone function of the distances
  for (const auto warp :
       {+[](double v) { return v * v * v; }, +[](double v) { return std::log1p(v); },
        +[](double v) { return std::min(v, 3.0) + 0.01 * v; }}) {
    const Eigen::MatrixXd warped = Warped(d, warp);
    const PerceptualSpace ordinal = ComputeOrdinalPerceptualSpace(warped, 2);
    EXPECT_TRUE(ordinal.converged);
    EXPECT_LT(ordinal.stress, 1e-3);
    // the order of 36 pairs pins nine points' shape to a few percent (every such shape
    // fits exactly: stress 1e-14); the metric space reads the warp as shape
    EXPECT_LT(ShapeMismatch(ordinal.points, truth), 0.06);
    const PerceptualSpace metric = ComputePerceptualSpace(warped, 2);
    EXPECT_GT(ShapeMismatch(metric.points, truth), 3 * ShapeMismatch(ordinal.points, truth));
  }
  // more stimuli, more pairs to order: the shape comes out closer
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> uniform(-3, 3);
  Eigen::MatrixXd many(25, 2);
  for (Eigen::Index i = 0; i < many.size(); ++i) many.data()[i] = uniform(rng);
  const PerceptualSpace ordinal =
      ComputeOrdinalPerceptualSpace(Warped(
                                        Distances(many), +[](double v) { return v * v * v; }),
                                    2);
  EXPECT_LT(ShapeMismatch(ordinal.points, many), 0.01);
}

TEST(OrdinalPerceptualSpace, ASpaceThatHoldsTheDataExactlyIsKept) {
  const Eigen::MatrixXd truth = ScatteredPlane(7);
  const PerceptualSpace ordinal = ComputeOrdinalPerceptualSpace(Distances(truth), 2);
  EXPECT_LT(ordinal.stress, 1e-6);
  EXPECT_LT(ShapeMismatch(ordinal.points, truth), 1e-4);
  // scaled back to the data: distances' root mean square is the dissimilarities'
  EXPECT_NEAR(Distances(ordinal.points).norm(), Distances(truth).norm(),
              1e-9 * Distances(truth).norm());
  EXPECT_NEAR(ordinal.points.colwise().sum().norm(), 0.0, 1e-9);  // centred
  // on principal axes: the first spreads most, and they are uncorrelated
  EXPECT_GE(ordinal.points.col(0).squaredNorm(), ordinal.points.col(1).squaredNorm());
  EXPECT_NEAR(ordinal.points.col(0).dot(ordinal.points.col(1)), 0.0,
              1e-9 * ordinal.points.squaredNorm());
}

TEST(OrdinalPerceptualSpace, NoisyRatingsStillComeOutCloseAndTheSameEveryRun) {
  const Eigen::MatrixXd truth = ScatteredPlane(13);
  Eigen::MatrixXd d = Distances(truth);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (Eigen::Index i = 0; i < 9; ++i) {
    for (Eigen::Index j = i + 1; j < 9; ++j)
      d(i, j) = d(j, i) = std::exp(d(i, j) * (1 + noise(rng)));
  }
  const PerceptualSpace a = ComputeOrdinalPerceptualSpace(d, 2);
  const PerceptualSpace b = ComputeOrdinalPerceptualSpace(d, 2);
  EXPECT_EQ(a.points, b.points);
  EXPECT_GT(a.stress, 1e-4);  // noise no plane holds
  EXPECT_LT(a.stress, 0.1);
  EXPECT_LT(ShapeMismatch(a.points, truth), 0.1);
  EXPECT_LT(ShapeMismatch(a.points, truth),
            ShapeMismatch(ComputePerceptualSpace(d, 2).points, truth));
}

TEST(OrdinalPerceptualSpace, TiedRatingsAndExtremeScalesGiveNoNan) {
  // a 7-point scale averaged over few participants: many ties
  const Eigen::MatrixXd truth = ScatteredPlane(21);
  const Eigen::MatrixXd rounded =
      Distances(truth).unaryExpr([](double v) { return std::round(v); });
  const PerceptualSpace tied = ComputeOrdinalPerceptualSpace(rounded, 2);
  EXPECT_TRUE(tied.points.allFinite());
  EXPECT_LT(tied.stress, 0.05);
  // three participants' ratings (7 steps) of the paper's nine gratings, in eighteenths,
  // from a reviewer's run: an exact monotone fit exists (ties part, Kruskal's primary
  // approach), and SMACOF creeps towards it. Stress-1 below 1e-5 is that fit: it used to
  // run its 2000 rounds at stress-1 8e-7 and say it had not settled.
  const int eighteenths[9][9] = {
      {0, 7, 15, 6, 12, 16, 14, 15, 18}, {7, 0, 8, 13, 9, 12, 16, 14, 15},
      {15, 8, 0, 15, 12, 6, 17, 15, 14}, {6, 13, 15, 0, 7, 14, 6, 12, 15},
      {12, 9, 12, 7, 0, 6, 12, 6, 12},   {16, 12, 6, 14, 6, 0, 17, 12, 6},
      {14, 16, 17, 6, 12, 17, 0, 5, 14}, {15, 14, 15, 12, 6, 12, 5, 0, 6},
      {18, 15, 14, 15, 12, 6, 14, 6, 0}};
  Eigen::MatrixXd rated(9, 9);
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) rated(i, j) = eighteenths[i][j] / 18.0;
  }
  const PerceptualSpace nine = ComputeOrdinalPerceptualSpace(rated, 2);
  EXPECT_TRUE(nine.converged) << nine.iterations << " rounds, stress " << nine.stress;
  EXPECT_LT(nine.iterations, OrdinalScalingOptions{}.max_iterations);
  EXPECT_LT(nine.stress, 1e-5);
  // the same shape at every scale
  for (const double scale : {1e-150, 1e300}) {
    const PerceptualSpace scaled = ComputeOrdinalPerceptualSpace(rounded * scale, 2);
    ASSERT_TRUE(scaled.points.allFinite()) << scale;
    EXPECT_LT((scaled.points / scale - tied.points).cwiseAbs().maxCoeff(),
              1e-9 * tied.points.cwiseAbs().maxCoeff())
        << scale;
    EXPECT_NEAR(scaled.stress, tied.stress, 1e-9) << scale;
  }
  // all alike: every point at the origin, as the classical space
  const PerceptualSpace alike = ComputeOrdinalPerceptualSpace(Eigen::MatrixXd::Zero(5, 5), 2);
  EXPECT_EQ(alike.points, Eigen::MatrixXd::Zero(5, 2));
  // every pair equally unlike: no plane holds it, but nothing breaks
  Eigen::MatrixXd equal = Eigen::MatrixXd::Constant(6, 6, 1.0);
  equal.diagonal().setZero();
  const PerceptualSpace flat = ComputeOrdinalPerceptualSpace(equal, 2);
  EXPECT_TRUE(flat.points.allFinite());
  EXPECT_TRUE(std::isfinite(flat.stress));
}

TEST(OrdinalPerceptualSpace, RejectsWhatCannotBeScaledAndBadOptions) {
  Eigen::MatrixXd d = Distances(ScatteredPlane(1));
  d(0, 1) = -1;
  EXPECT_THROW(ComputeOrdinalPerceptualSpace(d, 2), std::invalid_argument);
  d = Distances(ScatteredPlane(1));
  EXPECT_THROW(ComputeOrdinalPerceptualSpace(d, 9), std::invalid_argument);
  OrdinalScalingOptions options;
  options.max_iterations = 0;
  EXPECT_THROW(ComputeOrdinalPerceptualSpace(d, 2, options), std::invalid_argument);
  options.max_iterations = 10;
  options.tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ComputeOrdinalPerceptualSpace(d, 2, options), std::invalid_argument);
  options.tolerance = 0;
  for (const double bad :
       {-1e-5, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    options.exact_stress = bad;
    EXPECT_THROW(ComputeOrdinalPerceptualSpace(d, 2, options), std::invalid_argument) << bad;
  }
  options.exact_stress = OrdinalScalingOptions{}.exact_stress;
  // a round limit is a limit, and says so
  options.tolerance = 0;
  options.max_iterations = 2;
  const PerceptualSpace cut =
      ComputeOrdinalPerceptualSpace(Warped(
                                        d, +[](double v) { return v * v * v; }),
                                    2, options);
  EXPECT_EQ(cut.iterations, 2);
  EXPECT_FALSE(cut.converged);
}

}  // namespace
}  // namespace hapticad
