// The per-pass helpers the scalar contact sweeps share
// (sequential_impulse_sweeps.cpp, the coupled block of normals and friction
// in coupled_block_solver.cpp, shock_propagation.cpp): a pair's two body
// velocities held in locals for one pass over its rows, and the change
// tracking of the extra sweeps.
#pragma once

#include <algorithm>
#include <cmath>

#include "dynamics/contact_rows.h"
#include "dynamics/solver_body.h"

namespace talus {

// The velocities of a pair's two bodies, loaded into locals once per pass
// over the pair's rows and stored at its end.
struct PairVelocities {
  Vec3 vA, wA, vB, wB;

  static PairVelocities Load(const SolverVelocity& a, const SolverVelocity& b) {
    return {a.v, a.w, b.v, b.w};
  }
  void Store(SolverVelocity& a, SolverVelocity& b) const {
    a.v = vA;
    a.w = wA;
    b.v = vB;
    b.w = wB;
  }
  /// Cdot of the row along `d` with Jacobian terms `j`.
  template <typename Jacobian>
  [[nodiscard]] double Along(const Vec3& d, const Jacobian& j) const {
    return d.dot(vA - vB) + j.angularA.dot(wA) - j.angularB.dot(wB);
  }
  /// Adds the impulse `delta` along `d`: +d on A, -d on B.
  template <typename Jacobian>
  void Apply(double delta, const Vec3& d, const Jacobian& j, double invMassA, double invMassB) {
    const Vec3 impulse = delta * d;
    vA += invMassA * impulse;
    wA += delta * j.imageA;
    vB -= invMassB * impulse;
    wB -= delta * j.imageB;
  }
};

// The largest velocity change |impulse| / mass (m/s) the rows of one pass
// over a pair made, counted only for a new pair (the extra sweeps' stop
// test), and merged into the solver's sweep maximum once at the end of the
// pass. A local the compiler keeps in a register: when every row updated
// the member through an out-of-line call, the call spilled the pass's
// velocities and the member was reloaded after every row store, and the
// tracked sweeps (most of hull_pile's) ran slower for it. max is exact and
// NaN-blind in any grouping, so the maximum is the same bits.
struct ChangeTracker {
  explicit ChangeTracker(const PairRows& pair) : active(!pair.persisted) {}
  void Note(double impulse, double mass) {
    if (active && mass > 0.0) largest = std::max(largest, std::abs(impulse) / mass);
  }
  bool active;
  double largest = 0.0;
};

}  // namespace talus
