// Running the talus-testbed binary from a test (TALUS_TESTBED_BINARY, set
// by tests/testbed/CMakeLists.txt when the program is built) and reading
// what it printed: the suites that check the command line share these.
#pragma once

#include <string>

#include "support/command_outcome.h"

namespace talus::testing_support {

#ifdef TALUS_TESTBED_BINARY
/// talus-testbed with `arguments`: its exit status and everything it printed.
inline CommandOutcome RunTestbed(const std::string& arguments) {
  return RunCommand(std::string(TALUS_TESTBED_BINARY) + " " + arguments);
}
#endif

/// Whether `text` contains `part`.
inline bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace talus::testing_support
