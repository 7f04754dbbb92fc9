// Exact solve of a pair's normal-row LCP (see dynamics/block_lcp.h).
//
// Plain arrays of at most 4: the systems are small, and GCC 12's bounds
// checker misreads Eigen's dynamic-size views of fixed 4-vectors.
#include "dynamics/block_lcp.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus {
namespace {

// The rank cut PrepareBlock's pseudo-inverse uses: a direction whose K image
// is below this fraction of K's scale carries no load.
constexpr double kRankCut = 1e-9;

// Solves K_SS x_S = b_S for the points in `mask` by LDL^T (K_SS symmetric);
// other entries of x are 0. False when a pivot falls to 1e-12 of the
// largest diagonal or below: coincident or collinear points carry no
// independent load.
bool SolveSubset(const Eigen::Matrix4d& k, const double (&b)[4], int count, int mask, double (&x)[4]) {
  int index[4] = {0, 0, 0, 0};
  int size = 0;
  for (int i = 0; i < count; ++i) {
    if (mask & (1 << i)) index[size++] = i;
  }
  for (double& value : x) value = 0.0;
  if (size == 0) return true;
  double l[4][4] = {};
  double d[4] = {};
  double largestDiagonal = 0.0;
  for (int r = 0; r < size; ++r) largestDiagonal = std::max(largestDiagonal, std::abs(k(index[r], index[r])));
  for (int r = 0; r < size; ++r) {
    for (int c = 0; c <= r; ++c) {
      double sum = k(index[r], index[c]);
      for (int m = 0; m < c; ++m) sum -= l[r][m] * l[c][m] * d[m];
      if (c == r) {
        if (!(sum > 1e-12 * largestDiagonal)) return false;
        d[r] = sum;
        l[r][r] = 1.0;
      } else {
        l[r][c] = sum / d[c];
      }
    }
  }
  double y[4] = {};
  for (int r = 0; r < size; ++r) {
    double sum = b[index[r]];
    for (int m = 0; m < r; ++m) sum -= l[r][m] * y[m];
    y[r] = sum;
  }
  for (int r = size - 1; r >= 0; --r) {
    double sum = y[r] / d[r];
    for (int m = r + 1; m < size; ++m) sum -= l[m][r] * x[index[m]];
    x[index[r]] = sum;
  }
  return true;
}

double Dot(const double (&a)[4], const double (&b)[4]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

// Four points of a plane: K has the null vector u of their affine
// dependency (sum u_i = 0, sum u_i r_i = 0). Finds u with u_3 = 1 from the
// first three rows; false when K is not singular to kRankCut.
bool NullVector(const Eigen::Matrix4d& k, double scaleK, double (&u)[4]) {
  const double minusLast[4] = {-k(0, 3), -k(1, 3), -k(2, 3), 0.0};
  if (!SolveSubset(k, minusLast, 4, 0b0111, u)) return false;
  u[3] = 1.0;
  double largestU = 0.0;
  for (const double value : u) largestU = std::max(largestU, std::abs(value));
  for (int i = 0; i < 4; ++i) {
    double image = 0.0;
    for (int j = 0; j < 4; ++j) image += k(i, j) * u[j];
    if (!(std::abs(image) <= kRankCut * scaleK * largestU)) return false;
  }
  return true;
}

// Every point pushing, K singular: the answers are x0 + t u for t in the
// interval where all entries are >= 0; takes the least-norm one. False
// when the interval is empty.
bool SolveAllPushing(const double (&x0)[4], const double (&u)[4], double (&x)[4]) {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    if (u[i] > 0.0) {
      lo = std::max(lo, -x0[i] / u[i]);
    } else if (u[i] < 0.0) {
      hi = std::min(hi, -x0[i] / u[i]);
    } else if (x0[i] < 0.0) {
      return false;
    }
  }
  if (!(lo <= hi)) return false;
  const double t = std::clamp(-Dot(x0, u) / Dot(u, u), lo, hi);
  for (int i = 0; i < 4; ++i) x[i] = std::max(x0[i] + t * u[i], 0.0);
  return true;
}

}  // namespace

bool SolveBlockLcp(const Eigen::Matrix4d& k, const Eigen::Vector4d& bIn, int count, Eigen::Vector4d& x) {
  double b[4] = {0.0, 0.0, 0.0, 0.0};
  double scaleB = 0.0;
  double scaleK = 0.0;
  for (int i = 0; i < count; ++i) {
    b[i] = bIn[i];
    scaleB = std::max(scaleB, std::abs(b[i]));
    for (int j = 0; j < count; ++j) scaleK = std::max(scaleK, std::abs(k(i, j)));
  }
  double answer[4] = {0.0, 0.0, 0.0, 0.0};
  const auto accept = [&x, &answer] {
    x = Eigen::Vector4d(answer[0], answer[1], answer[2], answer[3]);
    return true;
  };
  int largestSubset = count;
  double u[4] = {0.0, 0.0, 0.0, 0.0};
  if (count == 4 && NullVector(k, scaleK, u)) {
    // Drop b's component along u, which no impulse can meet (the
    // pseudo-inverse step does the same), so that every subset below
    // solves the same consistent problem and the answers join up.
    const double along = Dot(b, u) / Dot(u, u);
    for (int i = 0; i < 4; ++i) b[i] -= along * u[i];
    double particular[4] = {0.0, 0.0, 0.0, 0.0};
    if (SolveSubset(k, b, 4, 0b0111, particular) && SolveAllPushing(particular, u, answer)) return accept();
    largestSubset = 3;
  }
  // K positive definite on every subset left: the LCP's answer is unique,
  // so the first subset that qualifies is it. Largest subsets first, then
  // by mask: a fixed order.
  for (int size = largestSubset; size >= 0; --size) {
    for (int mask = 0; mask < (1 << count); ++mask) {
      if (__builtin_popcount(static_cast<unsigned>(mask)) != size) continue;
      if (!SolveSubset(k, b, count, mask, answer)) continue;
      bool pushes = true;
      double largestX = 0.0;
      for (int i = 0; i < count; ++i) {
        pushes = pushes && answer[i] >= 0.0;
        largestX = std::max(largestX, std::abs(answer[i]));
      }
      if (!pushes) continue;
      const double tolerance = 1e-12 * std::max(scaleB, scaleK * largestX);
      bool separates = true;
      for (int i = 0; i < count && separates; ++i) {
        if (mask & (1 << i)) continue;
        double w = -b[i];
        for (int j = 0; j < count; ++j) w += k(i, j) * answer[j];
        separates = w >= -tolerance;
      }
      if (separates) return accept();
    }
  }
  return false;
}

}  // namespace talus
