// What the report's 3D replay and broad-phase figure need from a run: the
// shape of every body (from the scenario), and per frame every body's pose,
// the contacts the engine reported and the engine's own step counters.
//
// Replays are recorded only for the runs selected with RunnerOptions::replay
// (`talus-testbed run --replay`), and thinned to at most
// RunnerOptions::replayFrames frames taken from the trajectory's samples
// (first and last always), so results.json stays small. Everything is a
// pure function of the trajectory, so equal runs give equal replays.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/backend/trajectory.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/math.h"
#include "talus/result.h"

namespace talus::harness {

/// A body's shape for drawing, in the scenario's body frame.
struct ReplayShape {
  enum class Kind { Box, Sphere, Hull };
  Kind kind = Kind::Box;
  Vec3 halfExtents = Vec3::Zero();      ///< metres (boxes)
  double radius = 0.0;                  ///< metres (spheres)
  std::vector<Vec3> vertices;           ///< metres (hulls): the hull's vertices
  std::vector<std::vector<int>> faces;  ///< (hulls) counter-clockwise vertex loops seen from outside
  bool isStatic = false;                ///< static bodies are drawn grey
};

/// One recorded instant.
struct ReplayFrame {
  double time = 0.0;                     ///< seconds
  std::vector<Vec3> positions;           ///< metres: each body's origin (scenario frame), scenario order
  std::vector<Quat> orientations;        ///< each body's orientation, scenario order
  std::vector<ContactReading> contacts;  ///< as the backend reported them after this step (none at step 0)
  std::vector<double> counters;          ///< values of Replay::counterNames after this step
};

/// A run's replay; empty `frames` means none was recorded.
struct Replay {
  std::vector<ReplayShape> shapes;  ///< one per scenario body
  std::vector<std::string>
      counterNames;                 ///< the backend's step counters (Backend::StepCounters); may be empty
  std::vector<ReplayFrame> frames;  ///< in time order
};

/// The shape of a scenario body for drawing; hulls are built with BuildHull
/// (an Error names the body when its points span no volume).
Result<ReplayShape> MakeReplayShape(const BodySpec& body);

/// The replay of `run` from a trajectory recorded with contacts and
/// counters (Record's `detail`), thinned to at most `maxFrames` (>= 2)
/// frames spread evenly over the samples.
Result<Replay> MakeReplay(const Run& run, const Trajectory& trajectory, int maxFrames);

/// Whether `run` is selected by `selection`: an entry equal to the run's
/// id, its scenario's name, or "all".
bool IsReplaySelected(const Run& run, const std::vector<std::string>& selection);

/// The replay as compact JSON (results.json's "replay" field): shapes as
/// objects, frames as {"t", "p": [[x,y,z]...], "q": [[w,x,y,z]...],
/// "c": [[bodyA, bodyB, px, py, pz, nx, ny, nz, depth]...], "n": [counters]}.
nlohmann::ordered_json ReplayToJson(const Replay& replay);

/// Parses ReplayToJson's output; an Error names the place in `where`.
Result<Replay> ReplayFromJson(const nlohmann::ordered_json& json, const std::string& where);

}  // namespace talus::harness
