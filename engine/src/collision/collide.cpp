// Shape-pair dispatch (see collide.h).
#include "collision/collide.h"

#include <array>
#include <cassert>
#include <cstddef>

#include "collision/polyhedron_manifold.h"
#include "collision/sphere_contact.h"

namespace talus {
namespace {

struct PairContext {
  const NarrowPhaseSettings* settings;
  SatCache* cache;
  NarrowPhaseStats* stats;
  NarrowPhaseScratch* scratch;
};

using CollideFunction = bool (*)(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                                 const PairContext& context, ContactManifold* out);

bool Polyhedra(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
               const PairContext& context, ContactManifold* out) {
  const PosedHull hullA = PosedHull::Make(a.GetHull(), xfA);
  const PosedHull hullB = PosedHull::Make(b.GetHull(), xfB);
  const NarrowPhaseSettings& settings = *context.settings;
  SatCache* cache = settings.useSatCache ? context.cache : nullptr;
  const SatResult sat = RunSat(hullA, hullB, settings.satMode, settings.speculativeMargin, cache,
                               context.stats, context.scratch);
  if (sat.separated) {
    out->normal = sat.normal;
    out->depth = -sat.separation;
    out->pointCount = 0;
    return false;
  }
  BuildPolyhedronManifold(hullA, hullB, sat, settings.manifoldMode, settings.speculativeMargin, out,
                          context.scratch);
  return true;
}

bool SphereSphere(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                  const PairContext& context, ContactManifold* out) {
  return CollideSphereSphere(a, xfA, b, xfB, context.settings->speculativeMargin, out);
}

bool SphereBox(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
               const PairContext& context, ContactManifold* out) {
  return CollideSphereBox(a, xfA, b, xfB, context.settings->speculativeMargin, out);
}

bool SphereHull(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                const PairContext& context, ContactManifold* out) {
  return CollideSphereHull(a, xfA, b, xfB, context.settings->speculativeMargin, out);
}

// The mirrored entry: run `Routine` as (B, A), then turn the answer round.
template <CollideFunction Routine>
bool Swapped(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
             const PairContext& context, ContactManifold* out) {
  const bool touching = Routine(b, xfB, a, xfA, context, out);
  out->normal = -out->normal;
  if (!touching) return false;
  for (int i = 0; i < out->pointCount; ++i) {
    auto& point = out->points[static_cast<std::size_t>(i)];
    point.featureId = SwapFeatureId(point.featureId);
  }
  return true;
}

// Rows: A's type; columns: B's type (ShapeType order Hull, Box, Sphere).
constexpr std::array<std::array<CollideFunction, kShapeTypeCount>, kShapeTypeCount> kDispatch = {{
    {Polyhedra, Polyhedra, Swapped<SphereHull>},
    {Polyhedra, Polyhedra, Swapped<SphereBox>},
    {SphereHull, SphereBox, SphereSphere},
}};

}  // namespace

bool Collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
             const NarrowPhaseSettings& settings, SatCache* cache, NarrowPhaseStats* stats,
             ContactManifold* manifold, NarrowPhaseScratch* scratch) {
  assert(manifold != nullptr);
  assert(settings.speculativeMargin >= 0.0);
  const CollideFunction routine =
      kDispatch[static_cast<std::size_t>(a.Type())][static_cast<std::size_t>(b.Type())];
  const bool touching = routine(
      a, xfA, b, xfB, {.settings = &settings, .cache = cache, .stats = stats, .scratch = scratch}, manifold);
  if (stats) {
    ++stats->pairsTested;
    if (touching) {
      ++stats->pairsTouching;
      stats->manifoldPoints += manifold->pointCount;
    }
  }
  return touching;
}

}  // namespace talus
