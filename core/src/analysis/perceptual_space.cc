// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/analysis/perceptual_space.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hapticad {
namespace {

void CheckDissimilarity(const Eigen::MatrixXd& d, int dimensions) {
  const Eigen::Index n = d.rows();
  if (d.cols() != n) {
    throw std::invalid_argument("perceptual space: the dissimilarity matrix is " +
                                std::to_string(n) + " x " + std::to_string(d.cols()) +
                                ", not square");
  }
  if (n < 3) {
    throw std::invalid_argument("perceptual space: " + std::to_string(n) +
                                " stimuli; scaling needs at least 3");
  }
  if (dimensions < 1 || dimensions >= n) {
    throw std::invalid_argument("perceptual space: " + std::to_string(dimensions) +
                                " dimensions; give 1 to " + std::to_string(n - 1) + " for " +
                                std::to_string(n) + " stimuli");
  }
  if (!d.allFinite())
    throw std::invalid_argument("perceptual space: a dissimilarity is not finite");
  if (d.minCoeff() < 0)
    throw std::invalid_argument("perceptual space: a dissimilarity is negative");
  const double tolerance = 1e-9 * d.maxCoeff();  // of the largest: the same test at every scale
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::abs(d(i, i)) > tolerance) {
      throw std::invalid_argument("perceptual space: stimulus " + std::to_string(i) +
                                  " is not at zero dissimilarity from itself");
    }
    for (Eigen::Index j = i + 1; j < n; ++j) {
      if (std::abs(d(i, j) - d(j, i)) > tolerance) {
        throw std::invalid_argument("perceptual space: the dissimilarity of stimuli " +
                                    std::to_string(i) + " and " + std::to_string(j) +
                                    " differs by the order they are taken in");
      }
    }
  }
}

double StressOne(const Eigen::MatrixXd& points, const Eigen::MatrixXd& d) {
  double misfit = 0, total = 0;
  for (Eigen::Index i = 0; i < d.rows(); ++i) {
    for (Eigen::Index j = i + 1; j < d.rows(); ++j) {
      const double fitted = (points.row(i) - points.row(j)).norm();
      misfit += (fitted - d(i, j)) * (fitted - d(i, j));
      total += d(i, j) * d(i, j);
    }
  }
  return total > 0 ? std::sqrt(misfit / total) : 0.0;
}

// Signs each axis so the first stimulus off its middle lies on its positive side: a
// rule that rounding cannot flip, even when the points are symmetric about the origin.
void SignAxes(Eigen::MatrixXd* points) {
  for (Eigen::Index k = 0; k < points->cols(); ++k) {
    auto axis = points->col(k);
    const double middle = 1e-6 * axis.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < axis.size(); ++i) {
      if (std::abs(axis(i)) > middle) {
        if (axis(i) < 0) axis = -axis;
        break;
      }
    }
  }
}

// The upper triangle's pairs (i < j), row by row.
struct Pairs {
  std::vector<Eigen::Index> i, j;
  explicit Pairs(Eigen::Index n) {
    for (Eigen::Index a = 0; a < n; ++a) {
      for (Eigen::Index b = a + 1; b < n; ++b) {
        i.push_back(a);
        j.push_back(b);
      }
    }
  }
  std::size_t size() const { return i.size(); }
};

Eigen::VectorXd PairDistances(const Eigen::MatrixXd& points, const Pairs& pairs) {
  Eigen::VectorXd d(static_cast<Eigen::Index>(pairs.size()));
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    d(static_cast<Eigen::Index>(p)) = (points.row(pairs.i[p]) - points.row(pairs.j[p])).norm();
  }
  return d;
}

// The nondecreasing sequence nearest `y` in least squares (pool adjacent violators).
std::vector<double> MonotoneFit(const std::vector<double>& y) {
  std::vector<double> mean;
  std::vector<std::size_t> count;
  for (double v : y) {
    mean.push_back(v);
    count.push_back(1);
    while (mean.size() > 1 && mean[mean.size() - 2] > mean.back()) {
      const std::size_t a = mean.size() - 2;
      const double total =
          mean[a] * static_cast<double>(count[a]) + mean.back() * static_cast<double>(count.back());
      count[a] += count.back();
      mean[a] = total / static_cast<double>(count[a]);
      mean.pop_back();
      count.pop_back();
    }
  }
  std::vector<double> fitted;
  fitted.reserve(y.size());
  for (std::size_t b = 0; b < mean.size(); ++b) fitted.insert(fitted.end(), count[b], mean[b]);
  return fitted;
}

// Disparities: the monotone function of the dissimilarities (in `order`, with `tie_end`
// marking where each run of equal ones ends) nearest the distances. Within a run of ties
// the pairs are taken by distance, so ties may part (Kruskal's primary approach).
Eigen::VectorXd Disparities(const Eigen::VectorXd& distance, std::vector<std::size_t> order,
                            const std::vector<std::size_t>& tie_end) {
  for (std::size_t start = 0; start < order.size();) {
    const std::size_t end = tie_end[start];
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(start),
              order.begin() + static_cast<std::ptrdiff_t>(end), [&](std::size_t a, std::size_t b) {
                return distance(static_cast<Eigen::Index>(a)) <
                       distance(static_cast<Eigen::Index>(b));
              });
    start = end;
  }
  std::vector<double> sorted;
  sorted.reserve(order.size());
  for (std::size_t p : order) sorted.push_back(distance(static_cast<Eigen::Index>(p)));
  const std::vector<double> fitted = MonotoneFit(sorted);
  Eigen::VectorXd disparity(distance.size());
  for (std::size_t r = 0; r < order.size(); ++r)
    disparity(static_cast<Eigen::Index>(order[r])) = fitted[r];
  return disparity;
}

}  // namespace

PerceptualSpace ComputePerceptualSpace(const Eigen::MatrixXd& dissimilarity, int dimensions) {
  CheckDissimilarity(dissimilarity, dimensions);
  const Eigen::Index n = dissimilarity.rows();
  // symmetrised so rounding in the caller's average cannot tilt the eigenvectors, and
  // divided by the largest so squaring neither overflows nor underflows at any scale
  const double unit = dissimilarity.maxCoeff() > 0 ? dissimilarity.maxCoeff() : 1.0;
  const Eigen::MatrixXd d = 0.5 * (dissimilarity + dissimilarity.transpose()) / unit;
  const Eigen::MatrixXd squared = d.cwiseProduct(d);
  const Eigen::MatrixXd centring = Eigen::MatrixXd::Identity(n, n) -
                                   Eigen::MatrixXd::Constant(n, n, 1.0 / static_cast<double>(n));
  const Eigen::MatrixXd b = -0.5 * centring * squared * centring;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(b);
  if (solver.info() != Eigen::Success) {
    throw std::invalid_argument("perceptual space: the eigen-decomposition did not converge");
  }
  // Eigen sorts ascending: read from the end for the largest first
  PerceptualSpace space;
  space.points.setZero(n, dimensions);
  double all = 0, kept = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double value = solver.eigenvalues()(n - 1 - k);
    space.eigenvalues.push_back(value);
    all += std::abs(value);
    if (k < dimensions) kept += std::max(value, 0.0);
  }
  for (int k = 0; k < dimensions; ++k) {
    const double value = space.eigenvalues[static_cast<std::size_t>(k)];
    // a non-Euclidean or flat direction, or one of rounding only: no spread along it
    if (value <= 1e-12 * space.eigenvalues.front()) continue;
    space.points.col(k) = std::sqrt(value) * solver.eigenvectors().col(n - 1 - k);
  }
  SignAxes(&space.points);
  space.explained = all > 0 ? kept / all : 0.0;
  space.stress = StressOne(space.points, d);  // a ratio: the same in either unit
  space.points *= unit;
  const double largest = space.eigenvalues.front();
  if (largest > 0) {
    for (double& value : space.eigenvalues) value /= largest;
  }
  return space;
}

PerceptualSpace ComputeOrdinalPerceptualSpace(const Eigen::MatrixXd& dissimilarity, int dimensions,
                                              const OrdinalScalingOptions& options) {
  if (options.max_iterations < 1 || !(options.tolerance >= 0) ||
      !std::isfinite(options.tolerance) || !(options.exact_stress >= 0) ||
      !std::isfinite(options.exact_stress)) {
    throw std::invalid_argument(
        "ordinal perceptual space: give at least 1 iteration and a finite tolerance and exact "
        "stress >= 0");
  }
  // the classical space: the start, and the data's scree (checks the input too)
  PerceptualSpace space = ComputePerceptualSpace(dissimilarity, dimensions);
  const Eigen::Index n = dissimilarity.rows();
  const Pairs pairs(n);
  const double unit = dissimilarity.maxCoeff() > 0 ? dissimilarity.maxCoeff() : 1.0;
  Eigen::VectorXd delta(static_cast<Eigen::Index>(pairs.size()));
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const Eigen::Index a = pairs.i[p], b = pairs.j[p];
    delta(static_cast<Eigen::Index>(p)) = 0.5 * (dissimilarity(a, b) + dissimilarity(b, a)) / unit;
  }
  Eigen::MatrixXd x = space.points / unit;
  Eigen::VectorXd distance = PairDistances(x, pairs);
  if (!(distance.squaredNorm() > 0)) return space;  // all alike: every point at the origin

  // the pairs by dissimilarity, and where each run of equal ones (to rounding) ends
  std::vector<std::size_t> order(pairs.size());
  for (std::size_t p = 0; p < order.size(); ++p) order[p] = p;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return delta(static_cast<Eigen::Index>(a)) < delta(static_cast<Eigen::Index>(b));
  });
  std::vector<std::size_t> tie_end(order.size());
  for (std::size_t start = 0; start < order.size();) {
    std::size_t end = start + 1;
    while (end < order.size() && delta(static_cast<Eigen::Index>(order[end])) -
                                         delta(static_cast<Eigen::Index>(order[start])) <=
                                     1e-12) {
      ++end;
    }
    for (std::size_t r = start; r < end; ++r) tie_end[r] = end;
    start = end;
  }

  // SMACOF: the disparities fitted to the distances, scaled to a fixed sum of squares
  // (else the points would shrink towards a zero stress), then a Guttman transform
  const double target = static_cast<double>(pairs.size());
  double stress = std::numeric_limits<double>::infinity();
  space.converged = false;
  for (int round = 1; round <= options.max_iterations; ++round) {
    Eigen::VectorXd disparity = Disparities(distance, order, tie_end);
    disparity *= std::sqrt(target / disparity.squaredNorm());
    const double now = (disparity - distance).squaredNorm() / target;
    space.iterations = round;
    // `now` is the squared stress-1 of these points against disparities of their spread
    if (now <= options.exact_stress * options.exact_stress ||
        (round > 1 && stress - now <= options.tolerance * stress)) {
      space.converged = true;
      break;
    }
    stress = now;
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const Eigen::Index e = static_cast<Eigen::Index>(p);
      if (distance(e) <= 0) continue;  // coincident points pull on nothing
      const double w = disparity(e) / distance(e);
      b(pairs.i[p], pairs.j[p]) -= w;
      b(pairs.j[p], pairs.i[p]) -= w;
      b(pairs.i[p], pairs.i[p]) += w;
      b(pairs.j[p], pairs.j[p]) += w;
    }
    x = b * x / static_cast<double>(n);
    distance = PairDistances(x, pairs);
  }

  // Kruskal's stress-1 of the final points against their own monotone fit
  const Eigen::VectorXd disparity = Disparities(distance, order, tie_end);
  const double spread = distance.squaredNorm();
  space.stress = spread > 0 ? std::sqrt((distance - disparity).squaredNorm() / spread) : 0.0;
  // the points on their principal directions, largest spread first, signed as the
  // classical axes, and scaled so their distances' root mean square is the data's
  x.rowwise() -= x.colwise().mean();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> principal(x.transpose() * x);
  const Eigen::MatrixXd axes = principal.eigenvectors().rowwise().reverse();
  x = x * axes;
  SignAxes(&x);
  if (spread > 0) x *= std::sqrt(delta.squaredNorm() / spread);
  space.points = x * unit;
  return space;
}

PropertyVector FitPropertyVector(const Eigen::MatrixXd& points, const std::vector<double>& q) {
  const auto n = static_cast<Eigen::Index>(q.size());
  if (n != points.rows() || n < 2) {
    throw std::invalid_argument("property vector: " + std::to_string(q.size()) + " values for " +
                                std::to_string(points.rows()) +
                                " points; give one per point, at least 2");
  }
  const Eigen::Map<const Eigen::VectorXd> values(q.data(), n);
  if (!values.allFinite() || !points.allFinite()) {
    throw std::invalid_argument("property vector: a value or a point is not finite");
  }
  const double norm = values.squaredNorm();
  if (norm == 0)
    throw std::invalid_argument("property vector: every value is 0, so it points nowhere");
  PropertyVector vector;
  vector.direction = points.transpose() * values / norm;  // eq. 3
  vector.length = vector.direction.norm();
  if (vector.length > 0) {
    const Eigen::VectorXd along = points * (vector.direction / vector.length);
    const Eigen::VectorXd a = along.array() - along.mean();
    const Eigen::VectorXd b = values.array() - values.mean();
    const double spread = a.norm() * b.norm();
    vector.correlation = spread > 0 ? a.dot(b) / spread : 0.0;
  }
  return vector;
}

std::vector<double> ScaleToUnitRange(const std::vector<double>& values) {
  if (values.empty()) throw std::invalid_argument("scale to unit range: no values");
  for (double v : values) {
    if (!std::isfinite(v))
      throw std::invalid_argument("scale to unit range: a value is not finite");
  }
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  const double range = *high - *low;
  // a spread within rounding of the values is no variation: scaling it would draw noise
  if (!(range > 1e-12 * std::max(std::abs(*low), std::abs(*high))))
    throw std::invalid_argument("scale to unit range: the values do not vary");
  std::vector<double> scaled;
  scaled.reserve(values.size());
  for (double v : values) scaled.push_back((v - *low) / range - 0.5);
  return scaled;
}

}  // namespace hapticad
