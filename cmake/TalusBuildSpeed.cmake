# How the tree compiles fast on a 2-core machine (docs/building.md gives
# each tree's measured time and why each switch is on).
#
# - ccache, when it is installed: a rebuild of unchanged sources in the
#   same checkout (another branch and back, a tree removed and made again)
#   costs a cache lookup. Its cache lives outside the repository (ccache's
#   own default, ~/.cache/ccache, or CCACHE_DIR), so nothing of it can be
#   committed. A clone in another folder does not hit it: the unity files
#   name their sources by absolute path (docs/building.md).
# - Unity builds: most of a translation unit's time here is parsing Eigen,
#   nlohmann-json and GoogleTest, so compiling several sources as one file
#   parses them once per batch. Files that cannot share a unit (their own
#   compile options, such as the SIMD kernels) are left out by CMake itself.
#
# Precompiled headers were measured and left out: alone they took the
# Release tree from 15.9 to 11.5 minutes, but on top of the batches each
# target's header costs about as much as it saves (docs/building.md).
#
# Each is a cache option, so one tree can be built the plain way
# (-DTALUS_UNITY_BUILD=OFF) when a change needs checking file by file: a
# unity batch can hide a missing include.

option(TALUS_CCACHE "Compile through ccache when it is installed" ON)
option(TALUS_UNITY_BUILD "Compile each target's sources in batches (CMake unity builds)" ON)
set(TALUS_UNITY_BATCH_SIZE 16 CACHE STRING "Sources per unity batch (TALUS_UNITY_BUILD)")

if(TALUS_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(TALUS_CCACHE_PROGRAM ccache)
  if(TALUS_CCACHE_PROGRAM)
    set(CMAKE_CXX_COMPILER_LAUNCHER ${TALUS_CCACHE_PROGRAM})
  endif()
endif()

if(TALUS_UNITY_BUILD)
  set(CMAKE_UNITY_BUILD ON)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE ${TALUS_UNITY_BATCH_SIZE})
endif()
