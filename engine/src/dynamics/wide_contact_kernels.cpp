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

// Cdot of four rows along d.
Wide Along(const BundleVelocities& v, const Vector& d, const WideContactSolver::WideRow& row) {
  const Vector dv{v.vA.x - v.vB.x, v.vA.y - v.vB.y, v.vA.z - v.vB.z};
  return Dot(d, dv) + Dot(LoadVector(row.angularA), v.wA) - Dot(LoadVector(row.angularB), v.wB);
}

// Adds the impulses `delta` along d: +d on A, -d on B.
void Apply(BundleVelocities& v, Wide delta, const Vector& d, const WideContactSolver::WideRow& row,
           Wide invMassA, Wide invMassB) {
  const Vector impulse{delta * d.x, delta * d.y, delta * d.z};
  v.vA = {v.vA.x + invMassA * impulse.x, v.vA.y + invMassA * impulse.y, v.vA.z + invMassA * impulse.z};
  const Vector imageA = LoadVector(row.imageA);
  v.wA = {v.wA.x + delta * imageA.x, v.wA.y + delta * imageA.y, v.wA.z + delta * imageA.z};
  v.vB = {v.vB.x - invMassB * impulse.x, v.vB.y - invMassB * impulse.y, v.vB.z - invMassB * impulse.z};
  const Vector imageB = LoadVector(row.imageB);
  v.wB = {v.wB.x - delta * imageB.x, v.wB.y - delta * imageB.y, v.wB.z - delta * imageB.z};
}

// The velocity change |delta| / m of a row of a new pair (0 for an old
// pair's row or an empty one), as the scalar NoteChange computes it.
Wide Change(Wide delta, const WideContactSolver::WideRow& row) {
  const lanes::Mask tracked = lanes::GreaterEqual(L(row.track), lanes::Splat(1.0));
  return lanes::Select(tracked, lanes::Abs(delta) / L(row.mass), lanes::Zero());
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
    const Wide invMassA = L(bundle.invMassA);
    const Wide invMassB = L(bundle.invMassB);
    const bool friction = bundle.frictionBits != 0;
    for (int i = 0; i < bundle.points; ++i) {
      const WideRow& row = m_normals[static_cast<std::size_t>(bundle.firstNormal + i)];
      const Wide lambda = L(row.impulse);
      Vector impulse{lambda * n.x, lambda * n.y, lambda * n.z};
      Vector turnA = LoadVector(row.imageA);
      turnA = {lambda * turnA.x, lambda * turnA.y, lambda * turnA.z};
      Vector turnB = LoadVector(row.imageB);
      turnB = {lambda * turnB.x, lambda * turnB.y, lambda * turnB.z};
      if (friction) {
        for (int k = 0; k < 2; ++k) {
          const WideRow& f = m_frictions[static_cast<std::size_t>(bundle.firstFriction + 2 * i + k)];
          const Wide fl = L(f.impulse);
          const Vector t = LoadVector(bundle.tangent[k]);
          impulse = {impulse.x + fl * t.x, impulse.y + fl * t.y, impulse.z + fl * t.z};
          const Vector ia = LoadVector(f.imageA);
          const Vector ib = LoadVector(f.imageB);
          turnA = {turnA.x + fl * ia.x, turnA.y + fl * ia.y, turnA.z + fl * ia.z};
          turnB = {turnB.x + fl * ib.x, turnB.y + fl * ib.y, turnB.z + fl * ib.z};
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
    WideRow* rows = &m_normals[static_cast<std::size_t>(bundle.firstNormal)];
    BundleVelocities v = Load(bodies, bundle);
    const Vector n = LoadVector(bundle.normal);
    const Wide invMassA = L(bundle.invMassA);
    const Wide invMassB = L(bundle.invMassB);
    const int points = bundle.points;
    lanes::Mask rowByRow = lanes::MaskFromBits(0xFu);
    if (bundle.blockBits != 0) {
      // dlambda = K+ (target - J v) for every lane with a block, accepted
      // where no accumulated impulse would become negative.
      const Vector dv{v.vA.x - v.vB.x, v.vA.y - v.vB.y, v.vA.z - v.vB.z};
      const Wide vn0 = Dot(n, dv);
      // Rows past `points` are zero, as the scalar solver's padded 4x4.
      Wide rhs[kMaxBundlePoints] = {lanes::Zero(), lanes::Zero(), lanes::Zero(), lanes::Zero()};
      for (int i = 0; i < points; ++i) {
        const Wide vn =
            vn0 + Dot(LoadVector(rows[i].angularA), v.wA) - Dot(LoadVector(rows[i].angularB), v.wB);
        rhs[i] = L(rows[i].target) - vn;
      }
      Wide delta[kMaxBundlePoints];
      lanes::Mask accept = lanes::MaskFromBits(bundle.blockBits);
      for (int i = 0; i < points; ++i) {
        Wide sum = L(bundle.block[4 * i]) * rhs[0];
        for (int j = 1; j < kMaxBundlePoints; ++j) sum = sum + L(bundle.block[4 * i + j]) * rhs[j];
        delta[i] = sum;
        accept = accept & lanes::GreaterEqual(L(rows[i].impulse) + delta[i], lanes::Zero());
      }
      if (lanes::Any(accept)) {
        for (int i = 0; i < points; ++i) {
          const Wide lambda = L(rows[i].impulse);
          const Wide d = lanes::Select(accept, delta[i], lanes::Zero());
          S(rows[i].impulse, lanes::Select(accept, lambda + delta[i], lambda));
          if (track) largest = lanes::Max(largest, Change(d, rows[i]));
          Apply(v, d, n, rows[i], invMassA, invMassB);
        }
      }
      rowByRow = !accept;
    }
    if (lanes::Any(rowByRow)) {
      for (int i = 0; i < points; ++i) {
        WideRow& row = rows[i];
        const Wide vn = Along(v, n, row);
        const Wide previous = L(row.impulse);
        // Max(0, x) = (0 > x) ? 0 : x, std::max(x, 0.0)'s value bit for bit.
        const Wide solved = lanes::Max(lanes::Zero(), previous - L(row.mass) * (vn - L(row.target)));
        const Wide impulse = lanes::Select(rowByRow, solved, previous);
        S(row.impulse, impulse);
        const Wide delta = impulse - previous;
        if (track) largest = lanes::Max(largest, Change(delta, row));
        Apply(v, delta, n, row, invMassA, invMassB);
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
    const WideRow* normals = &m_normals[static_cast<std::size_t>(bundle.firstNormal)];
    WideRow* rows = &m_frictions[static_cast<std::size_t>(bundle.firstFriction)];
    BundleVelocities v = Load(bodies, bundle);
    const Vector t[2] = {LoadVector(bundle.tangent[0]), LoadVector(bundle.tangent[1])};
    const Wide mu = L(bundle.friction);
    const Wide invMassA = L(bundle.invMassA);
    const Wide invMassB = L(bundle.invMassB);
    for (int i = 0; i < bundle.points; ++i) {
      const Wide bound = mu * L(normals[i].impulse);
      for (int k = 0; k < 2; ++k) {
        WideRow& row = rows[2 * i + k];
        const Wide vt = Along(v, t[k], row);
        const Wide old = L(row.impulse);
        // std::clamp(x, lo, hi) = x < lo ? lo : (hi < x ? hi : x) for lo <=
        // hi, which is Min(hi, Max(lo, x)) with the lanes' rules, bit for bit.
        const Wide impulse = lanes::Min(bound, lanes::Max(-bound, old - L(row.mass) * vt));
        S(row.impulse, impulse);
        const Wide delta = impulse - old;
        if (track) largest = lanes::Max(largest, Change(delta, row));
        Apply(v, delta, t[k], row, invMassA, invMassB);
      }
    }
    Store(bodies, bundle, v);
  }
  return track ? Largest(largest) : 0.0;
}

}  // namespace talus
