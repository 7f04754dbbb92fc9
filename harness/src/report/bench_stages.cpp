// Stage and thread tables of the large-scene section (bench_stages.h).
//
// Every figure here comes from one talus-scenes file, so the 1-thread and
// N-thread runs of an engine were measured back to back on the same
// machine: the speed-ups are ratios from the same invocation, which holds
// on a busy machine where the absolute times do not.
#include "report/bench_stages.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "support/text_util.h"
#include "talus/harness/scenes/bench_scenes.h"

namespace talus::harness {
namespace {

// The runs of one scene at one size, in row order.
struct SizeRows {
  std::string scene;
  int parameter = 0;
  std::vector<const BenchReport*> rows;
};

std::vector<SizeRows> GroupBySize(const std::vector<const BenchReport*>& rows) {
  std::vector<SizeRows> groups;
  for (const BenchReport* r : rows) {
    if (groups.empty() || groups.back().scene != r->scene || groups.back().parameter != r->parameter) {
      groups.push_back({r->scene, r->parameter, {}});
    }
    groups.back().rows.push_back(r);
  }
  return groups;
}

std::string SizeName(const std::string& scene, int parameter) {
  const BenchScene* known = FindBenchScene(scene);
  const std::string name = known ? std::string(known->parameterName) : std::string("parameter");
  return Concat({scene, " ", name, " = ", std::to_string(parameter)});
}

bool Ran(const BenchReport* r) { return r->skipped.empty(); }

// The run of `like`'s engine and solver settings at `threads` among `rows`
// with as many steps, or null: a thread speed-up compares like with like.
const BenchReport* AtThreads(const std::vector<const BenchReport*>& rows, const BenchReport* like,
                             int threads) {
  for (const BenchReport* r : rows) {
    if (Ran(r) && r->engine == like->engine && SameSolver(r, like) && r->steps == like->steps &&
        r->threads == threads)
      return r;
  }
  return nullptr;
}

// "1.5" for a ratio of two positive finite times, "-" otherwise.
std::string Ratio(double numerator, double denominator) {
  if (!(numerator > 0.0) || !(denominator > 0.0) || !std::isfinite(numerator) || !std::isfinite(denominator))
    return "-";
  return FormatNumber(numerator / denominator, 3);
}

// "12.5%" of a part in a whole (one decimal: a stage under 0.05% reads 0.0%), "-" when the whole is not a
// positive finite time.
std::string Share(double part, double whole) {
  if (!(whole > 0.0) || !std::isfinite(whole) || !std::isfinite(part)) return "-";
  return FormatPrintf("%.1f%%", 100.0 * part / whole);
}

const BenchStage* FindStage(const BenchReport& r, const std::string& name) {
  for (const BenchStage& stage : r.stages) {
    if (stage.name == name) return &stage;
  }
  return nullptr;
}

// The (engine, N) pairs among `runs` that also have a 1-thread run: each
// gets a speed-up column.
std::vector<std::pair<const BenchReport*, const BenchReport*>> ThreadPairs(
    const std::vector<const BenchReport*>& runs) {
  std::vector<std::pair<const BenchReport*, const BenchReport*>> pairs;
  for (const BenchReport* r : runs) {
    if (r->threads == 1) continue;
    if (const BenchReport* one = AtThreads(runs, r, 1)) pairs.emplace_back(one, r);
  }
  return pairs;
}

void WriteStageTable(std::ostringstream& out, const SizeRows& size) {
  std::vector<const BenchReport*> runs;
  for (const BenchReport* r : size.rows) {
    if (Ran(r) && !r->stages.empty()) runs.push_back(r);
  }
  if (runs.empty()) return;
  std::vector<std::string> stages;  // first-seen order: each engine's own step order
  for (const BenchReport* r : runs) {
    for (const BenchStage& stage : r->stages) {
      if (std::find(stages.begin(), stages.end(), stage.name) == stages.end()) stages.push_back(stage.name);
    }
  }
  const auto pairs = ThreadPairs(runs);
  out << "\n### " << SizeName(size.scene, size.parameter) << ": where the time goes\n\n| stage |";
  for (const BenchReport* r : runs) out << ' ' << BenchRunLabel(*r) << " |";
  for (const auto& [one, many] : pairs)
    out << ' ' << one->engine << ": speed-up at " << many->threads << " threads |";
  out << "\n|---|";
  for (std::size_t i = 0; i < runs.size() + pairs.size(); ++i) out << "---|";
  out << '\n';
  for (const std::string& name : stages) {
    out << "| " << name << " |";
    for (const BenchReport* r : runs) {
      const BenchStage* stage = FindStage(*r, name);
      if (stage == nullptr) {
        out << " - |";
        continue;
      }
      out << ' ' << FormatNumber(stage->msMean, 3) << " (" << Share(stage->msMean, r->msMean) << "; max "
          << FormatNumber(stage->msMax, 3) << ") |";
    }
    for (const auto& [one, many] : pairs) {
      const BenchStage* before = FindStage(*one, name);
      const BenchStage* after = FindStage(*many, name);
      out << ' ' << (before && after ? Ratio(before->msMean, after->msMean) : std::string("-")) << " |";
    }
    out << '\n';
  }
  out << "| other (outside the stages) |";
  for (const BenchReport* r : runs) {
    double inside = 0.0;
    for (const BenchStage& stage : r->stages) inside += stage.msMean;
    out << " (" << Share(r->msMean - inside, r->msMean) << ") |";
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) out << " - |";
  out << "\n| step |";
  for (const BenchReport* r : runs)
    out << ' ' << FormatNumber(r->msMean, 4) << " (100%; max " << FormatNumber(r->msMax, 4) << ") |";
  for (const auto& [one, many] : pairs) out << ' ' << Ratio(one->totalMs, many->totalMs) << " |";
  out << '\n';
}

}  // namespace

bool SameSolver(const BenchReport* a, const BenchReport* b) {
  return a->solver.iterations == b->solver.iterations && a->solver.substeps == b->solver.substeps;
}

std::string BenchRunLabel(const BenchReport& report) {
  std::string label = report.engine;
  if (report.threads != 1) label += Concat({", ", std::to_string(report.threads), " threads"});
  if (report.solver.iterations != 0 || report.solver.substeps != 1)
    label += Concat({", ", BenchSolverLabel(report.solver)});
  return label;
}

std::string BenchStagesMarkdown(const std::vector<const BenchReport*>& rows) {
  std::ostringstream out;
  for (const SizeRows& size : GroupBySize(rows)) WriteStageTable(out, size);
  if (out.str().empty()) return "";
  return "\n### Where the time goes\n\nEach cell: the stage's mean ms/step over the run (its total / steps), "
         "and in brackets its share of the run's total time and its longest step, which shows the steps "
         "where new pairs touch and the velocity sweeps run on; \"other\" is the time outside the engine's "
         "stages. A speed-up column divides an engine's 1-thread mean by its N-thread one from the same "
         "invocation: a stage near 1 does not run on the thread pool.\n" +
         out.str();
}

std::string BenchThreadsMarkdown(const std::vector<const BenchReport*>& rows) {
  std::ostringstream table;
  for (const SizeRows& size : GroupBySize(rows)) {
    std::vector<std::string> engines;  // engines run at more than one count, first-seen order
    for (const BenchReport* r : size.rows) {
      if (!Ran(r) || std::find(engines.begin(), engines.end(), r->engine) != engines.end()) continue;
      const bool several = std::any_of(size.rows.begin(), size.rows.end(), [r](const BenchReport* other) {
        return Ran(other) && other->engine == r->engine && other->threads != r->threads;
      });
      if (several) engines.push_back(r->engine);
    }
    for (const std::string& engine : engines) {
      for (const BenchReport* r : size.rows) {
        if (!Ran(r) || r->engine != engine) continue;
        const BenchReport* one = AtThreads(size.rows, r, 1);
        BenchReport settings = *r;
        settings.threads = 1;  // the label of its settings, without the count the next column gives
        table << "| " << SizeName(size.scene, size.parameter) << " | " << BenchRunLabel(settings) << " | "
              << r->threads << " | " << FormatNumber(r->msMean, 4) << " | "
              << (one != nullptr ? Ratio(one->totalMs, r->totalMs) : std::string("-")) << " |\n";
      }
    }
  }
  if (table.str().empty()) return "";
  return "\n### Thread scaling\n\nEach engine's mean ms/step (total / steps) at each thread count it ran at, "
         "and the speed-up (ratio of the total times) over its own 1-thread run with the same settings in "
         "the same invocation (goal: at least " +
         FormatNumber(kBenchThreadGoalSpeedup) +
         " at 2 threads on pyramid H = 20 and hull_pile L = 20).\n\n| scene | engine | threads | ms/step "
         "(mean) | speed-up over 1 thread |\n|---|---|---|---|---|\n" +
         table.str();
}

std::string BenchThreadGoals(const std::vector<const BenchReport*>& rows) {
  std::ostringstream goals;
  for (const auto& [scene, parameter] : {std::pair<std::string, int>{"pyramid", 20}, {"hull_pile", 20}}) {
    std::vector<const BenchReport*> sized;
    for (const BenchReport* r : rows) {
      if (r->scene == scene && r->parameter == parameter) sized.push_back(r);
    }
    std::vector<std::string> engines;
    for (const BenchReport* r : sized) {
      if (r->threads != 2 || !Ran(r) || std::find(engines.begin(), engines.end(), r->engine) != engines.end())
        continue;
      if (r->solver.iterations != 0 || r->solver.substeps != 1) continue;  // the goal is at the defaults
      const BenchReport* one = AtThreads(sized, r, 1);
      if (one == nullptr || !(one->totalMs > 0.0) || !(r->totalMs > 0.0)) continue;
      engines.push_back(r->engine);
      const double speedup = one->totalMs / r->totalMs;
      goals << "- " << SizeName(scene, parameter) << ": " << r->engine
            << " at 1 / 2 threads = " << FormatNumber(speedup, 3)
            << " (goal >= " << FormatNumber(kBenchThreadGoalSpeedup) << ": "
            << (speedup >= kBenchThreadGoalSpeedup ? "met" : "missed") << ")\n";
    }
  }
  return goals.str();
}

}  // namespace talus::harness
