// SPDX-License-Identifier: GPL-3.0-or-later
// The perceptual space of a similarity study (seed 001 §IV, Fig. 7).
//
// Participants rate how alike each pair of n stimuli (virtual textures) feels; the
// ratings, inverted, give an n x n dissimilarity matrix. ComputePerceptualSpace places
// the stimuli as points in a space of `dimensions` dimensions whose distances follow
// the dissimilarities: classical (Torgerson) multidimensional scaling, the metric MDS
// that needs no starting guess and gives the same answer every run. Then
// FitPropertyVector draws a physical parameter through that space by the paper's eq. 3:
// the vector p minimising sum_i |x_i - q_i p|^2, i.e. p = sum q_i x_i / sum q_i^2,
// where q_i is stimulus i's parameter scaled to -0.5..0.5 (ScaleToUnitRange). Its
// direction is the parameter's trend through the space, its length how strongly the
// parameter shapes what was felt. As in the paper, q is not re-centred: the points are
// centred, so a q whose mean is not 0 leaves p's direction as it is but shortens it
// (sum q_i^2 grows with the mean's square); `correlation`, which is centred, does not
// depend on it.
//
// Units: dissimilarities in any unit (the points come out in the same unit). The
// space's axes mean nothing on their own: the points are centred on the origin and
// axis k is the k-th principal direction (largest spread first), signed so that the
// first stimulus off its middle lies on its positive side (the same input gives the
// same picture; two axes of equal spread have no preferred directions within their
// plane).
//
// Ratings on a scale say which pairs feel more alike, not by how much: ordinal (Kruskal's
// nonmetric) scaling, ComputeOrdinalPerceptualSpace, keeps only that order. It starts from
// the classical space and moves the points (SMACOF: Guttman transforms, de Leeuw) while
// their distances follow a monotone function of the dissimilarities fitted each round
// (isotonic regression; tied dissimilarities may part, Kruskal's primary approach), so a
// scale the participants used unevenly bends nothing. With few stimuli per dimension
// (fewer than about four per axis) such a fit can collapse towards clusters whatever the
// data say: compare it with the classical space.
//
// Throws std::invalid_argument, saying what is wrong, on input that cannot be scaled.
// Allocates; not for the servo thread.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace hapticad {

struct PerceptualSpace {
  Eigen::MatrixXd points;           // n x dimensions, row i is stimulus i; centred
  std::vector<double> eigenvalues;  // of the double-centred squared dissimilarities, all n, largest
                                    // first, over the largest (1 first; all 0 when every
                                    // dissimilarity is 0): a scree of how many axes the data need
  double explained = 0;             // the axes' kept eigenvalues over the sum of all eigenvalues'
                                    // magnitudes, 0..1 (Mardia): below 1 for axes left out and for
                                    // dissimilarities no space of any dimension holds
  double stress = 0;                // sqrt(sum (distance - dissimilarity)^2 / sum dissimilarity^2)
                                    // over the pairs: how far the points' distances stray from
                                    // the dissimilarities, relatively (0: exact; 0 when all are 0).
                                    // Ordinal: Kruskal's stress-1, against the monotone fit
                                    // instead of the dissimilarities, over sum distance^2
  int iterations = 0;               // ordinal: the rounds it took (0: classical)
  bool converged = true;            // ordinal: false when it stopped at the round limit
};

// Preconditions: `dissimilarity` is square, n >= 3, finite, >= 0, symmetric (within
// 1e-9 of its largest entry) with a zero diagonal; 1 <= dimensions < n. A dissimilarity
// that is not Euclidean gives negative eigenvalues; the axes kept take the largest
// (a negative one among them gives a zero axis), and `explained` and `stress` say how
// well the space holds the data.
PerceptualSpace ComputePerceptualSpace(const Eigen::MatrixXd& dissimilarity, int dimensions);

struct OrdinalScalingOptions {
  int max_iterations = 2000;   // >= 1
  double tolerance = 1e-12;    // >= 0: stops once a round lowers the stress by less than this
                               // share of it
  double exact_stress = 1e-5;  // >= 0: stops once stress-1 is below it, an exact fit. Ratings
                               // with ties often have one, and SMACOF only creeps towards it:
                               // 2000 rounds ended at 8e-7 still falling, "not settled"
};

// Ordinal (nonmetric) scaling of the same input, with the same preconditions, axes and
// signs (the points turned to their principal directions, scaled so their distances'
// root mean square is the dissimilarities'). `eigenvalues` and `explained` are the
// classical start's: a scree of the data. Also throws std::invalid_argument for options
// out of range.
PerceptualSpace ComputeOrdinalPerceptualSpace(const Eigen::MatrixXd& dissimilarity, int dimensions,
                                              const OrdinalScalingOptions& options = {});

struct PropertyVector {
  Eigen::VectorXd direction;  // eq. 3's p, in the space's units per unit of q
  double length = 0;          // |p|
  double correlation = 0;     // Pearson r between q_i and x_i . p / |p| (0 when p = 0): how
                              // well the points line up along the vector
};

// Eq. 3. Preconditions: q.size() == points.rows() >= 2, q finite and not all zero.
PropertyVector FitPropertyVector(const Eigen::MatrixXd& points, const std::vector<double>& q);

// The paper's scaling of a parameter to q: the lowest value to -0.5, the highest to
// +0.5, linearly between (three levels give -0.5, 0, +0.5). Precondition: finite values,
// not all equal (a parameter that does not vary draws no vector).
std::vector<double> ScaleToUnitRange(const std::vector<double>& values);

}  // namespace hapticad
