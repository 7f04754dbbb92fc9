// The JSON-lines form of benchmark reports (talus/harness/scenes/bench_run.h):
// what `talus-scenes --format jsonl` writes, one object per line, and what
// `talus-testbed report --scenes FILE` reads back to add the large-scene
// section to the comparison report.
//
// Layout of a line (keys in this order; figures a scene does not have are
// absent; a non-finite figure is null, since JSON has no NaN):
//   {"engine", "scene", "parameter", "bodies", "threads", "steps",
//    "iterations", "substeps",
//    ["repeat", "perturb_m", "perturb_seed" when perturbed],
//    "total_ms", "ms_per_step_mean", "ms_per_step_max", "max_contacts",
//    "drift_m" | "max_penetration_m", "kinetic_energy_j", "escaped",
//    "stages": [{"stage", "ms_mean", "ms_max"}, ...]}
// The times are finite and >= 0, and must hang together: steps >= 1,
// ms_per_step_mean = total_ms / steps, ms_per_step_mean <= ms_per_step_max
// <= total_ms (each within 1e-9 relative, the rounding of the sums).
// "iterations" (0: the engine's default) and "substeps" are those
// BenchSolverProblem accepts for the engine. "stages" (only for an engine
// that times its step's stages, in its order) must name each stage once,
// with finite times >= 0 whose means add up to no more than
// ms_per_step_mean and whose longest steps are no longer than
// ms_per_step_max (the stages run inside the timed step).
// A skipped run is {"engine", ..., "substeps", "skipped": "why"} with no
// figures. Reading validates every field and names the file, the line and
// the key of the first problem; nothing is returned from a bad file (one
// written before the cost became the total time, with
// "ms_per_step_median", is refused: "$.total_ms: missing"). The
// perturbation keys of `talus-scenes --perturb` are not read back: the
// report's large-scenes section takes unperturbed runs.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/scenes/bench_run.h"
#include "talus/result.h"

namespace talus::harness {

/// One report as a compact JSON object (no newline).
std::string BenchReportToJson(const BenchReport& report);

/// Every report of a JSON-lines text (blank lines ignored). `source` names
/// the text in error messages (a file name).
Result<std::vector<BenchReport>> ParseBenchReportLines(std::string_view text, std::string_view source);

/// The same, from a file.
Result<std::vector<BenchReport>> ReadBenchReportFile(const std::filesystem::path& path);

}  // namespace talus::harness
