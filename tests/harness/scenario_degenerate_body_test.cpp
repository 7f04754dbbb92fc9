// Degenerate bodies are refused at load (degenerate_body_check.h), before
// any engine sees them, naming the file, the body and the reason: a hull
// too small or without volume for its extent, a mass that is zero or
// denormal, an inertia that is not positive definite. Each threshold is
// checked from both sides, so the check refuses the degenerate body and
// nothing ordinary.
#include <gtest/gtest.h>

#include <string>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/support/number_text.h"

namespace talus::harness {
namespace scenario_degenerate_body_test {

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A scenario of a static ground and one dynamic body with `shape` and
// `massField` (e.g. "\"density\": 1000"). Built by appending: GCC 12
// mis-warns (-Wrestrict) on a literal + std::string chain.
std::string Scene(const std::string& shape, const std::string& massField) {
  std::string text =
      R"({"name": "degenerate", "world": {"timeStep": 0.01, "duration": {"steps": 10}}, "bodies": [
    {"name": "ground", "shape": {"kind": "box", "halfExtents": [10, 0.5, 10]}, "motion": "static", "position": [0, -0.5, 0]},
    {"name": "odd", "shape": )";
  text.append(shape)
      .append(R"(, "motion": "dynamic", "position": [0, 1, 0], )")
      .append(massField)
      .append("}]}");
  return text;
}

// A hull of a w x w x t slab's eight corners.
std::string Slab(double w, double t) {
  std::string text = R"({"kind": "hull", "points": [)";
  bool first = true;
  for (const double x : {0.0, w}) {
    for (const double y : {0.0, t}) {
      for (const double z : {0.0, w}) {
        text.append(first ? "[" : ", [").append(FormatNumber(x, 17)).append(", ").append(FormatNumber(y, 17));
        text.append(", ").append(FormatNumber(z, 17)).append("]");
        first = false;
      }
    }
  }
  return text.append("]}");
}

std::string Refusal(const std::string& text) {
  auto runs = ParseScenarioText(text, "degenerate.json");
  EXPECT_FALSE(runs) << "accepted";
  return runs ? std::string() : runs.GetError().message;
}

bool Accepted(const std::string& text) {
  auto runs = ParseScenarioText(text, "degenerate.json");
  EXPECT_TRUE(runs) << runs.GetError().message;
  return static_cast<bool>(runs);
}

TEST(DegenerateBody, AHullWithNoVolumeForItsExtentIsRefused) {
  // 1 m x 1 m x 1e-10 m: relative volume 1e-10 / 1.414^3 = 3.5e-11, under
  // 1e-9; its side faces' normals would carry round-off of about
  // epsilon / 1e-10 = 2e-6 rad.
  const std::string m = Refusal(Scene(Slab(1.0, 1e-10), R"("density": 1000)"));
  EXPECT_TRUE(Has(m,
                  "degenerate.json: /bodies/1/shape/points: body \"odd\": the hull has no volume for its "
                  "extent"))
      << m;
  EXPECT_TRUE(Has(m, "below 1e-09")) << m;
  // 1e-8 m thick: 3.5e-9 of the diagonal cubed, above the threshold.
  EXPECT_TRUE(Accepted(Scene(Slab(1.0, 1e-8), R"("density": 1000)")));
}

TEST(DegenerateBody, AFlatHullIsRefusedWithTheBuildersReason) {
  const std::string m = Refusal(Scene(Slab(1.0, 0.0), R"("density": 1000)"));
  EXPECT_TRUE(Has(m, "/bodies/1/shape/points: body \"odd\": the hull has no volume: ") && Has(m, "coplanar"))
      << m;
}

TEST(DegenerateBody, AHullOfPointsWithinAPicometreIsRefused) {
  // Five points within 1e-12 m (issue 26: ODE aborted in dMassCheck).
  const std::string tiny =
      R"({"kind": "hull", "points": [[0, 0, 0], [1e-12, 0, 0], [0, 1e-12, 0], [0, 0, 1e-12], [1e-12, 1e-12, 1e-12]]})";
  const std::string m = Refusal(Scene(tiny, R"("density": 1000)"));
  EXPECT_TRUE(
      Has(m, "/bodies/1/shape/points: body \"odd\": the hull's points lie within 1e-12 m of each other") &&
      Has(m, "at least 1e-06 m"))
      << m;
  // The same shape at the box's smallest size loads.
  const std::string small =
      R"({"kind": "hull", "points": [[0, 0, 0], [2e-6, 0, 0], [0, 2e-6, 0], [0, 0, 2e-6], [2e-6, 2e-6, 2e-6]]})";
  EXPECT_TRUE(Accepted(Scene(small, R"("density": 1000)")));
}

TEST(DegenerateBody, AZeroOrDenormalMassIsRefused) {
  // The schema refuses 0 itself; a denormal passes it.
  std::string m = Refusal(Scene(R"({"kind": "sphere", "radius": 0.5})", R"("mass": 1e-310)"));
  EXPECT_TRUE(Has(m, "/bodies/1/mass: body \"odd\": mass 1e-310 kg is zero, denormal or not finite")) << m;
  // Density x volume underflowing to exactly 0: 1e-320 kg/m^3 x 8e-18 m^3.
  m = Refusal(Scene(R"({"kind": "box", "halfExtents": [1e-6, 1e-6, 1e-6]})", R"("density": 1e-320)"));
  EXPECT_TRUE(Has(m, "/bodies/1/density: body \"odd\": mass 0 kg (density") && Has(m, "zero, denormal")) << m;
  // A tiny but normal mass whose moments stay normal (1e-291 kg m^2) loads.
  EXPECT_TRUE(Accepted(Scene(R"({"kind": "sphere", "radius": 0.5})", R"("mass": 1e-290)")));
}

TEST(DegenerateBody, AnInertiaThatIsNotPositiveDefiniteIsRefused) {
  // A normal mass whose moments are denormal: 1e-300 kg x (2e-6 m)^2 / 6.
  std::string m =
      Refusal(Scene(R"({"kind": "box", "halfExtents": [1e-6, 1e-6, 1e-6]})", R"("mass": 1e-300)"));
  EXPECT_TRUE(Has(m, "/bodies/1: body \"odd\": the inertia is not positive definite: principal moments"))
      << m;
  // A needle box 2e-6 x 2e-6 x 2e3 m: smallest moment / largest = 1e-18,
  // below 64 epsilon (1.4e-14): numerically singular for every engine.
  m = Refusal(Scene(R"({"kind": "box", "halfExtents": [1e-6, 1e-6, 1000]})", R"("density": 1000)"));
  EXPECT_TRUE(Has(m, "the inertia is not positive definite")) << m;
  // 2e-6 x 2e-6 x 2e-1 m: ratio 1e-10, accepted.
  EXPECT_TRUE(Accepted(Scene(R"({"kind": "box", "halfExtents": [1e-6, 1e-6, 0.1]})", R"("density": 1000)")));
}

}  // namespace scenario_degenerate_body_test
}  // namespace talus::harness
