// Test helpers for hulls built from point clouds: an independent check of
// every documented invariant (not trusting Hull::FromPolygons), the volume,
// and the deterministic point-set generators shared by the builder tests.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "talus/hull.h"

namespace talus::test {

/// Volume of a closed hull by the divergence theorem over its fan
/// triangulation, taken about the first vertex for precision far away.
double HullVolume(const Hull& hull);

/// Checks, with the hull's own tolerance: every point of `points` is behind
/// or within `slack` x tolerance of every face plane; every vertex is one of
/// `points` bit for bit; half-edge links form a closed 2-manifold with
/// V - E + F = 2; faces are planar and convex; adjacent faces are not
/// coplanar.
testing::AssertionResult CheckHull(const Hull& hull, const std::vector<Vec3>& points, double slack = 1.0);

/// Deterministic generators (seeded; same seed, same points).
std::vector<Vec3> BallPoints(std::uint64_t seed, int count, const Vec3& center = Vec3::Zero(),
                             double radius = 1.0);
std::vector<Vec3> SpherePoints(std::uint64_t seed, int count, double radius = 1.0);
/// Cube [-1, 1]^3 corners plus `extra` points on its faces, edges and grid.
std::vector<Vec3> CubeWithSurfacePoints(std::uint64_t seed, int extra);

/// Reads "x y z" lines; blank lines and lines starting with '#' are skipped.
std::vector<Vec3> ReadXyz(const std::string& path);

}  // namespace talus::test
