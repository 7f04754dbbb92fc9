// The closed-form pseudo-inverse of a pair's normal block against the eigen
// decomposition oracle, on many random contact geometries and on the
// degenerate ones that must fall back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "dynamics/block_inverse.h"

namespace talus {
namespace {

// SplitMix64 (Steele, Lea, Flood 2014) mapped to [0, 1): a fixed stream on
// every platform, unlike the standard distributions.
class Random {
 public:
  explicit Random(std::uint64_t seed) : m_state(seed) {}
  double Uniform() {
    m_state += 0x9e3779b97f4a7c15ull;
    std::uint64_t z = m_state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  double Between(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  Vec3 InBox(double half) { return {Between(-half, half), Between(-half, half), Between(-half, half)}; }

 private:
  std::uint64_t m_state;
};

// A pair's normal block as ContactSolver::Prepare builds it: rows
// [n, rA x n, -n, -rB x n] through the inverse masses and inertias.
struct Block {
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  std::vector<Vec3> arms;  // rA x n
};

Block MakeBlock(const Vec3& n, const std::vector<Vec3>& points, const Vec3& cA, const Vec3& cB,
                double invMassA, double invMassB, const Mat3& invInertiaA, const Mat3& invInertiaB) {
  Block block;
  std::vector<Vec3> ra, rb;
  for (const Vec3& p : points) {
    ra.push_back((p - cA).cross(n));
    rb.push_back((p - cB).cross(n));
  }
  block.arms = ra;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = 0; j < points.size(); ++j) {
      block.k(static_cast<int>(i), static_cast<int>(j)) =
          invMassA + invMassB + ra[i].dot(invInertiaA * ra[j]) + rb[i].dot(invInertiaB * rb[j]);
    }
  }
  return block;
}

Mat3 RandomInverseInertia(Random& random) {
  // R diag R^T with principal values spanning 1:10, like a box of 1:3 sides.
  const Quat q =
      Quat(random.Between(-1, 1), random.Between(-1, 1), random.Between(-1, 1), random.Between(-1, 1))
          .normalized();
  const Mat3 r = q.toRotationMatrix();
  const Vec3 d(random.Between(0.1, 1.0), random.Between(0.1, 1.0), random.Between(0.1, 1.0));
  return r * d.asDiagonal() * r.transpose();
}

double MaxAbs(const Eigen::Matrix4d& m) { return m.cwiseAbs().maxCoeff(); }

// 3,000 random pairs: 2-4 points on the contact plane (a face, an edge, or
// a clipped polygon's corners), random arms, masses (0.5-10 kg or 5-100 t)
// and inertias, one body static in a third of them. The closed form must equal the oracle to 1e-8
// of its largest entry (each is exact up to the condition number it
// accepts, at most ~1e7, times round-off 1.1e-16) and be a pseudo-inverse:
// K X K = K to the same relative tolerance.
TEST(BlockInverse, ClosedFormMatchesTheEigenOracleOnRandomManifolds) {
  Random random(20261122);
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 n = random.InBox(1.0).normalized();
    const Vec3 u = n.cross(Vec3::UnitX()).norm() > 0.1 ? Vec3(n.cross(Vec3::UnitX()).normalized())
                                                       : Vec3(n.cross(Vec3::UnitY()).normalized());
    const Vec3 v = n.cross(u);
    const int count = 2 + trial % 3;
    const Vec3 origin = random.InBox(2.0);
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i) {
      // Points on the plane plus a small depth along n, which J ignores.
      points.push_back(origin + random.Between(-1, 1) * u + random.Between(-1, 1) * v +
                       random.Between(-0.01, 0.01) * n);
    }
    const bool staticB = trial % 3 == 0;
    // Light bodies, and bodies of tonnes (K below the identity padding's 1,
    // where the oracle's cut is absolute).
    const double scale = trial % 2 == 0 ? 1.0 : 1e-4;
    const Block block = MakeBlock(
        n, points, origin + random.InBox(1.0), origin + random.InBox(1.0), scale * random.Between(0.1, 2.0),
        staticB ? 0.0 : scale * random.Between(0.1, 2.0), scale * RandomInverseInertia(random),
        staticB ? Mat3::Zero() : Mat3(scale * RandomInverseInertia(random)));
    const Eigen::Matrix4d fast = BlockPseudoInverse(block.k, n, block.arms);
    const Eigen::Matrix4d oracle = EigenPseudoInverse(block.k, count);
    ASSERT_LE(MaxAbs(fast - oracle), 1e-8 * MaxAbs(oracle))
        << "trial " << trial << ", " << count << " points";
    // K without the identity padding, so K X K = K holds on all 4 x 4.
    Eigen::Matrix4d k = block.k;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        if (r < count && c < count) continue;
        k(r, c) = 0.0;
        ASSERT_EQ(fast(r, c), 0.0) << "trial " << trial;
      }
    }
    // For tonne bodies the oracle's absolute cut may drop a soft mode on
    // purpose, and then X is not K's exact pseudo-inverse; the comparison
    // above covers those.
    if (scale == 1.0) {
      ASSERT_LE(MaxAbs(k * fast * k - k), 1e-8 * MaxAbs(k)) << "trial " << trial;
    }
  }
}

// A cube's face on the ground, the symmetric case the block exists for: a
// downward velocity error shared by four corners gets four equal impulses.
TEST(BlockInverse, SymmetricLoadOfFourCornersSplitsEvenly) {
  const Vec3 n = Vec3::UnitY();
  const std::vector<Vec3> corners = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  const Block block = MakeBlock(n, corners, {0, 1, 0}, {0, -1, 0}, 1.0 / 8.0, 0.0,
                                Mat3::Identity() / (8.0 * 8.0 / 12.0), Mat3::Zero());
  const Eigen::Vector4d impulse = BlockPseudoInverse(block.k, n, block.arms) * Eigen::Vector4d::Constant(1.0);
  // Total impulse m dv = 8 N s for a 1 m/s error, 2 each; round-off only.
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(impulse[i], 2.0, 1e-12) << i;
}

// Two corners 2.5-3 mm apart on an 8 t cube (the pyramid's): K is ~1e-3
// kg^-1 with a near-singular mode of 6-9e-10 (gap^2 / (2 I)). The oracle,
// padded with the identity, cuts at 1e-9 and drops that mode; the closed
// form must drop it too, not invert it into impulses of 1e9 N s (a 0.3 m
// pyramid drift before this case was handled: a test relative to K's own
// largest eigenvalue, 2e-3, accepted it).
TEST(BlockInverse, NearlyCoincidentPointsOnAHeavyBodyDropTheStiffModeLikeTheOracle) {
  const Vec3 n = Vec3::UnitY();
  const double mass = 8000.0;
  const Mat3 invInertia = Mat3::Identity() / (mass * 8.0 / 12.0);
  for (const double gap : {2.5e-3, 3e-3}) {
    const std::vector<Vec3> points = {{1, 0, -1}, {1, 0, -1 + gap}};
    const Block block =
        MakeBlock(n, points, {0, 1, 0}, {0, -1, 0}, 1.0 / mass, 0.0, invInertia, Mat3::Zero());
    const Eigen::Matrix4d fast = BlockPseudoInverse(block.k, n, block.arms);
    const Eigen::Matrix4d oracle = EigenPseudoInverse(block.k, 2);
    // The oracle keeps only the common mode: its 2x2 block has rank one
    // (determinant zero up to round-off on entries of ~500).
    EXPECT_LT(std::abs(oracle(0, 0) * oracle(1, 1) - oracle(0, 1) * oracle(1, 0)),
              1e-9 * oracle(0, 0) * oracle(0, 0))
        << gap;
    EXPECT_LE(MaxAbs(fast - oracle), 1e-8 * MaxAbs(oracle)) << gap;
  }
}

// Collinear points (an edge resting on an edge, four points on one line)
// leave K of rank 2: the affine dependency is not unique, the closed form
// must decline and the result still equal the oracle.
TEST(BlockInverse, CollinearPointsFallBackToTheOracle) {
  const Vec3 n = Vec3::UnitY();
  const std::vector<Vec3> line = {{-1, 0, 0}, {-0.25, 0, 0}, {0.5, 0, 0}, {1, 0, 0}};
  for (const int count : {3, 4}) {
    const std::vector<Vec3> points(line.begin(), line.begin() + count);
    const Block block =
        MakeBlock(n, points, {0.1, 1, 0.2}, {0, -1, 0}, 0.5, 0.0, Mat3::Identity() * 0.3, Mat3::Zero());
    const Eigen::Matrix4d fast = BlockPseudoInverse(block.k, n, block.arms);
    const Eigen::Matrix4d oracle = EigenPseudoInverse(block.k, count);
    EXPECT_LE(MaxAbs(fast - oracle), 1e-12 * MaxAbs(oracle)) << count;
    EXPECT_GT(MaxAbs(oracle), 0.0);
  }
}

}  // namespace
}  // namespace talus
