// Formatting benchmark reports (talus::harness::BenchReport) as the
// machine-readable lines of docs/bench-scenes.md: CSV (one header line, then one
// line per run, fixed columns) or JSON lines (one object per run, only the
// figures that apply to the scene). A skipped run is a line too, with its
// reason, so nothing is left out silently.
#pragma once

#include <string>

#include "talus/harness/scenes/bench_run.h"

namespace talus::scenes {

/// Output format of talus-scenes.
enum class ReportFormat { Csv, JsonLines };

/// The CSV header line (no newline): engine, scene, parameter, bodies,
/// threads, steps, iterations (0: the engine's default), substeps,
/// total_ms (the cost), ms_per_step_mean, ms_per_step_max, max_contacts,
/// drift_m, max_penetration_m, kinetic_energy_j, escaped, skipped,
/// stage_ms_mean (for an engine that times its stages:
/// "Stage=ms;Stage=ms;..." in its stage order, each its mean over the
/// steps; empty otherwise); when `perturbed` (talus-scenes
/// --perturb/--repeats), then repeat, perturb_m, perturb_seed.
std::string CsvHeader(bool perturbed = false);

/// One report as a CSV line (no newline). Figures a scene does not have are
/// empty fields; the skip reason is quoted. Numbers carry 6 significant
/// digits; a non-finite figure prints as nan or inf. A perturbed run's line
/// ends with its repeat, amount (17 digits) and seed.
std::string FormatCsv(const harness::BenchReport& report);

/// One report as a compact JSON object (no newline). A non-finite figure is
/// written as null (JSON has no NaN).
std::string FormatJson(const harness::BenchReport& report);

}  // namespace talus::scenes
