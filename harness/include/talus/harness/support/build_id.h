// The identity of the build that runs the harness, recorded in shard files
// so that `talus-testbed merge` refuses shards run by different builds
// (whose numbers need not agree bit for bit).
#pragma once

namespace talus::harness {

/// "<commit> <compiler> <version> <build type>", e.g.
/// "1e93efc0a1b2 GNU 12.2.0 Release"; the commit is followed by
/// "-dirty-<digest of the uncommitted changes>" in a modified tree and is
/// "unknown-commit" outside a git checkout. Generated at build time by
/// cmake/TalusBuildId.cmake.
const char* BuildId();

}  // namespace talus::harness
