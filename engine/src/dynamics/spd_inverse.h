// SpdInverse: the inverse of a small symmetric positive definite matrix,
// for the per-pair blocks the contact solver factorises every step (the
// normal block, dynamics/normal_block.h; the coupled block's Schur
// complement, dynamics/coupled_block_solver.cpp).
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace talus {

// The inverse of a symmetric positive definite M by its Cholesky factor
// M = L L^T: M^-1 = L^-T L^-1, with L^-1 by forward substitution
// (backward stable; Eigen's cofactor inverse lost three digits more on the
// ill-conditioned normal blocks of tests/dynamics/normal_block_test.cpp).
// Written out for the fixed sizes: Eigen's LLT solve against a matrix
// right-hand side takes its general blocked path, which cost more than the
// factorisation. Non-finite when M is not positive definite.
template <int N>
inline Eigen::Matrix<double, N, N> SpdInverse(const Eigen::Matrix<double, N, N>& m) {
  double l[N][N] = {};
  for (int j = 0; j < N; ++j) {
    double pivot = m(j, j);
    for (int k = 0; k < j; ++k) pivot -= l[j][k] * l[j][k];
    if (!(pivot > 0.0))
      return Eigen::Matrix<double, N, N>::Constant(std::numeric_limits<double>::quiet_NaN());
    l[j][j] = std::sqrt(pivot);
    for (int i = j + 1; i < N; ++i) {
      double sum = m(i, j);
      for (int k = 0; k < j; ++k) sum -= l[i][k] * l[j][k];
      l[i][j] = sum / l[j][j];
    }
  }
  // L^-1, lower triangular, column by column.
  double inverse[N][N] = {};
  for (int j = 0; j < N; ++j) {
    inverse[j][j] = 1.0 / l[j][j];
    for (int i = j + 1; i < N; ++i) {
      double sum = 0.0;
      for (int k = j; k < i; ++k) sum -= l[i][k] * inverse[k][j];
      inverse[i][j] = sum / l[i][i];
    }
  }
  Eigen::Matrix<double, N, N> result;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (int k = i; k < N; ++k) sum += inverse[k][i] * inverse[k][j];
      result(i, j) = sum;
      result(j, i) = sum;
    }
  }
  return result;
}

}  // namespace talus
