// The hull_rest truths of the shipped scenarios against an oracle that
// shares no code with the engine: qhull's triangulated hull
// (reference::ComputePointHull) and the divergence-theorem centroid over its
// triangles (reference::ComputeSolidMoments), not the engine's BuildHull
// and ComputeMassProperties. The scenario file states the resting face's
// normal and the centre of mass's height above it; this test is what makes
// those numbers a truth independent of the engine under test. The harness
// cannot link qhull (harness <- reference, docs/ARCHITECTURE.md), so the
// check lives here, beside the other reference-side oracles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/point_hull.h"

namespace talus {
namespace hull_rest_truth_test {

namespace fs = std::filesystem;

// Cosine above which a qhull triangle lies in the named face: normals
// written to 16 digits agree to round-off; a neighbouring face is degrees away.
constexpr double kSameFaceCosine = 1.0 - 1e-9;

struct OracleFace {
  double height = 0.0;          ///< centroid's distance to the face plane, m
  bool centroidInside = false;  ///< the centroid projects inside one of the face's triangles
  int triangles = 0;            ///< qhull triangles in the face
};

// The face of `hull` with outward normal `normal` as seen from `centroid`.
OracleFace FaceFromQhull(const reference::PointHull& hull, const Vec3& centroid, const Vec3& normal) {
  OracleFace face;
  face.height = std::numeric_limits<double>::quiet_NaN();
  for (const auto& t : hull.triangles) {
    const Vec3& a = hull.vertices[t[0]];
    const Vec3& b = hull.vertices[t[1]];
    const Vec3& c = hull.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    if (n.dot(normal) < kSameFaceCosine) continue;
    ++face.triangles;
    face.height = (a - centroid).dot(n);
    // Inside the triangle: the projected centroid is on the inner side of all three edges.
    const Vec3 p = centroid + face.height * n;
    const bool inside =
        n.dot((b - a).cross(p - a)) > 0 && n.dot((c - b).cross(p - b)) > 0 && n.dot((a - c).cross(p - c)) > 0;
    face.centroidInside = face.centroidInside || inside;
  }
  return face;
}

TEST(HullRestTruth, OracleMatchesAClosedFormTetrahedron) {
  // A right tetrahedron with legs 1: centroid (1/4, 1/4, 1/4), so it rests
  // on its base z = 0 with the centroid 1/4 above it.
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto hull = reference::ComputePointHull(points);
  ASSERT_TRUE(hull) << hull.GetError().message;
  const reference::SolidMoments moments = reference::ComputeSolidMoments(hull.Value());
  EXPECT_NEAR((moments.centroid - Vec3::Constant(0.25)).norm(), 0.0, 1e-15);
  const OracleFace face = FaceFromQhull(hull.Value(), moments.centroid, -Vec3::UnitZ());
  EXPECT_EQ(face.triangles, 1);
  EXPECT_NEAR(face.height, 0.25, 1e-15);
  EXPECT_TRUE(face.centroidInside);
}

TEST(HullRestTruth, EveryShippedHullRestTruthAgreesWithQhull) {
  int checked = 0;
  for (const auto& entry : fs::recursive_directory_iterator(TALUS_SCENARIO_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "schema.json") continue;
    auto runs = harness::LoadScenarioFile(entry.path());
    ASSERT_TRUE(runs) << runs.GetError().message;
    for (const harness::Run& run : runs.Value()) {
      for (const harness::Truth& truth : run.scenario.truths) {
        const auto* rest = std::get_if<harness::HullRestTruth>(&truth.kind);
        if (rest == nullptr) continue;
        const auto& shape = std::get<harness::HullShape>(run.scenario.bodies[truth.body].shape);
        auto hull = reference::ComputePointHull(shape.points);
        ASSERT_TRUE(hull) << hull.GetError().message;
        const Vec3 centroid = reference::ComputeSolidMoments(hull.Value()).centroid;
        const OracleFace face = FaceFromQhull(hull.Value(), centroid, rest->faceNormal);
        ASSERT_GT(face.triangles, 0) << run.id << ": faceNormal names no qhull facet";
        // The file's number is the oracle's to the digits written (1e-12 m).
        EXPECT_NEAR(rest->height, face.height, 1e-12)
            << run.id << ": the oracle's height is " << std::setprecision(17) << face.height;
        EXPECT_TRUE(face.centroidInside) << run.id << ": the face is not a stable resting face";
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 1);
}

}  // namespace hull_rest_truth_test
}  // namespace talus
