// Greedy area-maximising contact reduction (see manifold_reduction.h).
#include "collision/manifold_reduction.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace talus {
namespace {

// A point in the contact plane (plain, so sorting stays simple).
struct Vec2 {
  double x;
  double y;
};

double Cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Area of the convex hull of a few 2D points (Andrew's monotone chain).
double HullArea(std::array<Vec2, kMaxManifoldPoints + 1> points, std::size_t count) {
  if (count < 3) return 0.0;
  std::sort(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(count),
            [](const Vec2& l, const Vec2& r) { return l.x < r.x || (l.x == r.x && l.y < r.y); });
  std::array<Vec2, 2 * (kMaxManifoldPoints + 1)> chain;
  std::size_t k = 0;
  const auto push = [&](const Vec2& p, std::size_t floor) {
    while (k >= floor + 2 && Cross2(chain[k - 2], chain[k - 1], p) <= 0.0) --k;
    if (k < chain.size()) chain[k++] = p;
  };
  for (std::size_t i = 0; i < count; ++i) push(points[i], 0);
  const std::size_t lower = k - 1;
  for (std::size_t i = count - 1; i-- > 0;) push(points[i], lower);
  double twiceArea = 0.0;
  for (std::size_t i = 0; i + 1 < k; ++i)
    twiceArea += chain[i].x * chain[i + 1].y - chain[i + 1].x * chain[i].y;
  return 0.5 * std::abs(twiceArea);
}

}  // namespace

double ContactPolygonArea(std::span<const Vec3> points, const Vec3& normal) {
  assert(points.size() <= kMaxManifoldPoints + 1);
  const Vec3 u = normal.unitOrthogonal();
  const Vec3 v = normal.cross(u);
  std::array<Vec2, kMaxManifoldPoints + 1> planar{};
  for (std::size_t i = 0; i < points.size(); ++i) planar[i] = {u.dot(points[i]), v.dot(points[i])};
  return HullArea(planar, points.size());
}

int ReduceContactPoints(std::span<const ContactPoint> candidates, const Vec3& normal, int maxCount,
                        ContactPoint* out) {
  assert(maxCount >= 1 && maxCount <= kMaxManifoldPoints);
  const int count = static_cast<int>(candidates.size());
  if (count <= maxCount) {
    std::copy(candidates.begin(), candidates.end(), out);
    return count;
  }
  // A basis of the contact plane.
  const Vec3 u = normal.unitOrthogonal();
  const Vec3 v = normal.cross(u);
  const auto planar = [&](int i) {
    const Vec3& p = candidates[static_cast<std::size_t>(i)].position;
    return Vec2{u.dot(p), v.dot(p)};
  };

  std::array<int, kMaxManifoldPoints> chosen{};
  std::array<Vec2, kMaxManifoldPoints + 1> kept{};
  const auto isChosen = [&](int i, int n) {
    return std::find(chosen.begin(), chosen.begin() + n, i) != chosen.begin() + n;
  };

  // 1: the deepest point.
  int first = 0;
  for (int i = 1; i < count; ++i) {
    if (candidates[static_cast<std::size_t>(i)].depth > candidates[static_cast<std::size_t>(first)].depth)
      first = i;
  }
  chosen[0] = first;
  kept[0] = planar(first);
  int n = 1;

  // 2: the point farthest from it in the plane.
  int second = -1;
  double farthest = -1.0;
  for (int i = 0; i < count; ++i) {
    if (i == first) continue;
    const Vec2 q = planar(i);
    const double d = (q.x - kept[0].x) * (q.x - kept[0].x) + (q.y - kept[0].y) * (q.y - kept[0].y);
    if (d > farthest) {
      farthest = d;
      second = i;
    }
  }
  chosen[n] = second;
  kept[n++] = planar(second);

  // 3..maxCount: the point that grows the kept hull's area the most.
  while (n < maxCount) {
    int best = -1;
    double bestArea = -1.0;
    for (int i = 0; i < count; ++i) {
      if (isChosen(i, n)) continue;
      kept[static_cast<std::size_t>(n)] = planar(i);
      const double area = HullArea(kept, static_cast<std::size_t>(n) + 1);
      if (area > bestArea) {
        bestArea = area;
        best = i;
      }
    }
    chosen[static_cast<std::size_t>(n)] = best;
    kept[static_cast<std::size_t>(n)] = planar(best);
    ++n;
  }
  for (int i = 0; i < n; ++i)
    out[i] = candidates[static_cast<std::size_t>(chosen[static_cast<std::size_t>(i)])];
  return n;
}

}  // namespace talus
