// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/analysis/perceptual_space.h"

#include <algorithm>
#include <cmath>
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
    Eigen::VectorXd axis = solver.eigenvectors().col(n - 1 - k);
    // the first stimulus off the axis's middle on its positive side: a rule that
    // rounding cannot flip, even when the points are symmetric about the origin
    const double middle = 1e-6 * axis.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < n; ++i) {
      if (std::abs(axis(i)) > middle) {
        if (axis(i) < 0) axis = -axis;
        break;
      }
    }
    space.points.col(k) = std::sqrt(value) * axis;
  }
  space.explained = all > 0 ? kept / all : 0.0;
  space.stress = StressOne(space.points, d);  // a ratio: the same in either unit
  space.points *= unit;
  const double largest = space.eigenvalues.front();
  if (largest > 0) {
    for (double& value : space.eigenvalues) value /= largest;
  }
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
