// Persistent contact points (see collision/manifold_persistence.h).
#include "collision/manifold_persistence.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "collision/manifold_reduction.h"
#include "collision/polyhedron_manifold.h"
#include "collision/posed_hull.h"
#include "collision/sat.h"

namespace talus {
namespace {

// A remembered point that survived the break tests, at the current poses.
struct Survivor {
  ContactPoint point;
  Vec3 localA;  // A's surface point, A's frame (as recorded)
  Vec3 localB;  // B's surface point, B's frame (as recorded)
};

double NearestDistance(const Vec3& p, std::span<const Vec3> kept) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Vec3& q : kept) nearest = std::min(nearest, (p - q).norm());
  return nearest;
}

}  // namespace

double PersistentBreakDistance(double setting, double radiusA, double radiusB) {
  return std::min(setting, kPersistentRelative * std::min(radiusA, radiusB));
}

// A line depth this close to the point's own is the same measure: 1e-9 of
// the pair's size, the exactness the clipped manifold's miss test asked of
// positions when this was chosen (that test now allows round-off only,
// kInsideRoundOffUlps in polyhedron_manifold.cpp).
constexpr double kSnapRelative = 1e-9;

namespace {

// A feature this close to parallel with the line (sine squared for an
// edge, cosine for a face normal) has no reliable crossing (unitless; as
// kParallelFaceCosine in polyhedron_manifold.cpp: round-off divided by a
// round-off rate is garbage).
constexpr double kParallelLine = 1e-9;

// Where the line p + t n (n unit) meets feature `feature` (16-bit packed,
// contact_manifold.h) of `hull`: its t, or NaN when the feature is none,
// out of range (indices wrap above 16383), parallel to the line, or farther
// from the line than `tolerance` (metres). A vertex is its own point; an
// edge gives its point closest to the line; a face the line's crossing of
// its plane.
double FeatureOnLine(const PosedHull& hull, std::uint32_t feature, const Vec3& p, const Vec3& n,
                     double tolerance) {
  const double none = std::numeric_limits<double>::quiet_NaN();
  const auto type = static_cast<FeatureType>(feature >> 14);
  const int index = static_cast<int>(feature & 0x3FFFu);
  Vec3 point = Vec3::Zero();
  if (type == FeatureType::Vertex && index < hull.hull->VertexCount()) {
    point = hull.Vertex(index);
  } else if (type == FeatureType::Edge && index < hull.hull->EdgeCount()) {
    // The segment a + s d (s in [0, 1]) against the line p + t n: the s
    // that minimises |a + s d - p - t n| once t takes its best value.
    const Vec3 a = hull.Vertex(hull.EdgeStart(index));
    const Vec3 d = hull.Vertex(hull.EdgeEnd(index)) - a;
    const Vec3 w = a - p;
    const double across = d.squaredNorm() - n.dot(d) * n.dot(d);  // |d|^2 sin^2
    if (!(across > kParallelLine * d.squaredNorm())) return none;
    const double s = std::clamp((n.dot(d) * n.dot(w) - d.dot(w)) / across, 0.0, 1.0);
    point = a + s * d;
  } else if (type == FeatureType::Face && index < hull.hull->FaceCount()) {
    const Plane plane = hull.FacePlane(index);
    const double rate = plane.normal.dot(n);
    if (!(std::abs(rate) > kParallelLine)) return none;
    return -plane.SignedDistance(p) / rate;
  } else {
    return none;
  }
  const double t = n.dot(point - p);
  return ((point - p) - t * n).norm() <= tolerance ? t : none;
}

}  // namespace

void SnapAnchorsToSurfaces(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                           const ContactManifold& manifold, ManifoldAnchors* anchors) {
  assert(a.IsPolyhedron() && b.IsPolyhedron() && anchors->pointCount == manifold.pointCount);
  const PosedHull hullA = PosedHull::Make(a.GetHull(), xfA);
  const PosedHull hullB = PosedHull::Make(b.GetHull(), xfB);
  const double size = SatLengthScale(a.GetHull(), b.GetHull());
  const Vec3& n = manifold.normal;
  for (std::size_t i = 0; i < static_cast<std::size_t>(manifold.pointCount); ++i) {
    const ContactPoint& point = manifold.points[i];
    const double roundOff = kDepthRoundOffUlps * std::numeric_limits<double>::epsilon() *
                            (point.position.cwiseAbs().maxCoeff() + size);
    const double tolerance = kSnapRelative * size + roundOff;
    // First the two features that made the point, where they meet its
    // normal line; else where the line enters A and leaves B (A lies on
    // the +n side).
    double onA = FeatureOnLine(hullA, point.featureId >> 16, point.position, n, tolerance);
    double onB = FeatureOnLine(hullB, point.featureId & 0xFFFFu, point.position, n, tolerance);
    if (!std::isfinite(onA) || !std::isfinite(onB) || !(std::abs((onB - onA) - point.depth) <= tolerance)) {
      double hiA = 0.0;
      double loB = 0.0;
      LineInterval(hullA, point.position, n, roundOff, &onA, &hiA);
      LineInterval(hullB, point.position, n, roundOff, &loB, &onB);
      if (!std::isfinite(onA) || !std::isfinite(onB) || onA > hiA || loB > onB) continue;
      if (!(std::abs((onB - onA) - point.depth) <= tolerance)) continue;
    }
    anchors->localPointA[i] = xfA.ApplyInverse(point.position + onA * n);
    anchors->localPointB[i] = xfB.ApplyInverse(point.position + onB * n);
  }
}

namespace {

// The remembered points at the current poses into `survivors`, minus the
// broken ones and those a fresh point replaces; returns their count.
std::size_t CollectSurvivors(const ContactManifold& previous, const ManifoldAnchors& previousAnchors,
                             const Transform& xfA, const Transform& xfB, double distance,
                             const ContactManifold& fresh,
                             std::array<Survivor, kMaxManifoldPoints>& survivors) {
  const Vec3& n = fresh.normal;
  const std::size_t freshCount = static_cast<std::size_t>(fresh.pointCount);
  std::size_t survivorCount = 0;
  const std::size_t previousCount =
      static_cast<std::size_t>(std::min(previous.pointCount, previousAnchors.pointCount));
  for (std::size_t i = 0; i < previousCount; ++i) {
    const std::uint32_t id = previous.points[i].featureId;
    bool replaced = false;
    for (std::size_t j = 0; j < freshCount; ++j) replaced = replaced || fresh.points[j].featureId == id;
    if (replaced) continue;
    const Vec3 onA = xfA.Apply(previousAnchors.localPointA[i]);
    const Vec3 onB = xfB.Apply(previousAnchors.localPointB[i]);
    const Vec3 gap = onB - onA;
    const double depth = n.dot(gap);
    const double drift = (gap - depth * n).norm();
    // Separated along n, or slid apart along the surfaces: the two surface
    // points no longer describe a place where the shapes touch.
    if (depth < -distance || drift > distance) continue;
    survivors[survivorCount++] = {.point = {.position = 0.5 * (onA + onB), .depth = depth, .featureId = id},
                                  .localA = previousAnchors.localPointA[i],
                                  .localB = previousAnchors.localPointB[i]};
  }
  return survivorCount;
}

// The unused survivor that grows the area of the kept polygon (the first
// `keptCount` of `kept`, whose slot keptCount is scratch) most; while that
// is zero for every candidate (fewer than two kept, or all collinear), the
// one farthest from the kept points. -1 when none is farther than
// `distance` from every kept point.
int WidestSurvivor(std::span<const Survivor> survivors, std::span<const bool> used, double distance,
                   const Vec3& n, std::array<Vec3, kMaxManifoldPoints + 1>& kept, std::size_t keptCount) {
  int best = -1;
  double bestArea = 0.0;
  double bestSpread = 0.0;
  for (std::size_t i = 0; i < survivors.size(); ++i) {
    if (used[i]) continue;
    const Vec3& p = survivors[i].point.position;
    const double spread = NearestDistance(p, std::span<const Vec3>(kept.data(), keptCount));
    // Within the break distance of a kept point: adds no support.
    if (!(spread > distance)) continue;
    kept[keptCount] = p;
    const double area = ContactPolygonArea(std::span<const Vec3>(kept.data(), keptCount + 1), n);
    if (area > bestArea || (area == bestArea && spread > bestSpread)) {
      best = static_cast<int>(i);
      bestArea = area;
      bestSpread = spread;
    }
  }
  return best;
}

}  // namespace

int MergePersistentPoints(const ContactManifold& previous, const ManifoldAnchors& previousAnchors,
                          const Transform& xfA, const Transform& xfB, double distance, int maxFreshPoints,
                          ContactManifold* fresh, ManifoldAnchors* freshAnchors) {
  assert(std::isfinite(distance) && distance > 0.0);
  assert(freshAnchors->recorded && freshAnchors->pointCount == fresh->pointCount);
  if (!previousAnchors.recorded || fresh->pointCount <= 0 || fresh->pointCount > maxFreshPoints ||
      fresh->pointCount >= kPersistentMaxPoints)
    return 0;
  const Vec3& n = fresh->normal;
  const std::size_t freshCount = static_cast<std::size_t>(fresh->pointCount);
  // Only a contact under load needs the support: a fresh manifold whose
  // deepest point has a gap (speculative, depth <= 0) is left as the narrow
  // phase made it. Filled, it carried remembered points up to the break
  // distance from bodies that no longer touch, and the 2870-cube pyramid
  // drifted 62 mm instead of 1.4 mm (docs/collision-narrow-phase.md).
  double deepest = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < freshCount; ++j) deepest = std::max(deepest, fresh->points[j].depth);
  if (!(deepest > 0.0)) return 0;

  std::array<Survivor, kMaxManifoldPoints> survivors{};
  const std::size_t survivorCount =
      CollectSurvivors(previous, previousAnchors, xfA, xfB, distance, *fresh, survivors);

  // Fill up to kPersistentMaxPoints, one widest survivor at a time.
  std::array<Vec3, kMaxManifoldPoints + 1> kept{};
  std::size_t keptCount = freshCount;
  for (std::size_t j = 0; j < freshCount; ++j) kept[j] = fresh->points[j].position;
  std::array<bool, kMaxManifoldPoints> used{};
  int added = 0;
  while (keptCount < static_cast<std::size_t>(kPersistentMaxPoints)) {
    const int best = WidestSurvivor(std::span<const Survivor>(survivors.data(), survivorCount), used,
                                    distance, n, kept, keptCount);
    if (best < 0) break;
    const Survivor& chosen = survivors[static_cast<std::size_t>(best)];
    used[static_cast<std::size_t>(best)] = true;
    kept[keptCount] = chosen.point.position;
    fresh->points[keptCount] = chosen.point;
    freshAnchors->localPointA[keptCount] = chosen.localA;
    freshAnchors->localPointB[keptCount] = chosen.localB;
    ++keptCount;
    ++added;
  }
  fresh->pointCount = static_cast<int>(keptCount);
  freshAnchors->pointCount = static_cast<int>(keptCount);
  return added;
}

}  // namespace talus
