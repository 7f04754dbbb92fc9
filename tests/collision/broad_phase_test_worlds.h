// Random broad phase worlds for the tests: deterministic (SplitMix64, fixed
// seeds), with uniform or mixed sizes, static and oversized bodies, motion
// over steps and bodies added and removed, plus the brute-force oracle every
// structure is compared with.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "collision/broad_phase_proxy.h"
#include "talus/harness/support/split_mix64.h"

namespace talus::testing {

/// The SplitMix64 stream of the benchmark scenes (talus/harness/support/split_mix64.h,
/// header-only), so the worlds are the same on every standard library, with
/// the ranges these tests draw from.
class SplitMix64 : public harness::SplitMix64 {
 public:
  using harness::SplitMix64::SplitMix64;
  /// Uniform in [0, 1).
  double Uniform() { return NextUniform(); }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Log-uniform in [lo, hi), lo > 0: mixed sizes over decades.
  double LogUniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * Uniform()); }
};

/// How a random world is drawn.
struct WorldSpec {
  int count = 1000;               ///< body slots
  double halfExtent = 20.0;       ///< centres uniform in [-h, h]^3 (m)
  double minRadius = 0.5;         ///< m
  double maxRadius = 0.5;         ///< m; > minRadius gives log-uniform sizes
  double staticFraction = 0.1;    ///< share of bodies that are static
  int oversizedStatics = 0;       ///< huge static spheres (radius 10-60 h/20)
  double inactiveFraction = 0.0;  ///< share of slots left empty
  double speed = 0.0;             ///< m per step, dynamic bodies
};

/// A world that moves: proxies plus a velocity per slot.
struct TestWorld {
  std::vector<BroadPhaseProxy> proxies;
  std::vector<Vec3> velocity;
};

inline BroadPhaseProxy RandomProxy(const WorldSpec& spec, SplitMix64& rng) {
  BroadPhaseProxy p;
  p.sphere.center = {rng.Uniform(-spec.halfExtent, spec.halfExtent),
                     rng.Uniform(-spec.halfExtent, spec.halfExtent),
                     rng.Uniform(-spec.halfExtent, spec.halfExtent)};
  p.sphere.radius =
      spec.maxRadius > spec.minRadius ? rng.LogUniform(spec.minRadius, spec.maxRadius) : spec.minRadius;
  p.isStatic = rng.Uniform() < spec.staticFraction;
  p.active = rng.Uniform() >= spec.inactiveFraction;
  return p;
}

inline TestWorld MakeWorld(const WorldSpec& spec, std::uint64_t seed) {
  SplitMix64 rng(seed);
  TestWorld world;
  for (int i = 0; i < spec.count; ++i) {
    world.proxies.push_back(RandomProxy(spec, rng));
    const Vec3 v{rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1)};
    world.velocity.push_back(spec.speed * v);
  }
  // Oversized statics replace the first slots: floors and walls made early.
  for (int k = 0; k < spec.oversizedStatics && k < spec.count; ++k) {
    BroadPhaseProxy& p = world.proxies[static_cast<std::size_t>(k)];
    p.sphere.radius = rng.Uniform(0.5, 3.0) * spec.halfExtent;
    p.isStatic = true;
    p.active = true;
  }
  return world;
}

/// One step: dynamic bodies move; a few slots are emptied, refilled or
/// flipped between static and dynamic; now and then slots are appended or
/// the array shrinks, as a world adding and removing bodies would.
inline void StepWorld(const WorldSpec& spec, TestWorld& world, SplitMix64& rng) {
  for (std::size_t i = 0; i < world.proxies.size(); ++i) {
    BroadPhaseProxy& p = world.proxies[i];
    if (!p.isStatic) p.sphere.center += world.velocity[i];
    const double u = rng.Uniform();
    if (u < 0.01) {
      p.active = !p.active;
    } else if (u < 0.015) {
      p = RandomProxy(spec, rng);
    } else if (u < 0.017) {
      p.isStatic = !p.isStatic;
    }
  }
  const double u = rng.Uniform();
  if (u < 0.3) {
    for (int k = 0; k < 5; ++k) {
      world.proxies.push_back(RandomProxy(spec, rng));
      world.velocity.push_back(Vec3::Zero());
    }
  } else if (u < 0.4 && world.proxies.size() > 10) {
    world.proxies.resize(world.proxies.size() - 3);
    world.velocity.resize(world.velocity.size() - 3);
  }
}

/// The oracle: every pair of active proxies, not both static, whose spheres
/// touch, in (a, b) order. Written independently of the engine's loops.
inline std::vector<BroadPhasePair> OraclePairs(const std::vector<BroadPhaseProxy>& proxies) {
  std::vector<BroadPhasePair> pairs;
  const int n = static_cast<int>(proxies.size());
  for (int a = 0; a < n; ++a) {
    const BroadPhaseProxy& pa = proxies[static_cast<std::size_t>(a)];
    if (!pa.active) continue;
    for (int b = a + 1; b < n; ++b) {
      const BroadPhaseProxy& pb = proxies[static_cast<std::size_t>(b)];
      if (pb.active && !(pa.isStatic && pb.isStatic) && SpheresTouch(pa.sphere, pb.sphere))
        pairs.push_back({a, b});
    }
  }
  return pairs;
}

}  // namespace talus::testing
