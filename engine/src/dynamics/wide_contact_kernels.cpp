// The SIMD passes of the wide contact solver: warm start, normal rows
// (block solve with its row-by-row fallback) and friction rows of a range
// of bundles of one colour, four pairs per bundle, one per lane (see
// dynamics/wide_contact_solver.h). The only file compiled with the build's
// SIMD flags (CMake option TALUS_SIMD); it does no Eigen arithmetic, so the
// rest of the engine is the same code in every build.
//
// Per lane the arithmetic is the scalar solver's, in its order: Cdot =
// d.(vA - vB) + (rA x d).wA - (rB x d).wB; lambda = max(lambda - m (Cdot -
// target), 0) for a normal row, clamp(lambda - m Cdot, -mu lambda_n,
// mu lambda_n) for a friction row; vA += mA^-1 (dl d), wA += dl IA^-1 (rA x
// d), B the opposite. A block lane computes dlambda = K+ (target - J v) and
// keeps it when no impulse would pull; other lanes (and rejected ones) go
// row by row with the accepted lanes' changes masked to zero.
#include "dynamics/simd_lanes.h"
#include "dynamics/wide_contact_solver.h"

namespace talus {
namespace {

using lanes::Wide;

Wide L(const WideContactSolver::Lanes& lanes) { return lanes::Load(lanes.v); }
void S(WideContactSolver::Lanes& lanes, Wide value) { lanes::Store(lanes.v, value); }

struct Vector {
  Wide x, y, z;
};

Vector LoadVector(const WideContactSolver::Lanes* xyz) { return {L(xyz[0]), L(xyz[1]), L(xyz[2])}; }
Wide Dot(const Vector& a, const Vector& b) { return lanes::Dot(a.x, a.y, a.z, b.x, b.y, b.z); }

// The velocities of the four lanes' bodies A and B.
struct BundleVelocities {
  Vector vA, wA, vB, wB;
};

// The six velocities of a solver body lie contiguous (SolverVelocity is
// two Vec3 = six doubles); an empty lane reads zeros.
static_assert(sizeof(SolverVelocity) == 6 * sizeof(double), "v and w contiguous");
constexpr double kNoBody[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

// Gathers the lanes' bodies and transposes them into lanes.
void Gather(SolverBodies& bodies, const int (&index)[4], Vector& v, Vector& w) {
  const double* rows[4];
  for (int lane = 0; lane < 4; ++lane) {
    rows[lane] = index[lane] < 0 ? kNoBody : reinterpret_cast<const double*>(&bodies.Velocity(index[lane]));
  }
  Wide lanesOut[6];
  lanes::Transpose6(rows, lanesOut);
  v = {lanesOut[0], lanesOut[1], lanesOut[2]};
  w = {lanesOut[3], lanesOut[4], lanesOut[5]};
}

// Writes the lanes in `bits` back (bodies contacts can move; immovable ones
// are only read, so concurrent ranges never write a shared body).
void Scatter(SolverBodies& bodies, const int (&index)[4], unsigned bits, const Vector& v, const Vector& w) {
  double* rows[4];
  for (int lane = 0; lane < 4; ++lane) {
    // Lanes outside `bits` are skipped by Untranspose6, never written.
    rows[lane] =
        ((bits >> lane) & 1u) != 0 ? reinterpret_cast<double*>(&bodies.Velocity(index[lane])) : nullptr;
  }
  const Wide values[6] = {v.x, v.y, v.z, w.x, w.y, w.z};
  lanes::Untranspose6(values, bits, rows);
}

BundleVelocities Load(SolverBodies& bodies, const WideContactSolver::Bundle& bundle) {
  BundleVelocities v;
  Gather(bodies, bundle.bodyA, v.vA, v.wA);
  Gather(bodies, bundle.bodyB, v.vB, v.wB);
  return v;
}

void Store(SolverBodies& bodies, const WideContactSolver::Bundle& bundle, const BundleVelocities& v) {
  Scatter(bodies, bundle.bodyA, bundle.storeBitsA, v.vA, v.wA);
  Scatter(bodies, bundle.bodyB, bundle.storeBitsB, v.vB, v.wB);
}

Vector Cross(const Vector& a, const Vector& b) {
  // Eigen's cross product for a Vector3d, term by term.
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// A world inverse inertia, row-major, of four lanes.
struct Inertia {
  Wide m[9];
};

Inertia LoadInertia(const WideContactSolver::Lanes (&lanes)[9]) {
  Inertia inertia;
  for (int k = 0; k < 9; ++k) inertia.m[k] = L(lanes[k]);
  return inertia;
}

// I v in Eigen's order for a Mat3 times a Vec3 in this build (SSE2 packets
// for rows 0 and 1, summed in column order; row 2 reduced as x + (y + z);
// measured on 1e5 random products, and the bit-for-bit test would catch a
// change).
Vector Times(const Inertia& inertia, const Vector& v) {
  const Wide* m = inertia.m;
  return {(m[0] * v.x + m[1] * v.y) + m[2] * v.z, (m[3] * v.x + m[4] * v.y) + m[5] * v.z,
          m[6] * v.x + (m[7] * v.y + m[8] * v.z)};
}

// The angular parts of four rows along d and their images, as the scalar
// MakeRowJacobian (dynamics/contact_rows.h) forms them in Prepare (contact_row_set.cpp).
struct Jacobian {
  Vector angularA, angularB, imageA, imageB;
};

Jacobian MakeJacobian(const Vector& d, const WideContactSolver::WidePoint& point, const Inertia& inertiaA,
                      const Inertia& inertiaB) {
  Jacobian j;
  j.angularA = Cross(LoadVector(point.armA), d);
  j.angularB = Cross(LoadVector(point.armB), d);
  j.imageA = Times(inertiaA, j.angularA);
  j.imageB = Times(inertiaB, j.angularB);
  return j;
}

// Cdot of four rows along d.
Wide Along(const BundleVelocities& v, const Vector& d, const Jacobian& j) {
  const Vector dv{v.vA.x - v.vB.x, v.vA.y - v.vB.y, v.vA.z - v.vB.z};
  return Dot(d, dv) + Dot(j.angularA, v.wA) - Dot(j.angularB, v.wB);
}

// Adds the impulses `delta` along d: +d on A, -d on B.
void Apply(BundleVelocities& v, Wide delta, const Vector& d, const Jacobian& j, Wide invMassA,
           Wide invMassB) {
  const Vector impulse{delta * d.x, delta * d.y, delta * d.z};
  v.vA = {v.vA.x + invMassA * impulse.x, v.vA.y + invMassA * impulse.y, v.vA.z + invMassA * impulse.z};
  v.wA = {v.wA.x + delta * j.imageA.x, v.wA.y + delta * j.imageA.y, v.wA.z + delta * j.imageA.z};
  v.vB = {v.vB.x - invMassB * impulse.x, v.vB.y - invMassB * impulse.y, v.vB.z - invMassB * impulse.z};
  v.wB = {v.wB.x - delta * j.imageB.x, v.wB.y - delta * j.imageB.y, v.wB.z - delta * j.imageB.z};
}

// The velocity change |delta| / m of a row of a new pair with m > 0 (0
// otherwise), as the scalar ChangeTracker computes it.
Wide Change(Wide delta, Wide mass, lanes::Mask newPair) {
  const lanes::Mask tracked = newPair & !lanes::GreaterEqual(lanes::Zero(), mass);
  return lanes::Select(tracked, lanes::Abs(delta) / mass, lanes::Zero());
}

double Largest(Wide change) {
  alignas(32) double t[4];
  lanes::Store(t, change);
  double largest = 0.0;
  for (const double value : t) largest = value > largest ? value : largest;
  return largest;
}

}  // namespace

void WideContactSolver::WarmStartRange(SolverBodies& bodies, int colour, int begin, int end) const {
  const int first = m_colourStart[static_cast<std::size_t>(colour)];
  for (int b = first + begin; b < first + end; ++b) {
    const Bundle& bundle = m_bundles[static_cast<std::size_t>(b)];
    BundleVelocities v = Load(bodies, bundle);
    const Vector n = LoadVector(bundle.normal);
    const Vector t[2] = {LoadVector(bundle.tangent[0]), LoadVector(bundle.tangent[1])};
    const Inertia inertiaA = LoadInertia(bundle.invInertiaA);
    const Inertia inertiaB = LoadInertia(bundle.invInertiaB);
    const Wide invMassA = L(bundle.invMassA);
    const Wide invMassB = L(bundle.invMassB);
    const bool friction = bundle.frictionBits != 0;
    for (int i = 0; i < bundle.points; ++i) {
      const WidePoint& point = m_points[static_cast<std::size_t>(bundle.firstPoint + i)];
      const Jacobian jn = MakeJacobian(n, point, inertiaA, inertiaB);
      const Wide lambda = L(point.normalImpulse);
      Vector impulse{lambda * n.x, lambda * n.y, lambda * n.z};
      Vector turnA{lambda * jn.imageA.x, lambda * jn.imageA.y, lambda * jn.imageA.z};
      Vector turnB{lambda * jn.imageB.x, lambda * jn.imageB.y, lambda * jn.imageB.z};
      if (friction) {
        for (int k = 0; k < 2; ++k) {
          const Jacobian jt = MakeJacobian(t[k], point, inertiaA, inertiaB);
          const Wide fl = L(point.tangentImpulse[k]);
          impulse = {impulse.x + fl * t[k].x, impulse.y + fl * t[k].y, impulse.z + fl * t[k].z};
          turnA = {turnA.x + fl * jt.imageA.x, turnA.y + fl * jt.imageA.y, turnA.z + fl * jt.imageA.z};
          turnB = {turnB.x + fl * jt.imageB.x, turnB.y + fl * jt.imageB.y, turnB.z + fl * jt.imageB.z};
        }
      }
      v.vA = {v.vA.x + invMassA * impulse.x, v.vA.y + invMassA * impulse.y, v.vA.z + invMassA * impulse.z};
      v.wA = {v.wA.x + turnA.x, v.wA.y + turnA.y, v.wA.z + turnA.z};
      v.vB = {v.vB.x - invMassB * impulse.x, v.vB.y - invMassB * impulse.y, v.vB.z - invMassB * impulse.z};
      v.wB = {v.wB.x - turnB.x, v.wB.y - turnB.y, v.wB.z - turnB.z};
    }
    Store(bodies, bundle, v);
  }
}

double WideContactSolver::SolveNormalRange(SolverBodies& bodies, int colour, int begin, int end, bool track) {
  const int first = m_colourStart[static_cast<std::size_t>(colour)];
  Wide largest = lanes::Zero();
  for (int b = first + begin; b < first + end; ++b) {
    const Bundle& bundle = m_bundles[static_cast<std::size_t>(b)];
    WidePoint* points = &m_points[static_cast<std::size_t>(bundle.firstPoint)];
    BundleVelocities v = Load(bodies, bundle);
    const Vector n = LoadVector(bundle.normal);
    const Wide invMassA = L(bundle.invMassA);
    const Wide invMassB = L(bundle.invMassB);
    const lanes::Mask newPair = lanes::MaskFromBits(bundle.newBits);
    const int count = bundle.points;
    Jacobian j[kMaxBundlePoints];
    {
      const Inertia inertiaA = LoadInertia(bundle.invInertiaA);
      const Inertia inertiaB = LoadInertia(bundle.invInertiaB);
      for (int i = 0; i < count; ++i) j[i] = MakeJacobian(n, points[i], inertiaA, inertiaB);
    }
    lanes::Mask rowByRow = lanes::MaskFromBits(0xFu);
    if (bundle.blockBits != 0) {
      // dlambda = K+ (target - J v) for every lane with a block, accepted
      // where no accumulated impulse would become negative.
      const Vector dv{v.vA.x - v.vB.x, v.vA.y - v.vB.y, v.vA.z - v.vB.z};
      const Wide vn0 = Dot(n, dv);
      // Rows past `count` are zero, as the scalar solver's padded 4x4.
      Wide rhs[kMaxBundlePoints] = {lanes::Zero(), lanes::Zero(), lanes::Zero(), lanes::Zero()};
      for (int i = 0; i < count; ++i) {
        const Wide vn = vn0 + Dot(j[i].angularA, v.wA) - Dot(j[i].angularB, v.wB);
        rhs[i] = L(points[i].target) - vn;
      }
      Wide delta[kMaxBundlePoints];
      lanes::Mask accept = lanes::MaskFromBits(bundle.blockBits);
      for (int i = 0; i < count; ++i) {
        Wide sum = L(bundle.block[4 * i]) * rhs[0];
        for (int k = 1; k < kMaxBundlePoints; ++k) sum = sum + L(bundle.block[4 * i + k]) * rhs[k];
        delta[i] = sum;
        accept = accept & lanes::GreaterEqual(L(points[i].normalImpulse) + delta[i], lanes::Zero());
      }
      if (lanes::Any(accept)) {
        for (int i = 0; i < count; ++i) {
          const Wide lambda = L(points[i].normalImpulse);
          const Wide d = lanes::Select(accept, delta[i], lanes::Zero());
          S(points[i].normalImpulse, lanes::Select(accept, lambda + delta[i], lambda));
          if (track) largest = lanes::Max(largest, Change(d, L(points[i].normalMass), newPair));
          Apply(v, d, n, j[i], invMassA, invMassB);
        }
      }
      rowByRow = !accept;
    }
    if (lanes::Any(rowByRow)) {
      for (int i = 0; i < count; ++i) {
        WidePoint& point = points[i];
        const Wide mass = L(point.normalMass);
        const Wide vn = Along(v, n, j[i]);
        const Wide previous = L(point.normalImpulse);
        // Max(0, x) = (0 > x) ? 0 : x, std::max(x, 0.0)'s value bit for bit.
        const Wide solved = lanes::Max(lanes::Zero(), previous - mass * (vn - L(point.target)));
        const Wide impulse = lanes::Select(rowByRow, solved, previous);
        S(point.normalImpulse, impulse);
        const Wide delta = impulse - previous;
        if (track) largest = lanes::Max(largest, Change(delta, mass, newPair));
        Apply(v, delta, n, j[i], invMassA, invMassB);
      }
    }
    Store(bodies, bundle, v);
  }
  return track ? Largest(largest) : 0.0;
}

double WideContactSolver::SolveFrictionRange(SolverBodies& bodies, int colour, int begin, int end,
                                             bool track) {
  const int first = m_colourStart[static_cast<std::size_t>(colour)];
  Wide largest = lanes::Zero();
  for (int b = first + begin; b < first + end; ++b) {
    const Bundle& bundle = m_bundles[static_cast<std::size_t>(b)];
    if (bundle.frictionBits == 0) continue;
    WidePoint* points = &m_points[static_cast<std::size_t>(bundle.firstPoint)];
    BundleVelocities v = Load(bodies, bundle);
    const Vector t[2] = {LoadVector(bundle.tangent[0]), LoadVector(bundle.tangent[1])};
    const Inertia inertiaA = LoadInertia(bundle.invInertiaA);
    const Inertia inertiaB = LoadInertia(bundle.invInertiaB);
    const Wide mu = L(bundle.friction);
    const Wide invMassA = L(bundle.invMassA);
    const Wide invMassB = L(bundle.invMassB);
    const lanes::Mask newPair = lanes::MaskFromBits(bundle.newBits);
    for (int i = 0; i < bundle.points; ++i) {
      WidePoint& point = points[i];
      const Wide bound = mu * L(point.normalImpulse);
      for (int k = 0; k < 2; ++k) {
        const Jacobian j = MakeJacobian(t[k], point, inertiaA, inertiaB);
        const Wide mass = L(point.tangentMass[k]);
        const Wide vt = Along(v, t[k], j);
        const Wide old = L(point.tangentImpulse[k]);
        // std::clamp(x, lo, hi) = x < lo ? lo : (hi < x ? hi : x) for lo <=
        // hi, which is Min(hi, Max(lo, x)) with the lanes' rules, bit for bit.
        const Wide impulse = lanes::Min(bound, lanes::Max(-bound, old - mass * vt));
        S(point.tangentImpulse[k], impulse);
        const Wide delta = impulse - old;
        if (track) largest = lanes::Max(largest, Change(delta, mass, newPair));
        Apply(v, delta, t[k], j, invMassA, invMassB);
      }
    }
    Store(bodies, bundle, v);
  }
  return track ? Largest(largest) : 0.0;
}

}  // namespace talus
