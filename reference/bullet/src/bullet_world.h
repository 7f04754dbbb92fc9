// One Bullet world behind the harness's Backend interface, written once
// against btScalar and compiled twice: into talus_bullet_backend with
// BT_USE_DOUBLE_PRECISION against Debian's bullet-float64 libraries, and into
// the talus_bullet_f32 module against the single-precision default build
// (pkg-config bullet). The two builds export the same C++ names, so they never
// share a process image: the module is loaded by bullet_f32_loader.cpp with
// RTLD_LOCAL | RTLD_DEEPBIND and exports one C entry point.
//
// Nothing here depends on btScalar, so both sides agree on these types; what
// the Bullet code needs from the harness library (the combine rules) comes in
// as function pointers, so the module links no harness code of its own.
#pragma once

#include <memory>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/bullet_backend.h"

namespace talus::reference {

/// The harness functions a Bullet world calls, from the executable's side.
struct BulletHost {
  double (*combine)(harness::CombineRule rule, double a, double b) = nullptr;
  const char* (*combineName)(harness::CombineRule rule) = nullptr;
};

/// Builds `run` in this library's Bullet build. `masses` are the bodies' mass
/// properties in scenario order (ComputeBodyMass); a count mismatch is an Error.
Result<std::unique_ptr<harness::Backend>> CreateBulletWorld(const harness::Run& run,
                                                            const std::vector<BodyMass>& masses,
                                                            BulletTuning tuning, const BulletHost& host);

}  // namespace talus::reference
