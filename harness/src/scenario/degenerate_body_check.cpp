// Degenerate bodies (see degenerate_body_check.h). The hull's volume and
// inertia come from the engine's public hull builder and exact mass
// properties; the checks need only their order of magnitude, far coarser
// than any difference between that and the peers' own integration.
#include "scenario/degenerate_body_check.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>
#include <variant>

#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/hull_builder.h"
#include "talus/mass_properties.h"

namespace talus::harness {
namespace {

// Volume (m^3) and inertia about the centroid at density 1 (m^5).
struct UnitSolid {
  double volume = 0.0;
  Mat3 inertia = Mat3::Zero();
};

double ScaleSafeNorm(const Vec3& v) {
  const double scale = v.cwiseAbs().maxCoeff();
  return scale > 0.0 ? scale * (v / scale).norm() : 0.0;
}

std::string Named(const BodySpec& body, const std::string& problem) {
  return Concat({"body ", Quoted(body.name), ": ", problem});
}

// The hull's solid, or the reason it has none worth the name.
std::variant<UnitSolid, BodyProblem> HullSolid(const BodySpec& body, const HullShape& hull) {
  Vec3 low = hull.points.front();
  Vec3 high = low;
  for (const Vec3& p : hull.points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double halfSpan = 0.5 * (high - low).maxCoeff();
  if (halfSpan < kMinLength) {
    return BodyProblem{"/shape/points",
                       Named(body, Concat({"the hull's points lie within ", FormatNumber(2.0 * halfSpan),
                                           " m of each other; its largest half extent must be at least ",
                                           FormatNumber(kMinLength), " m, as a box's"}))};
  }
  auto built = BuildHull(hull.points);
  if (!built) {
    return BodyProblem{"/shape/points",
                       Named(body, Concat({"the hull has no volume: ", built.GetError().message}))};
  }
  auto mass = ComputeMassProperties(built.Value(), 1.0);
  if (!mass) return BodyProblem{"/shape/points", Named(body, Concat({"hull: ", mass.GetError().message}))};
  const double extent = ScaleSafeNorm(high - low);
  const double relative = mass.Value().volume / (extent * extent * extent);
  if (!(relative >= kMinHullRelativeVolume)) {
    return BodyProblem{
        "/shape/points",
        Named(body, Concat({"the hull has no volume for its extent: ", FormatNumber(mass.Value().volume),
                            " m^3 within a bounding-box diagonal of ", FormatNumber(extent), " m is ",
                            FormatNumber(relative), " of the diagonal cubed, below ",
                            FormatNumber(kMinHullRelativeVolume),
                            " (a slab thinner than about 3e-9 of its size)"}))};
  }
  return UnitSolid{mass.Value().volume, mass.Value().inertia};
}

UnitSolid BoxSolid(const BoxShape& box) {
  const Vec3 e = 2.0 * box.halfExtents;
  UnitSolid solid;
  solid.volume = e.x() * e.y() * e.z();
  solid.inertia.diagonal() =
      solid.volume / 12.0 *
      Vec3(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(), e.x() * e.x() + e.y() * e.y());
  return solid;
}

UnitSolid SphereSolid(const SphereShape& sphere) {
  const double r = sphere.radius;
  UnitSolid solid;
  solid.volume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  solid.inertia = 0.4 * solid.volume * r * r * Mat3::Identity();
  return solid;
}

}  // namespace

std::optional<BodyProblem> FindDegenerateBody(const BodySpec& body) {
  UnitSolid solid;
  if (const auto* box = std::get_if<BoxShape>(&body.shape)) {
    solid = BoxSolid(*box);
  } else if (const auto* sphere = std::get_if<SphereShape>(&body.shape)) {
    solid = SphereSolid(*sphere);
  } else {
    auto hull = HullSolid(body, std::get<HullShape>(body.shape));
    if (auto* problem = std::get_if<BodyProblem>(&hull)) return *problem;
    solid = std::get<UnitSolid>(hull);
  }
  if (body.motion != Motion::Dynamic) return std::nullopt;

  constexpr double kSmallestNormal = std::numeric_limits<double>::min();
  const bool byMass = body.mass > 0.0;
  const double mass = byMass ? body.mass : body.density * solid.volume;
  if (!std::isfinite(mass) || !(mass >= kSmallestNormal)) {
    const std::string how = byMass ? std::string()
                                   : Concat({" (density ", FormatNumber(body.density), " kg/m^3 x volume ",
                                             FormatNumber(solid.volume), " m^3)"});
    return BodyProblem{byMass ? "/mass" : "/density",
                       Named(body, Concat({"mass ", FormatNumber(mass), " kg", how,
                                           " is zero, denormal or not finite (the smallest normal double is ",
                                           FormatNumber(kSmallestNormal), ")"}))};
  }
  const Mat3 inertia = mass / solid.volume * solid.inertia;
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(inertia, Eigen::EigenvaluesOnly);
  const Vec3 moments = solver.eigenvalues();  // ascending
  if (!inertia.allFinite() || !(moments[0] >= kSmallestNormal) ||
      !(moments[0] >= kMinRelativeMoment * moments[2])) {
    return BodyProblem{"", Named(body, Concat({"the inertia is not positive definite: principal moments ",
                                               FormatNumber(moments[0]), ", ", FormatNumber(moments[1]), ", ",
                                               FormatNumber(moments[2]),
                                               " kg m^2; the smallest must be a normal double and at least ",
                                               FormatNumber(kMinRelativeMoment), " of the largest"}))};
  }
  return std::nullopt;
}

}  // namespace talus::harness
