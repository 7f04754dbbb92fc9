// The normal block's pseudo-inverse (dynamics/normal_block.h). Oracles it
// does not share: an analytic split (a cube on four symmetric corners), the
// four Moore-Penrose conditions, and Eigen's SVD, a different algorithm,
// over many random pairs; then the rank decisions must be the eigen
// path's (a mode it drops is never kept).
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "dynamics/normal_block.h"

namespace talus {
namespace normal_block_test {

// One pair's normal rows: points, the normal, two bodies' centres,
// inverse masses and inverse inertias, and what NormalBlock builds of them.
struct PairBlock {
  Eigen::Matrix4d k;
  NormalArms arms{};
  int count = 0;
};

PairBlock MakeBlock(const Vec3* points, int count, const Vec3& normal, const Vec3& centreA,
                    const Vec3& centreB, double invMassA, double invMassB, const Mat3& invInertiaA,
                    const Mat3& invInertiaB) {
  RowJacobian rows[4];
  PairBlock block;
  block.count = count;
  for (int i = 0; i < count; ++i) {
    rows[i] = MakeRowJacobian(normal, points[i] - centreA, points[i] - centreB, invInertiaA, invInertiaB);
    block.arms[static_cast<std::size_t>(i)] = rows[i].angularA;
  }
  block.k = NormalBlock(count, invMassA, invMassB, [&rows](int i) -> const RowJacobian& { return rows[i]; });
  return block;
}

// A random symmetric positive definite inverse inertia, eigenvalues in
// [lo, hi] 1/(kg m^2), in a random frame.
Mat3 RandomInverseInertia(std::mt19937& random, double lo, double hi) {
  std::uniform_real_distribution<double> value(lo, hi);
  std::normal_distribution<double> gauss;
  const Eigen::Quaterniond turn =
      Eigen::Quaterniond(gauss(random), gauss(random), gauss(random), gauss(random)).normalized();
  const Mat3 r = turn.toRotationMatrix();
  return r * Vec3(value(random), value(random), value(random)).asDiagonal() * r.transpose();
}

Vec3 RandomUnit(std::mt19937& random) {
  std::normal_distribution<double> gauss;
  return Vec3(gauss(random), gauss(random), gauss(random)).normalized();
}

// A random pair: `count` points scattered over a 1 m patch of a plane
// (each up to 1 cm off it, as clipped manifold points can be), a body on
// each side, B static in one case of three.
PairBlock RandomPair(std::mt19937& random, int count) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vec3 n = RandomUnit(random);
  const Vec3 t1 = n.unitOrthogonal();
  const Vec3 t2 = n.cross(t1);
  Vec3 points[4];
  for (int i = 0; i < count; ++i)
    points[i] = 0.5 * unit(random) * t1 + 0.5 * unit(random) * t2 + 0.01 * unit(random) * n;
  const Vec3 centreA = 0.5 * n + 0.3 * Vec3(unit(random), unit(random), unit(random));
  const Vec3 centreB = -0.5 * n + 0.3 * Vec3(unit(random), unit(random), unit(random));
  const bool staticB = random() % 3 == 0;
  std::uniform_real_distribution<double> invMass(1e-4, 10.0);
  return MakeBlock(points, count, n, centreA, centreB, invMass(random), staticB ? 0.0 : invMass(random),
                   RandomInverseInertia(random, 1e-3, 50.0),
                   staticB ? Mat3::Zero() : RandomInverseInertia(random, 1e-3, 50.0));
}

// The pseudo-inverse by SVD over the pair's points, singular values below
// 1e-9 of the largest counted as zero (for the well-separated spectra of
// the random pairs the cut agrees with the eigen path's).
Eigen::Matrix4d SvdPseudoInverse(const Eigen::Matrix4d& k, int count) {
  const Eigen::MatrixXd block = k.topLeftCorner(count, count);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(block, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::VectorXd inverse = svd.singularValues();
  const double largest = inverse.maxCoeff();
  for (Eigen::Index i = 0; i < inverse.size(); ++i)
    inverse[i] = inverse[i] > 1e-9 * largest ? 1.0 / inverse[i] : 0.0;
  Eigen::Matrix4d result = Eigen::Matrix4d::Zero();
  result.topLeftCorner(count, count) = svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();
  return result;
}

// The four Moore-Penrose conditions on the pair's points, relative to the
// matrices' size: K X K = K, X K X = X, K X and X K symmetric.
void ExpectPenrose(const Eigen::Matrix4d& k, const Eigen::Matrix4d& x, int count, double tolerance) {
  const Eigen::MatrixXd kc = k.topLeftCorner(count, count);
  const Eigen::MatrixXd xc = x.topLeftCorner(count, count);
  const double kScale = kc.norm();
  const double xScale = xc.norm();
  EXPECT_LE((kc * xc * kc - kc).norm(), tolerance * kScale);
  EXPECT_LE((xc * kc * xc - xc).norm(), tolerance * xScale);
  EXPECT_LE((kc * xc - (kc * xc).transpose()).norm(), tolerance * kScale * xScale);
  EXPECT_LE((xc * kc - (xc * kc).transpose()).norm(), tolerance * kScale * xScale);
}

// Analytic: a cube of mass m on four corners symmetric about the point
// below its centre. The arms sum to zero, so K 1 = (4 / m) 1 and the
// least-norm answer to a uniform velocity error r is r m / 4 at every
// corner (any other split also solves K x = r, but carries a moment).
TEST(NormalBlockTest, SymmetricCornersShareAUniformLoadEqually) {
  const double mass = 62.5;
  const double side = 0.5;
  const double inertia = mass * side * side / 6.0;
  const Vec3 n = Vec3::UnitY();
  const Vec3 centre(0.0, side / 2, 0.0);
  const Vec3 corners[4] = {{-0.25, 0, -0.25}, {0.25, 0, -0.25}, {0.25, 0, 0.25}, {-0.25, 0, 0.25}};
  const PairBlock block = MakeBlock(corners, 4, n, centre, Vec3::Zero(), 1.0 / mass, 0.0,
                                    Mat3::Identity() / inertia, Mat3::Zero());
  const Eigen::Matrix4d x = BlockPseudoInverse(block.k, 4, block.arms);
  const double r = 0.3;  // m/s
  const Eigen::Vector4d split = x * Eigen::Vector4d::Constant(r);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(split[i], r * mass / 4.0, 1e-12 * r * mass) << "corner " << i;
  ExpectPenrose(block.k, x, 4, 1e-12);
}

// Property, 3,000 random pairs of 2, 3 and 4 points: the result is the
// Moore-Penrose inverse, agrees with the SVD and with the eigen path.
TEST(NormalBlockTest, RandomPairsGiveTheMoorePenroseInverse) {
  std::mt19937 random(20261202);
  for (int trial = 0; trial < 3000; ++trial) {
    const int count = 2 + trial % 3;
    const PairBlock block = RandomPair(random, count);
    const Eigen::Matrix4d x = BlockPseudoInverse(block.k, count, block.arms);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << ", " << count << " points");
    ExpectPenrose(block.k, x, count, 1e-9);
    const double scale = x.norm();
    EXPECT_LE((x - SvdPseudoInverse(block.k, count)).norm(), 1e-8 * scale);
    EXPECT_LE((x - EigenBlockPseudoInverse(block.k, count)).norm(), 1e-8 * scale);
    // Nothing outside the pair's points.
    for (int i = count; i < 4; ++i) EXPECT_EQ(x.row(i).norm() + x.col(i).norm(), 0.0);
  }
}

// Four points on a line (after projection along n): K has rank 2, no
// unique null vector, and the answer is the eigen path's.
TEST(NormalBlockTest, CollinearPointsTakeTheEigenPath) {
  const Vec3 n = Vec3::UnitY();
  const Vec3 points[4] = {{-0.3, 0, 0}, {-0.1, 0, 0}, {0.2, 0, 0}, {0.3, 0.001, 0}};
  const PairBlock block = MakeBlock(points, 4, n, Vec3(0.05, 0.4, 0.1), Vec3::Zero(), 0.5, 0.0,
                                    Mat3::Identity() * 3.0, Mat3::Zero());
  const Eigen::Matrix4d x = BlockPseudoInverse(block.k, 4, block.arms);
  const Eigen::Matrix4d reference = EigenBlockPseudoInverse(block.k, 4);
  EXPECT_TRUE(x == reference);
  ExpectPenrose(block.k, x, 4, 1e-9);
}

// The trap of the identity padding: below four points the eigen path's cut
// is 1e-9 max(lambda_max, 1) per kg, absolute for heavy bodies. Two
// corners 2 mm apart under an 8 t cube have a twisting mode near 1e-9
// that the eigen path drops; the closed form must drop it too.
TEST(NormalBlockTest, HeavyBodyKeepsTheEigenPathsRankCut) {
  const double mass = 8000.0;
  const double inertia = mass * 4.0 / 6.0;  // a 2 m cube
  const Vec3 n = Vec3::UnitY();
  const Vec3 points[2] = {{0.999, 0, 1.0}, {1.001, 0, 1.0}};
  const PairBlock block = MakeBlock(points, 2, n, Vec3(0, 1, 0), Vec3::Zero(), 1.0 / mass, 0.0,
                                    Mat3::Identity() / inertia, Mat3::Zero());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spectrum(block.k.topLeftCorner<2, 2>());
  ASSERT_LT(spectrum.eigenvalues()[0], 1e-9);  // the scene is the trap
  EXPECT_TRUE(BlockPseudoInverse(block.k, 2, block.arms) == EigenBlockPseudoInverse(block.k, 2));
}

// Arms that do not belong to K (a caller's mistake) cannot give a wrong
// inverse: the null vector is checked against K and the eigen path taken.
TEST(NormalBlockTest, ArmsThatAreNotKsFallBack) {
  std::mt19937 random(5);
  const PairBlock block = RandomPair(random, 4);
  const PairBlock other = RandomPair(random, 4);
  const Eigen::Matrix4d x = BlockPseudoInverse(block.k, 4, other.arms);
  EXPECT_TRUE(x == EigenBlockPseudoInverse(block.k, 4));
}

}  // namespace normal_block_test
}  // namespace talus
