// The libccd oracle: Talus hulls (and boxes, which are hulls) placed by a
// Transform, handed to libccd's GJK, MPR and GJK+EPA through support
// functions, with the answers in Talus's conventions (normal from B towards
// A, depth positive when penetrating).
//
// libccd (Daniel Fiser, Debian libccd-dev 2.1) is built with CCD_DOUBLE, so
// nothing is rounded to float on the way. It is an imperfect oracle: GJK
// may fail or answer NaN near face-touching contact, EPA may not converge
// near touching, MPR's depth and direction are a point on the portal, not
// the minimum. Every answer therefore carries a status, and the validation
// counts oracle failures apart from disagreements.
#pragma once

#include "talus/hull.h"
#include "talus/math.h"
#include "talus/transform.h"

namespace talus::reference {

/// A hull placed in the world, as libccd sees it: only its support mapping
/// (brute force over the vertices, exact) and its centre (the vertex mean,
/// for MPR). The hull must outlive the object.
struct CcdObject {
  const Hull* hull = nullptr;
  Transform transform;

  /// The world vertex farthest along the world direction `direction`
  /// (ties: the lowest vertex index).
  [[nodiscard]] Vec3 Support(const Vec3& direction) const;
  /// The world position of the mean of the vertices (inside the hull).
  [[nodiscard]] Vec3 Center() const;
};

/// libccd's tolerances and iteration cap (ccd_t). Defaults: tighter than
/// libccd's own (1e-4 m for EPA and MPR), so the oracle is at its best on
/// metre-sized shapes, and a finite iteration cap (libccd's default is
/// unbounded) so that a non-converging query ends and is counted.
struct CcdSettings {
  unsigned long maxIterations = 1000;  ///< per query, > 0
  double epaTolerance = 1e-6;          ///< metres, > 0
  double mprTolerance = 1e-6;          ///< metres, > 0
  double distTolerance = 1e-9;         ///< metres, > 0 (GJK distance)
};

/// How a libccd query ended.
enum class CcdStatus {
  Ok,         ///< an answer with finite numbers
  Failed,     ///< libccd returned an error (-2: out of memory)
  NotFinite,  ///< libccd answered but depth, direction or point is NaN/Inf
};

/// One libccd answer in Talus's conventions.
struct CcdAnswer {
  CcdStatus status = CcdStatus::Ok;
  bool intersecting = false;   ///< libccd's verdict
  double depth = 0.0;          ///< metres, >= 0 (penetration queries only)
  Vec3 normal = Vec3::Zero();  ///< unit, from B towards A (penetration queries only)
  Vec3 point = Vec3::Zero();   ///< world contact position (penetration queries only)
};

/// ccdGJKIntersect: the verdict only.
CcdAnswer CcdGjkIntersect(const CcdObject& a, const CcdObject& b, const CcdSettings& settings = {});
/// ccdMPRIntersect: the verdict only.
CcdAnswer CcdMprIntersect(const CcdObject& a, const CcdObject& b, const CcdSettings& settings = {});
/// ccdGJKPenetration: GJK then EPA; depth, normal and point when intersecting.
CcdAnswer CcdGjkPenetration(const CcdObject& a, const CcdObject& b, const CcdSettings& settings = {});
/// ccdMPRPenetration: depth, normal and point from the final portal.
CcdAnswer CcdMprPenetration(const CcdObject& a, const CcdObject& b, const CcdSettings& settings = {});

}  // namespace talus::reference
