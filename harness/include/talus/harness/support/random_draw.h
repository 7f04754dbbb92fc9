// RandomDraw: the random shapes' draws (uniform numbers, integers, unit
// vectors, rotations) from one std::mt19937_64, shared by the SAT check's
// pair generator and the hull builder's property tests. Header-only: the
// tests that use it link only the engine.
//
// Each draw consumes the engine in a fixed order, so a seed fixes every
// value; unit vectors and rotations are normalised Gaussian draws (uniform
// on the sphere and on SO(3)), redrawn in the rare case the draw is too
// short (norm <= 1e-3) to normalise accurately.
#pragma once

#include <random>

#include "talus/math.h"

namespace talus::harness {

struct RandomDraw {
  std::mt19937_64 rng;

  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  /// Uniform integer in [lo, hi].
  int Integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
  /// Uniform on the unit sphere.
  Vec3 UnitVector() {
    std::normal_distribution<double> normal(0.0, 1.0);
    for (;;) {
      const Vec3 v(normal(rng), normal(rng), normal(rng));
      if (v.norm() > 1e-3) return v.normalized();
    }
  }
  /// A uniformly distributed rotation.
  Quat Rotation() {
    std::normal_distribution<double> normal(0.0, 1.0);
    for (;;) {
      Quat q(normal(rng), normal(rng), normal(rng), normal(rng));
      if (q.norm() > 1e-3) return q.normalized();
    }
  }
};

}  // namespace talus::harness
