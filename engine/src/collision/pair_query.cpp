// CollideShapes (talus/pair_query.h): checks the arguments, runs the
// narrow-phase dispatch (collide.h) once without a cache, and copies the
// manifold into the public answer.
#include "talus/pair_query.h"

#include <cmath>
#include <cstddef>
#include <string>

#include "collision/collide.h"

namespace talus {
namespace {

// |q| may differ from 1 by this much: a quaternion normalised in double
// precision is within a few ulps; 1e-6 admits one read from float data.
constexpr double kUnitQuaternionTolerance = 1e-6;

Result<bool> CheckTransform(const Transform& xf, const char* name) {
  if (!xf.position.allFinite()) return Error{std::string(name) + ".position: not finite"};
  const Quat& q = xf.rotation;
  if (!q.coeffs().allFinite()) return Error{std::string(name) + ".rotation: not finite"};
  if (std::abs(q.norm() - 1.0) > kUnitQuaternionTolerance)
    return Error{std::string(name) + ".rotation: not a unit quaternion (|q| = " + std::to_string(q.norm()) +
                 ")"};
  return true;
}

}  // namespace

static_assert(kPairQueryMaxPoints == kMaxManifoldPoints, "the public answer holds a whole manifold");
static_assert(static_cast<std::uint32_t>(PairFeatureType::Face) ==
                      static_cast<std::uint32_t>(FeatureType::Face) &&
                  static_cast<std::uint32_t>(PairFeatureType::None) ==
                      static_cast<std::uint32_t>(FeatureType::None),
              "the public feature types are the manifold's");

Result<PairContact> CollideShapes(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                                  const NarrowPhaseSettings& settings) {
  if (Result<bool> ok = CheckTransform(xfA, "xfA"); !ok) return ok.GetError();
  if (Result<bool> ok = CheckTransform(xfB, "xfB"); !ok) return ok.GetError();
  if (!std::isfinite(settings.speculativeMargin) || settings.speculativeMargin < 0.0)
    return Error{"settings.speculativeMargin: must be finite and >= 0, got " +
                 std::to_string(settings.speculativeMargin)};
  ContactManifold manifold{};
  PairContact out;
  out.touching = Collide(a, xfA, b, xfB, settings, nullptr, nullptr, &manifold);
  out.separation = -manifold.depth;
  out.normal = manifold.normal;
  out.pointCount = out.touching ? manifold.pointCount : 0;
  for (int i = 0; i < out.pointCount; ++i) {
    const ContactPoint& p = manifold.points[static_cast<std::size_t>(i)];
    out.points[static_cast<std::size_t>(i)] = {
        .position = p.position, .depth = p.depth, .featureId = p.featureId};
  }
  return out;
}

}  // namespace talus
