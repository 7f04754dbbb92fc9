// libccd through support functions. libccd calls back with a `const void*`
// object; ours is a CcdObject. Its direction "dir" of a penetration is the
// one obj2 (B) must be moved along by `depth` to separate the pair, so the
// Talus normal (B towards A, the way A is pushed) is -dir.
#include "talus/reference/ccd_oracle.h"

#include <ccd/ccd.h>

#include <cassert>
#include <cmath>
#include <limits>

namespace talus::reference {
namespace {

Vec3 ToVec3(const ccd_vec3_t& v) { return {v.v[0], v.v[1], v.v[2]}; }

void Support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const Vec3 p = static_cast<const CcdObject*>(object)->Support(ToVec3(*direction));
  ccdVec3Set(out, p.x(), p.y(), p.z());
}

void Center(const void* object, ccd_vec3_t* out) {
  const Vec3 c = static_cast<const CcdObject*>(object)->Center();
  ccdVec3Set(out, c.x(), c.y(), c.z());
}

ccd_t MakeCcd(const CcdSettings& settings) {
  assert(settings.maxIterations > 0 && settings.epaTolerance > 0.0 && settings.mprTolerance > 0.0 &&
         settings.distTolerance > 0.0);
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = Support;
  ccd.support2 = Support;
  ccd.center1 = Center;
  ccd.center2 = Center;
  ccd.max_iterations = settings.maxIterations;
  ccd.epa_tolerance = settings.epaTolerance;
  ccd.mpr_tolerance = settings.mprTolerance;
  ccd.dist_tolerance = settings.distTolerance;
  return ccd;
}

// A penetration return code (0 intersecting, -1 separated, -2 error) and
// its outputs in Talus's conventions.
CcdAnswer FromPenetration(int code, double depth, const ccd_vec3_t& dir, const ccd_vec3_t& pos) {
  CcdAnswer answer;
  if (code == -1) return answer;
  if (code != 0) {
    answer.status = CcdStatus::Failed;
    return answer;
  }
  answer.intersecting = true;
  answer.depth = depth;
  answer.normal = -ToVec3(dir);
  answer.point = ToVec3(pos);
  if (!std::isfinite(depth) || !answer.normal.allFinite() || !answer.point.allFinite()) {
    answer.status = CcdStatus::NotFinite;
    return answer;
  }
  const double length = answer.normal.norm();
  if (length > 0.0) answer.normal /= length;
  return answer;
}

}  // namespace

Vec3 CcdObject::Support(const Vec3& direction) const {
  assert(hull != nullptr);
  const Vec3 local = transform.RotateInverse(direction);
  const auto vertices = hull->Vertices();
  std::size_t best = 0;
  double bestValue = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const double value = local.dot(vertices[i]);
    if (value > bestValue) {
      bestValue = value;
      best = i;
    }
  }
  return transform.Apply(vertices[best]);
}

Vec3 CcdObject::Center() const {
  assert(hull != nullptr);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : hull->Vertices()) sum += v;
  return transform.Apply(sum / static_cast<double>(hull->VertexCount()));
}

CcdAnswer CcdGjkIntersect(const CcdObject& a, const CcdObject& b, const CcdSettings& settings) {
  const ccd_t ccd = MakeCcd(settings);
  return {.intersecting = ccdGJKIntersect(&a, &b, &ccd) != 0};
}

CcdAnswer CcdMprIntersect(const CcdObject& a, const CcdObject& b, const CcdSettings& settings) {
  const ccd_t ccd = MakeCcd(settings);
  return {.intersecting = ccdMPRIntersect(&a, &b, &ccd) != 0};
}

CcdAnswer CcdGjkPenetration(const CcdObject& a, const CcdObject& b, const CcdSettings& settings) {
  const ccd_t ccd = MakeCcd(settings);
  ccd_real_t depth = 0.0;
  ccd_vec3_t dir;
  ccd_vec3_t pos;
  ccdVec3Set(&dir, 0.0, 0.0, 0.0);
  ccdVec3Set(&pos, 0.0, 0.0, 0.0);
  const int code = ccdGJKPenetration(&a, &b, &ccd, &depth, &dir, &pos);
  return FromPenetration(code, depth, dir, pos);
}

CcdAnswer CcdMprPenetration(const CcdObject& a, const CcdObject& b, const CcdSettings& settings) {
  const ccd_t ccd = MakeCcd(settings);
  ccd_real_t depth = 0.0;
  ccd_vec3_t dir;
  ccd_vec3_t pos;
  ccdVec3Set(&dir, 0.0, 0.0, 0.0);
  ccdVec3Set(&pos, 0.0, 0.0, 0.0);
  const int code = ccdMPRPenetration(&a, &b, &ccd, &depth, &dir, &pos);
  return FromPenetration(code, depth, dir, pos);
}

}  // namespace talus::reference
