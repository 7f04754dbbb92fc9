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
#include <optional>

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

namespace {

// Why the settings cannot run, naming the field; "" when they can.
std::string SettingsProblem(const SatCheckSettings& settings) {
  if (settings.pairs < 1 || settings.pairs > kMaxPairs)
    return "pairs: must be between 1 and " + std::to_string(kMaxPairs) + ", got " +
           std::to_string(settings.pairs);
  if (!(settings.touchingBand >= 0.0)) return "touchingBand: must be >= 0";
  if (!(settings.pointTolerance >= 0.0)) return "pointTolerance: must be >= 0";
  if (settings.timingRepeats < 0) return "timingRepeats: must be >= 0";
  if (settings.worstCases < 0) return "worstCases: must be >= 0";
  return {};
}

// An empty report: the settings, the counters, one MethodReport per method.
SatCheckReport StartReport(const SatCheckSettings& settings, const std::vector<Method>& methods) {
  SatCheckReport report;
  report.settings = settings;
  report.placementCounts.assign(4, 0);
  report.alignmentCounts.assign(3, 0);
  for (const Method& m : methods) {
    MethodReport out;
    out.name = m.name;
    out.family = m.family;
    out.givesDepth = m.givesDepth;
    out.givesPoints = m.givesPoints;
    report.methods.push_back(std::move(out));
  }
  return report;
}

// One pair as every method is judged on it: the truth, the world vertices
// and the pair's bounds (sat_check.h).
struct PairFacts {
  const ShapePair& pair;
  const Hull& hullA;
  const Hull& hullB;
  const reference::PenetrationTruth& truth;
  std::string configuration;
  std::vector<Vec3> verticesA;
  std::vector<Vec3> verticesB;
  double roundOff = 0.0;    // round-off of the pair's world coordinates
  double depthBound = 0.0;  // the SAT's preference band + exactness + round-off
  double pointBound = 0.0;  // the point tolerance + round-off
  bool inBand = false;      // inside the touching band: either verdict is acceptable
};

PairFacts MakePairFacts(const ShapePair& pair, const reference::PenetrationTruth& truth,
                        const SatCheckSettings& settings) {
  PairFacts facts{.pair = pair,
                  .hullA = pair.a.GetHull(),
                  .hullB = pair.b.GetHull(),
                  .truth = truth,
                  .configuration = Describe(pair),
                  .verticesA = WorldVertices(pair.a, pair.xfA),
                  .verticesB = WorldVertices(pair.b, pair.xfB)};
  // The pair's bounds (sat_check.h): round-off of its world coordinates,
  // the exactness asked, and the SAT's stated preference band.
  facts.roundOff = kRoundOffUlps * std::numeric_limits<double>::epsilon() *
                   LargestCoordinate(facts.verticesA, facts.verticesB);
  const double exact = kExactRelative * pair.size + facts.roundOff;
  facts.depthBound = AxisPreferenceBand(facts.hullA, facts.hullB) + exact;
  facts.pointBound = settings.pointTolerance * pair.size + facts.roundOff;
  facts.inBand = std::abs(truth.signedDistance) < settings.touchingBand * pair.size + facts.roundOff;
  return facts;
}

// The truth's Minkowski difference against qhull's.
void CheckTruthWithQhull(const ShapePair& pair, SatCheckReport& report) {
  ++report.truth.qhullChecks;
  Result<bool> check =
      reference::CheckMinkowskiWithQhull(pair.a.GetHull(), pair.xfA, pair.b.GetHull(), pair.xfB);
  if (!check) {
    ++report.truth.qhullMismatches;
    const std::string message = "pair " + std::to_string(pair.index) + ": " + check.GetError().message;
    report.truth.qhullMessages.push_back(message);
    report.truthBroken.push_back("Minkowski hull (qhull) vs BuildHull, " + message);
  }
}

// The truth against the closed form of two face-aligned boxes.
void CheckTruthWithBoxClosedForm(const PairFacts& facts, const SatCheckSettings& settings,
                                 SatCheckReport& report) {
  const ShapePair& pair = facts.pair;
  const reference::PenetrationTruth& truth = facts.truth;
  // The closed form needs the same rotation (not the parallel families'
  // twists); far pairs are left out, their truth carries the round-off
  // of 1e5 m coordinates.
  if (!(pair.alignment == Alignment::Face && pair.a.Type() == ShapeType::Box &&
        pair.b.Type() == ShapeType::Box && pair.xfA.rotation.coeffs() == pair.xfB.rotation.coeffs() &&
        pair.family != Family::Far))
    return;
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
  } else if (std::abs(closed - truth.signedDistance) > facts.roundOff) {
    // Beyond the round-off of the pair's coordinates (kRoundOffUlps).
    report.truthBroken.push_back("box closed form " + Sci(closed) + " m vs truth " +
                                 Sci(truth.signedDistance) + " m on pair " + std::to_string(pair.index));
  }
}

// Mean time of one query over `repeats` runs (ns).
double TimeQuery(const std::function<Answer()>& query, int repeats) {
  const auto start = std::chrono::steady_clock::now();
  int sink = 0;  // keeps the repeated queries from being optimised away
  for (int r = 0; r < repeats; ++r) sink += query().intersecting ? 1 : 0;
  volatile int keep = sink;
  static_cast<void>(keep);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  return static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count()) / repeats;
}

// What judging one method's answer on one pair writes to: its report, its
// samples (all pairs and the pair's family) and the run's failures.
struct MethodSink {
  const Method& method;
  MethodReport& out;
  Samples& sample;
  FamilySamples& familySample;
  std::vector<std::string>& failures;
  int worstCases = 0;
  bool Talus() const { return out.family == "talus"; }
  // "<method>: <what> on pair N (configuration)", the form of every gate failure.
  void Fail(const std::string& what, const PairFacts& facts) const {
    failures.push_back(out.name + ": " + what + " on pair " + std::to_string(facts.pair.index) + " (" +
                       facts.configuration + ")");
  }
};

// Counts the verdict against the truth's. A Talus mode that returns an
// error or a wrong verdict outside the band fails the gate; a peer's wrong
// verdict is an oracle failure, listed all the same. False when the
// method failed to answer (nothing more to judge).
bool JudgeVerdict(const Answer& answer, const PairFacts& facts, const CaseRecord& base,
                  const MethodSink& sink) {
  MethodReport& out = sink.out;
  if (!answer.ok) {
    if (sink.Talus() && out.oracleFailures == 0)
      sink.failures.push_back(out.name + ": error on pair " + std::to_string(facts.pair.index) + " (" +
                              facts.configuration + "): " + answer.error);
    ++out.oracleFailures;
    return false;
  }
  if (answer.intersecting == facts.truth.intersecting) {
    ++out.agree;
  } else if (facts.inBand) {
    ++out.touchingBandDisagree;
  } else if (sink.Talus()) {
    if (out.disagree++ == 0)
      sink.failures.push_back(out.name + ": wrong verdict on pair " + std::to_string(facts.pair.index) +
                              " (" + facts.configuration + ", true distance " +
                              Sci(facts.truth.signedDistance) + " m)");
    out.disagreements.push_back(base);
  } else {
    ++out.oracleFailures;
    out.disagreements.push_back(base);
  }
  return true;
}

// Depth error, normal excess and normal angle of a method that gives them,
// on a pair both it and the truth call intersecting, outside the band.
void JudgeDepthAndNormal(const Answer& answer, const PairFacts& facts, const CaseRecord& base,
                         PairMethodResult& result, const MethodSink& sink) {
  const reference::PenetrationTruth& truth = facts.truth;
  MethodReport& out = sink.out;
  const double depthError = std::abs(answer.depth - truth.Depth());
  sink.sample.depthError.push_back(depthError);
  sink.familySample.depthError.push_back(depthError);
  if (sink.Talus() && depthError > facts.depthBound && out.depthOverBound++ == 0)
    sink.Fail("depth error " + Sci(depthError) + " m > bound " + Sci(facts.depthBound) + " m", facts);
  CaseRecord worst = base;
  worst.value = depthError;
  KeepWorst(out.worstDepth, worst, sink.worstCases);
  const Vec3 n = answer.normal.normalized();
  const double overlap = MaxAlong(facts.verticesB, n) + MaxAlong(facts.verticesA, -n);
  result.normalExcess = overlap - truth.Depth();
  sink.sample.normalExcess.push_back(std::max(result.normalExcess, 0.0));
  sink.familySample.normalExcess.push_back(std::max(result.normalExcess, 0.0));
  if (sink.Talus() && result.normalExcess > facts.depthBound && out.normalOverBound++ == 0)
    sink.Fail("normal excess " + Sci(result.normalExcess) + " m > bound " + Sci(facts.depthBound) + " m",
              facts);
  worst.value = result.normalExcess;
  KeepWorst(out.worstNormal, worst, sink.worstCases);
  if (truth.minimumFaces == 1) {
    const double angle = std::acos(std::clamp(n.dot(truth.normal), -1.0, 1.0));
    sink.sample.normalAngle.push_back(angle);
    sink.familySample.normalAngle.push_back(angle);
  }
}

// No point is deeper than the manifold's depth (the projections'
// overlap). The deepest point carries it unless the SAT's deepest vertex
// lies outside the other shape; shallower is counted, not gated
// (sat_check.h).
void JudgeDeepestPoint(const Answer& answer, const PairFacts& facts, const MethodSink& sink) {
  MethodReport& out = sink.out;
  const double deepest = *std::max_element(answer.pointDepths.begin(), answer.pointDepths.end());
  const double bound = facts.roundOff + kExactRelative * facts.pair.size;
  if (deepest < answer.depth - bound) ++out.deepestPointShallower;
  if (deepest > answer.depth + bound && out.deepestPointDeeper++ == 0)
    sink.Fail("deepest point " + Sci(deepest) + " m, manifold depth " + Sci(answer.depth) + " m", facts);
}

// How far each contact point lies outside the shapes.
void JudgePoints(const Answer& answer, const PairFacts& facts, const MethodSink& sink) {
  MethodReport& out = sink.out;
  const ShapePair& pair = facts.pair;
  for (const Vec3& p : answer.points) {
    const double outsideA = Outside(pair.a, pair.xfA, p);
    const double outsideB = Outside(pair.b, pair.xfB, p);
    const double outside = std::max(outsideA, outsideB);
    sink.sample.pointOutside.push_back(outside);
    sink.familySample.pointOutside.push_back(outside);
    // Misplaced: farther out of either shape than the true depth
    // (a point midway between the surfaces of a contact patch is
    // within that of both) plus the tolerance.
    if (outside > facts.pointBound + facts.truth.Depth()) ++out.pointsOverTolerance;
    if (!sink.Talus()) continue;
    // Outside either shape beyond round-off: gated for the Clipped
    // modes (issue 26: every point inside both shapes), measured for
    // WriteUp, whose rule takes vertices near the other shape.
    if (outside > facts.roundOff && out.pointsOutsideEither++ == 0 && !sink.method.writeUpPoints)
      sink.Fail("a point " + Sci(outside) + " m outside a shape (bound " + Sci(facts.roundOff) + " m)",
                facts);
    // Outside both: gated. The write-up's rule takes vertices up to
    // its tolerance (WriteUpTolerance) outside the other shape by design.
    const double bothBound =
        facts.pointBound + (sink.method.writeUpPoints ? WriteUpTolerance(facts.hullA, facts.hullB) : 0.0);
    if (std::min(outsideA, outsideB) > bothBound && out.pointsOutsideBoth++ == 0)
      sink.Fail("a point " + Sci(std::min(outsideA, outsideB)) + " m outside both shapes", facts);
  }
}

// Runs one method on one pair (timed when asked) and judges its answer.
PairMethodResult JudgeMethod(const PairContext& context, const PairFacts& facts,
                             const SatCheckSettings& settings, const MethodSink& sink) {
  const std::function<Answer()> query = sink.method.prepare(context);
  const Answer answer = query();
  PairMethodResult result{.ok = answer.ok,
                          .intersecting = answer.intersecting,
                          .depth = answer.depth,
                          .normalExcess = 0.0,
                          .points = static_cast<int>(answer.points.size()),
                          .timeNs = 0.0};
  if (settings.timingRepeats > 0) {
    result.timeNs = TimeQuery(query, settings.timingRepeats);
    sink.sample.timeNs.push_back(result.timeNs);
  }
  const CaseRecord base{.pair = facts.pair.index,
                        .configuration = facts.configuration,
                        .trueSignedDistance = facts.truth.signedDistance,
                        .methodIntersecting = answer.intersecting,
                        .value = 0.0};
  if (!JudgeVerdict(answer, facts, base, sink)) return result;
  if (sink.method.givesDepth && answer.intersecting && facts.truth.intersecting && !facts.inBand)
    JudgeDepthAndNormal(answer, facts, base, result, sink);
  if (sink.Talus() && answer.intersecting && !answer.pointDepths.empty())
    JudgeDeepestPoint(answer, facts, sink);
  if (sink.method.givesPoints && !facts.inBand) JudgePoints(answer, facts, sink);
  return result;
}

// One pair: the truth and its checks, then every method. An Error when
// the truth cannot be computed.
std::optional<Error> RunPair(const ShapePair& pair, const std::vector<Method>& methods,
                             const SatCheckSettings& settings, std::vector<Samples>& samples,
                             SatCheckReport& report) {
  ++report.placementCounts[static_cast<std::size_t>(pair.placement)];
  ++report.alignmentCounts[static_cast<std::size_t>(pair.alignment)];
  const Hull& hullA = pair.a.GetHull();
  const Hull& hullB = pair.b.GetHull();
  Result<reference::PenetrationTruth> truthResult =
      reference::ComputePenetrationTruth(hullA, pair.xfA, hullB, pair.xfB);
  if (!truthResult)
    return Error{"pair " + std::to_string(pair.index) + ": " + truthResult.GetError().message};
  const reference::PenetrationTruth& truth = truthResult.Value();
  const PairFacts facts = MakePairFacts(pair, truth, settings);
  if (settings.checkWithQhull) CheckTruthWithQhull(pair, report);
  CheckTruthWithBoxClosedForm(facts, settings, report);
  if (truth.intersecting) ++report.truth.intersecting;
  if (facts.inBand) ++report.truth.touchingBand;
  if (truth.intersecting && truth.minimumFaces > 1) ++report.truth.tiedMinimum;

  const BulletHullShape bulletA(hullA);
  const BulletHullShape bulletB(hullB);
  const PairContext context{.pair = &pair,
                            .ccdA = {.hull = &hullA, .transform = pair.xfA},
                            .ccdB = {.hull = &hullB, .transform = pair.xfB},
                            .bulletA = &bulletA,
                            .bulletB = &bulletB};
  PairRecord record{.index = pair.index,
                    .configuration = facts.configuration,
                    .trueSignedDistance = truth.signedDistance,
                    .trueNormal = truth.normal,
                    .results = {}};
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const MethodSink sink{.method = methods[m],
                          .out = report.methods[m],
                          .sample = samples[m],
                          .familySample = samples[m].families[static_cast<std::size_t>(pair.family)],
                          .failures = report.failures,
                          .worstCases = settings.worstCases};
    record.results.push_back(JudgeMethod(context, facts, settings, sink));
  }
  report.pairs.push_back(std::move(record));
  return std::nullopt;
}

// Each method's samples reduced to percentiles, overall and by family.
void SummariseMethods(const std::vector<Samples>& samples, SatCheckReport& report) {
  for (std::size_t m = 0; m < samples.size(); ++m) {
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
}

}  // namespace

Result<SatCheckReport> RunSatCheck(const SatCheckSettings& settings) {
  if (const std::string problem = SettingsProblem(settings); !problem.empty()) return Error{problem};
  const std::vector<Method> methods = AllMethods();
  SatCheckReport report = StartReport(settings, methods);
  const std::vector<ShapePair> pairs = GeneratePairs(settings.pairs, settings.seed);
  report.pairCount = static_cast<int>(pairs.size());
  std::vector<Samples> samples(methods.size());
  for (const ShapePair& pair : pairs) {
    if (std::optional<Error> error = RunPair(pair, methods, settings, samples, report)) return *error;
  }
  SummariseMethods(samples, report);
  return report;
}

}  // namespace talus::validation
