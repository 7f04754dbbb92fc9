// The validation run (see sat_check.h). For each pair: the truth first,
// then each method in a fixed order; the per-method samples are reduced to
// percentiles at the end. Methods are a table of small adaptors that all
// answer in one form (Answer), so the comparison code is written once.
#include "sat_check.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "collision/collide.h"
#include "collision/polyhedron_manifold.h"
#include "collision/sat.h"
#include "talus/harness/support/number_text.h"
#include "talus/pair_query.h"
#include "talus/reference/bullet_narrow_phase.h"
#include "talus/reference/ccd_oracle.h"
#include "talus/reference/minkowski_truth.h"

namespace talus::validation {
namespace {

using reference::BulletHullShape;
using reference::BulletNarrowPhaseMethod;
using reference::CcdAnswer;
using reference::CcdObject;
using reference::CcdStatus;

// One method's answer on one pair; depth and normal only when the method
// gives them, points in world space.
struct Answer {
  bool ok = true;
  bool intersecting = false;
  double depth = 0.0;
  Vec3 normal = Vec3::Zero();
  std::vector<Vec3> points;
  std::vector<double> pointDepths;  // Talus only: each point's own depth
  std::string error;                // Talus only: the pair query's error, when !ok
};

// What a method needs about a pair, built once per pair.
struct PairContext {
  const ShapePair* pair = nullptr;
  CcdObject ccdA;
  CcdObject ccdB;
  const BulletHullShape* bulletA = nullptr;
  const BulletHullShape* bulletB = nullptr;
};

struct Method {
  std::string name;
  std::string family;
  bool givesDepth = false;
  bool givesPoints = false;
  bool writeUpPoints = false;  // Talus's WriteUp manifold (its own 5 mm rule)
  // Prepares (untimed) and returns the timed query.
  std::function<std::function<Answer()>(const PairContext&)> prepare;
};

Method TalusMethod(SatMode satMode, ManifoldMode manifoldMode, bool cached) {
  std::string name = std::string("talus-") + (satMode == SatMode::Full ? "full" : "pruned") +
                     (manifoldMode == ManifoldMode::WriteUp ? "-writeup" : "-clipped") +
                     (cached ? "-cached" : "");
  const NarrowPhaseSettings settings{.satMode = satMode, .manifoldMode = manifoldMode, .useSatCache = cached};
  const bool writeUp = manifoldMode == ManifoldMode::WriteUp;
  if (!cached) {
    // The public pair query, as a user calls it.
    return {name, "talus", true, true, writeUp, [settings](const PairContext& c) {
              return std::function<Answer()>([settings, &c]() {
                const Result<PairContact> contact =
                    CollideShapes(c.pair->a, c.pair->xfA, c.pair->b, c.pair->xfB, settings);
                Answer answer;
                answer.ok = contact.Ok();
                if (!answer.ok) {
                  answer.error = contact.GetError().message;
                  return answer;
                }
                if (!contact.Value().touching) return answer;
                const PairContact& pc = contact.Value();
                answer.intersecting = true;
                answer.depth = -pc.separation;
                answer.normal = pc.normal;
                for (int i = 0; i < pc.pointCount; ++i) {
                  answer.points.push_back(pc.points[static_cast<std::size_t>(i)].position);
                  answer.pointDepths.push_back(pc.points[static_cast<std::size_t>(i)].depth);
                }
                return answer;
              });
            }};
  }
  // The pair query has no cache; the cached modes call the dispatch the
  // World uses, with the cache as a resting pair has it: filled by the
  // previous query.
  return {name, "talus", true, true, writeUp, [settings](const PairContext& c) {
            SatCache primed;
            ContactManifold scratch{};
            Collide(c.pair->a, c.pair->xfA, c.pair->b, c.pair->xfB, settings, &primed, nullptr, &scratch);
            return std::function<Answer()>([settings, primed, &c]() {
              SatCache cache = primed;
              ContactManifold manifold{};
              Answer answer;
              answer.intersecting = Collide(c.pair->a, c.pair->xfA, c.pair->b, c.pair->xfB, settings, &cache,
                                            nullptr, &manifold);
              if (answer.intersecting) {
                answer.depth = manifold.depth;
                answer.normal = manifold.normal;
                for (int i = 0; i < manifold.pointCount; ++i) {
                  answer.points.push_back(manifold.points[static_cast<std::size_t>(i)].position);
                  answer.pointDepths.push_back(manifold.points[static_cast<std::size_t>(i)].depth);
                }
              }
              return answer;
            });
          }};
}

Answer FromCcd(const CcdAnswer& ccd) {
  Answer answer;
  answer.ok = ccd.status == CcdStatus::Ok;
  answer.intersecting = ccd.intersecting;
  answer.depth = ccd.depth;
  answer.normal = ccd.normal;
  if (ccd.intersecting && answer.ok) answer.points.push_back(ccd.point);
  return answer;
}

Method CcdMethod(const std::string& name, bool givesDepth,
                 CcdAnswer (*query)(const CcdObject&, const CcdObject&, const reference::CcdSettings&)) {
  return {name, "libccd", givesDepth, givesDepth, false, [query](const PairContext& c) {
            return std::function<Answer()>([query, &c]() { return FromCcd(query(c.ccdA, c.ccdB, {})); });
          }};
}

Method BulletMethod(const std::string& name, BulletNarrowPhaseMethod which) {
  return {name, "bullet", true, true, false, [which](const PairContext& c) {
            return std::function<Answer()>([which, &c]() {
              const reference::BulletAnswer bullet =
                  BulletPairQuery(*c.bulletA, c.pair->xfA, *c.bulletB, c.pair->xfB, which);
              Answer answer;
              answer.ok = bullet.ok;
              answer.intersecting = bullet.intersecting;
              answer.depth = bullet.intersecting ? -bullet.signedDistance : 0.0;
              answer.normal = bullet.normal;
              if (bullet.ok && bullet.intersecting) answer.points.push_back(bullet.point);
              return answer;
            });
          }};
}

std::vector<Method> AllMethods() {
  std::vector<Method> methods;
  for (const bool cached : {false, true}) {
    for (const SatMode mode : {SatMode::Full, SatMode::GaussMapPruned}) {
      for (const ManifoldMode manifold : {ManifoldMode::WriteUp, ManifoldMode::Clipped})
        methods.push_back(TalusMethod(mode, manifold, cached));
    }
  }
  methods.push_back(CcdMethod("ccd-gjk-intersect", false, reference::CcdGjkIntersect));
  methods.push_back(CcdMethod("ccd-mpr-intersect", false, reference::CcdMprIntersect));
  methods.push_back(CcdMethod("ccd-gjk-penetration", true, reference::CcdGjkPenetration));
  methods.push_back(CcdMethod("ccd-mpr-penetration", true, reference::CcdMprPenetration));
  methods.push_back(BulletMethod("bullet-gjk-pair-detector", BulletNarrowPhaseMethod::GjkPairDetector));
  methods.push_back(BulletMethod("bullet-gjkepa2", BulletNarrowPhaseMethod::GjkEpa2));
  return methods;
}

std::vector<Vec3> WorldVertices(const Shape& shape, const Transform& xf) {
  std::vector<Vec3> out;
  for (const Vec3& v : shape.GetHull().Vertices()) out.push_back(xf.Apply(v));
  return out;
}

double MaxAlong(const std::vector<Vec3>& points, const Vec3& direction) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) best = std::max(best, direction.dot(p));
  return best;
}

// How far `point` lies outside the shape (m, 0 inside): the largest
// signed distance to its face planes.
double Outside(const Shape& shape, const Transform& xf, const Vec3& point) {
  const Vec3 local = xf.ApplyInverse(point);
  double worst = -std::numeric_limits<double>::infinity();
  for (const HullFace& face : shape.GetHull().Faces())
    worst = std::max(worst, face.plane.SignedDistance(local));
  return std::max(worst, 0.0);
}

Distribution Summarise(std::vector<double> values) {
  Distribution d;
  d.count = static_cast<int>(values.size());
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  const auto at = [&values](double q) {
    const auto i = static_cast<std::size_t>(std::floor(q * static_cast<double>(values.size() - 1) + 0.5));
    return values[std::min(i, values.size() - 1)];
  };
  d.p50 = at(0.5);
  d.p90 = at(0.9);
  d.p99 = at(0.99);
  d.max = values.back();
  return d;
}

void KeepWorst(std::vector<CaseRecord>& worst, CaseRecord record, int keep) {
  worst.push_back(std::move(record));
  std::stable_sort(worst.begin(), worst.end(),
                   [](const CaseRecord& l, const CaseRecord& r) { return l.value > r.value; });
  if (static_cast<int>(worst.size()) > keep) worst.resize(static_cast<std::size_t>(keep));
}

struct FamilySamples {
  std::vector<double> depthError;
  std::vector<double> normalAngle;
  std::vector<double> normalExcess;
  std::vector<double> pointOutside;
};

struct Samples {
  std::vector<double> depthError;
  std::vector<double> normalAngle;
  std::vector<double> normalExcess;
  std::vector<double> pointOutside;
  std::vector<double> timeNs;
  std::vector<FamilySamples> families = std::vector<FamilySamples>(kFamilyCount);
};

double LargestCoordinate(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double largest = 0.0;
  for (const Vec3& v : a) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  for (const Vec3& v : b) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  return largest;
}

std::string Sci(double value) { return harness::FormatPrintf("%.3e", value); }

}  // namespace

int ExitStatus(const SatCheckReport& report) {
  if (!report.truthBroken.empty()) return kExitTruthBroken;
  return report.failures.empty() ? kExitPassed : kExitBoundBroken;
}

double BoxPairSignedDistance(const Vec3& halfA, const Vec3& halfB, const Vec3& offset) {
  const Vec3 overlap = halfA + halfB - offset.cwiseAbs();
  if (overlap.minCoeff() >= 0.0) return -overlap.minCoeff();
  return overlap.cwiseMin(0.0).norm();
}

Result<std::uint64_t> ParseSeed(std::string_view text) {
  const std::string shown = text.size() > 40 ? std::string(text.substr(0, 40)) + "..." : std::string(text);
  const bool digits =
      !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  std::uint64_t seed = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), seed);
  if (!digits || error != std::errc() || end != text.data() + text.size()) {
    std::string escaped;
    for (const char c : shown) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte >= 0x20 && byte < 0x7f) {
        escaped += c;
      } else {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02X", byte);
        escaped += hex;
      }
    }
    return Error{"--seed \"" + escaped + "\": need a whole number from 0 to 18446744073709551615" +
                 (error == std::errc::result_out_of_range ? " (too large)" : "")};
  }
  return seed;
}

Result<SatCheckReport> RunSatCheck(const SatCheckSettings& settings) {
  if (settings.pairs < 1 || settings.pairs > kMaxPairs)
    return Error{"pairs: must be between 1 and " + std::to_string(kMaxPairs) + ", got " +
                 std::to_string(settings.pairs)};
  if (!(settings.touchingBand >= 0.0)) return Error{"touchingBand: must be >= 0"};
  if (!(settings.pointTolerance >= 0.0)) return Error{"pointTolerance: must be >= 0"};
  if (settings.timingRepeats < 0) return Error{"timingRepeats: must be >= 0"};
  if (settings.worstCases < 0) return Error{"worstCases: must be >= 0"};

  SatCheckReport report;
  report.settings = settings;
  report.placementCounts.assign(4, 0);
  report.alignmentCounts.assign(3, 0);
  const std::vector<ShapePair> pairs = GeneratePairs(settings.pairs, settings.seed);
  report.pairCount = static_cast<int>(pairs.size());
  const std::vector<Method> methods = AllMethods();
  for (const Method& m : methods) {
    MethodReport out;
    out.name = m.name;
    out.family = m.family;
    out.givesDepth = m.givesDepth;
    out.givesPoints = m.givesPoints;
    report.methods.push_back(std::move(out));
  }
  std::vector<Samples> samples(methods.size());

  for (const ShapePair& pair : pairs) {
    ++report.placementCounts[static_cast<std::size_t>(pair.placement)];
    ++report.alignmentCounts[static_cast<std::size_t>(pair.alignment)];
    const Hull& hullA = pair.a.GetHull();
    const Hull& hullB = pair.b.GetHull();
    Result<reference::PenetrationTruth> truthResult =
        reference::ComputePenetrationTruth(hullA, pair.xfA, hullB, pair.xfB);
    if (!truthResult)
      return Error{"pair " + std::to_string(pair.index) + ": " + truthResult.GetError().message};
    const reference::PenetrationTruth& truth = truthResult.Value();
    const std::string configuration = Describe(pair);
    if (settings.checkWithQhull) {
      ++report.truth.qhullChecks;
      Result<bool> check = reference::CheckMinkowskiWithQhull(hullA, pair.xfA, hullB, pair.xfB);
      if (!check) {
        ++report.truth.qhullMismatches;
        const std::string message = "pair " + std::to_string(pair.index) + ": " + check.GetError().message;
        report.truth.qhullMessages.push_back(message);
        report.truthBroken.push_back("Minkowski hull (qhull) vs BuildHull, " + message);
      }
    }
    const std::vector<Vec3> verticesA = WorldVertices(pair.a, pair.xfA);
    const std::vector<Vec3> verticesB = WorldVertices(pair.b, pair.xfB);
    // The pair's bounds (sat_check.h): round-off of its world coordinates,
    // the exactness asked, and the SAT's stated preference band.
    const double roundOff =
        kRoundOffUlps * std::numeric_limits<double>::epsilon() * LargestCoordinate(verticesA, verticesB);
    // The closed form needs the same rotation (not the parallel families'
    // twists); far pairs are left out, their truth carries the round-off
    // of 1e5 m coordinates.
    if (pair.alignment == Alignment::Face && pair.a.Type() == ShapeType::Box &&
        pair.b.Type() == ShapeType::Box && pair.xfA.rotation.coeffs() == pair.xfB.rotation.coeffs() &&
        pair.family != Family::Far) {
      const Vec3 offset = pair.xfA.RotateInverse(pair.xfB.position - pair.xfA.position);
      const double closed = BoxPairSignedDistance(pair.a.HalfExtents(), pair.b.HalfExtents(), offset);
      ++report.truth.boxClosedFormChecks;
      report.truth.boxClosedFormMaxError =
          std::max(report.truth.boxClosedFormMaxError, std::abs(closed - truth.signedDistance));
      if ((closed <= 0.0) != truth.intersecting && std::abs(closed) > settings.touchingBand) {
        ++report.truth.boxClosedFormVerdictMismatches;
        report.truthBroken.push_back("box closed form " + Sci(closed) + " m vs truth " +
                                     Sci(truth.signedDistance) + " m, verdicts differ, on pair " +
                                     std::to_string(pair.index));
      } else if (std::abs(closed - truth.signedDistance) > roundOff) {
        // Beyond the round-off of the pair's coordinates (kRoundOffUlps).
        report.truthBroken.push_back("box closed form " + Sci(closed) + " m vs truth " +
                                     Sci(truth.signedDistance) + " m on pair " + std::to_string(pair.index));
      }
    }
    const double exact = kExactRelative * pair.size + roundOff;
    const double depthBound = AxisPreferenceBand(hullA, hullB) + exact;
    const double pointBound = settings.pointTolerance * pair.size + roundOff;
    const bool inBand = std::abs(truth.signedDistance) < settings.touchingBand * pair.size + roundOff;
    const auto familyIndex = static_cast<std::size_t>(pair.family);
    if (truth.intersecting) ++report.truth.intersecting;
    if (inBand) ++report.truth.touchingBand;
    if (truth.intersecting && truth.minimumFaces > 1) ++report.truth.tiedMinimum;

    const BulletHullShape bulletA(hullA);
    const BulletHullShape bulletB(hullB);
    const PairContext context{.pair = &pair,
                              .ccdA = {.hull = &hullA, .transform = pair.xfA},
                              .ccdB = {.hull = &hullB, .transform = pair.xfB},
                              .bulletA = &bulletA,
                              .bulletB = &bulletB};
    PairRecord record{.index = pair.index,
                      .configuration = configuration,
                      .trueSignedDistance = truth.signedDistance,
                      .trueNormal = truth.normal,
                      .results = {}};

    for (std::size_t m = 0; m < methods.size(); ++m) {
      MethodReport& out = report.methods[m];
      Samples& sample = samples[m];
      const std::function<Answer()> query = methods[m].prepare(context);
      const Answer answer = query();
      PairMethodResult result{.ok = answer.ok,
                              .intersecting = answer.intersecting,
                              .depth = answer.depth,
                              .normalExcess = 0.0,
                              .points = static_cast<int>(answer.points.size()),
                              .timeNs = 0.0};
      if (settings.timingRepeats > 0) {
        const auto start = std::chrono::steady_clock::now();
        int sink = 0;  // keeps the repeated queries from being optimised away
        for (int r = 0; r < settings.timingRepeats; ++r) sink += query().intersecting ? 1 : 0;
        volatile int keep = sink;
        static_cast<void>(keep);
        const auto elapsed = std::chrono::steady_clock::now() - start;
        result.timeNs =
            static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count()) /
            settings.timingRepeats;
        sample.timeNs.push_back(result.timeNs);
      }
      const CaseRecord base{.pair = pair.index,
                            .configuration = configuration,
                            .trueSignedDistance = truth.signedDistance,
                            .methodIntersecting = answer.intersecting,
                            .value = 0.0};
      if (!answer.ok) {
        // A Talus mode that returns an error on a valid pair fails the gate.
        if (out.family == "talus" && out.oracleFailures == 0)
          report.failures.push_back(out.name + ": error on pair " + std::to_string(pair.index) + " (" +
                                    configuration + "): " + answer.error);
        ++out.oracleFailures;
        record.results.push_back(result);
        continue;
      }
      if (answer.intersecting == truth.intersecting) {
        ++out.agree;
      } else if (inBand) {
        ++out.touchingBandDisagree;
      } else if (out.family == "talus") {
        if (out.disagree++ == 0)
          report.failures.push_back(out.name + ": wrong verdict on pair " + std::to_string(pair.index) +
                                    " (" + configuration + ", true distance " + Sci(truth.signedDistance) +
                                    " m)");
        out.disagreements.push_back(base);
      } else {
        // A peer's wrong verdict is an oracle failure, listed all the same.
        ++out.oracleFailures;
        out.disagreements.push_back(base);
      }
      const bool talus = out.family == "talus";
      FamilySamples& familySample = sample.families[familyIndex];
      if (methods[m].givesDepth && answer.intersecting && truth.intersecting && !inBand) {
        const double depthError = std::abs(answer.depth - truth.Depth());
        sample.depthError.push_back(depthError);
        familySample.depthError.push_back(depthError);
        if (talus && depthError > depthBound && out.depthOverBound++ == 0)
          report.failures.push_back(out.name + ": depth error " + Sci(depthError) + " m > bound " +
                                    Sci(depthBound) + " m on pair " + std::to_string(pair.index) + " (" +
                                    configuration + ")");
        CaseRecord worst = base;
        worst.value = depthError;
        KeepWorst(out.worstDepth, worst, settings.worstCases);
        const Vec3 n = answer.normal.normalized();
        const double overlap = MaxAlong(verticesB, n) + MaxAlong(verticesA, -n);
        result.normalExcess = overlap - truth.Depth();
        sample.normalExcess.push_back(std::max(result.normalExcess, 0.0));
        familySample.normalExcess.push_back(std::max(result.normalExcess, 0.0));
        if (talus && result.normalExcess > depthBound && out.normalOverBound++ == 0)
          report.failures.push_back(out.name + ": normal excess " + Sci(result.normalExcess) + " m > bound " +
                                    Sci(depthBound) + " m on pair " + std::to_string(pair.index) + " (" +
                                    configuration + ")");
        worst.value = result.normalExcess;
        KeepWorst(out.worstNormal, worst, settings.worstCases);
        if (truth.minimumFaces == 1) {
          const double angle = std::acos(std::clamp(n.dot(truth.normal), -1.0, 1.0));
          sample.normalAngle.push_back(angle);
          familySample.normalAngle.push_back(angle);
        }
      }
      if (talus && answer.intersecting && !answer.pointDepths.empty()) {
        // No point is deeper than the manifold's depth (the projections'
        // overlap). The deepest point carries it unless the SAT's deepest
        // vertex lies outside the other shape; shallower is counted, not
        // gated (sat_check.h).
        const double deepest = *std::max_element(answer.pointDepths.begin(), answer.pointDepths.end());
        const double bound = roundOff + kExactRelative * pair.size;
        if (deepest < answer.depth - bound) ++out.deepestPointShallower;
        if (deepest > answer.depth + bound && out.deepestPointDeeper++ == 0)
          report.failures.push_back(out.name + ": deepest point " + Sci(deepest) + " m, manifold depth " +
                                    Sci(answer.depth) + " m on pair " + std::to_string(pair.index) + " (" +
                                    configuration + ")");
      }
      if (methods[m].givesPoints && !inBand) {
        for (const Vec3& p : answer.points) {
          const double outsideA = Outside(pair.a, pair.xfA, p);
          const double outsideB = Outside(pair.b, pair.xfB, p);
          const double outside = std::max(outsideA, outsideB);
          sample.pointOutside.push_back(outside);
          familySample.pointOutside.push_back(outside);
          // Misplaced: farther out of either shape than the true depth
          // (a point midway between the surfaces of a contact patch is
          // within that of both) plus the tolerance.
          if (outside > pointBound + truth.Depth()) ++out.pointsOverTolerance;
          if (!talus) continue;
          // Outside either shape beyond round-off: gated for the Clipped
          // modes (issue 26: every point inside both shapes), measured for
          // WriteUp, whose rule takes vertices near the other shape.
          if (outside > roundOff && out.pointsOutsideEither++ == 0 && !methods[m].writeUpPoints)
            report.failures.push_back(out.name + ": a point " + Sci(outside) + " m outside a shape (bound " +
                                      Sci(roundOff) + " m) on pair " + std::to_string(pair.index) + " (" +
                                      configuration + ")");
          // Outside both: gated. The write-up's rule takes vertices up to
          // its tolerance (WriteUpTolerance) outside the other shape by design.
          const double bothBound =
              pointBound + (methods[m].writeUpPoints ? WriteUpTolerance(hullA, hullB) : 0.0);
          if (std::min(outsideA, outsideB) > bothBound && out.pointsOutsideBoth++ == 0)
            report.failures.push_back(out.name + ": a point " + Sci(std::min(outsideA, outsideB)) +
                                      " m outside both shapes on pair " + std::to_string(pair.index) + " (" +
                                      configuration + ")");
        }
      }
      record.results.push_back(result);
    }
    report.pairs.push_back(std::move(record));
  }

  for (std::size_t m = 0; m < methods.size(); ++m) {
    MethodReport& out = report.methods[m];
    out.depthError = Summarise(samples[m].depthError);
    out.normalAngle = Summarise(samples[m].normalAngle);
    out.normalExcess = Summarise(samples[m].normalExcess);
    out.pointOutside = Summarise(samples[m].pointOutside);
    out.timeNs = Summarise(samples[m].timeNs);
    for (int f = 0; f < kFamilyCount; ++f) {
      const FamilySamples& fs = samples[m].families[static_cast<std::size_t>(f)];
      out.families.push_back({.family = ToString(static_cast<Family>(f)),
                              .depthError = Summarise(fs.depthError),
                              .normalAngle = Summarise(fs.normalAngle),
                              .normalExcess = Summarise(fs.normalExcess),
                              .pointOutside = Summarise(fs.pointOutside)});
    }
  }
  return report;
}

}  // namespace talus::validation
