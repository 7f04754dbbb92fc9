// The subcommands `sweep`, `merge` and `stress` of talus-testbed
// (docs/testbed-sweeps.md), each in its own file. Each Add function adds
// its subcommand to the app; when that subcommand is parsed, `chosen` is
// set to the action, which returns the process exit code
// (testbed_commands.h).
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <string>

#include "talus/harness/backend/backend.h"
#include "talus/harness/support/atomic_file.h"

namespace talus::testbed {

/// What main runs after parsing; empty when none of these was chosen.
using CommandAction = std::function<int()>;

void AddSweepCommand(CLI::App& app, CommandAction& chosen);
void AddMergeCommand(CLI::App& app, CommandAction& chosen);
void AddStressCommand(CLI::App& app, CommandAction& chosen);

/// Writes `text` to `path`, creating its folder; false (after printing
/// "talus-testbed: PATH: cannot write (REASON)" on stderr) when it fails.
bool WriteText(const std::filesystem::path& path, const std::string& text);

/// Writes every file of `files` or none (harness WriteFilesAtomically),
/// creating their folders; false (after printing the first failing file
/// and why on stderr) when it fails.
bool WriteTexts(const std::vector<harness::FileText>& files);

}  // namespace talus::testbed
