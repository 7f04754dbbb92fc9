// PolygonNormal: the Newell normal of a polygon, with each cross product
// rounded once instead of four times. Owns nothing; both Quickhull's working
// faces (geometry/quickhull_mesh.cpp) and Hull::FromPolygons use it, so the
// builder decides with exactly the planes the validation checks.
//
// Why: a thin face (a long sliver triangle, or the long narrow
// parallelogram that an edge of A and a nearly parallel edge of B make in a
// Minkowski difference A - B) has a normal that plain double arithmetic gets
// wrong by about eps * length / width radians: every component of
// (a - c) x (b - c) is a difference of two products of size length^2 that
// cancel to length * width. The plane then misses the face's own vertices by
// several times the hull tolerance although the points are coplanar to a
// hundredth of it (seen on 14 of 2000 validation pairs). Evaluating each
// component a*d - b*c with Kahan's fused multiply-add algorithm (error
// within 2 ulps of the result; Jeannerod, Louvet and Muller, "Further
// analysis of Kahan's algorithm for the accurate computation of 2x2
// determinants", Math. Comp. 2013) leaves only the rounding of the
// differences v - origin, which is a perturbation of the vertices by about
// eps * |v - origin|: the plane then fits the given vertices to that, far
// below the tolerance. std::fma is correctly rounded on every platform, so
// the result is bit-identical wherever it runs.
#pragma once

#include <cmath>

#include "talus/math.h"

namespace talus {

/// a * d - b * c with one final rounding error of at most about 2 ulps
/// (Kahan's algorithm with fused multiply-add).
inline double DifferenceOfProducts(double a, double d, double b, double c) {
  const double bc = b * c;
  const double error = std::fma(-b, c, bc);  // exact: bc - b * c
  const double ad = std::fma(a, d, -bc);
  return ad + error;
}

/// Cross product u x v, each component accurate to about 2 ulps.
inline Vec3 AccurateCross(const Vec3& u, const Vec3& v) {
  return {DifferenceOfProducts(u.y(), v.z(), u.z(), v.y()), DifferenceOfProducts(u.z(), v.x(), u.x(), v.z()),
          DifferenceOfProducts(u.x(), v.y(), u.y(), v.x())};
}

/// The length of `v` without overflow or underflow in the squares: the
/// components of a cross product of coordinate differences are products of
/// two lengths, and their squares (four lengths) leave the double range for
/// lengths beyond about 1e77 m or below 1e-77 m, although the result fits.
inline double ScaledNorm(const Vec3& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0.0) || !std::isfinite(largest)) return largest;
  return largest * (v / largest).norm();
}

/// Newell's normal of the closed loop of `count` points `pointAt(0..count-1)`
/// (counter-clockwise seen from the side it points to), taken about `origin`
/// (pass the loop's centroid: small differences keep their precision far
/// from the world origin). Not normalised: its length is twice the area.
template <class PointAt>
Vec3 PolygonNormal(int count, const PointAt& pointAt, const Vec3& origin) {
  Vec3 normal = Vec3::Zero();
  Vec3 previous = pointAt(count - 1) - origin;
  for (int i = 0; i < count; ++i) {
    const Vec3 current = pointAt(i) - origin;
    normal += AccurateCross(previous, current);
    previous = current;
  }
  return normal;
}

}  // namespace talus
