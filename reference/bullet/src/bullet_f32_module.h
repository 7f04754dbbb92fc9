// The one door into the talus_bullet_f32 module (the single-precision Bullet
// build, see bullet_world.h): a C entry point taking a request and filling a
// world or an error. Both sides are compiled from this header in the same
// build; the request carries a layout fingerprint, so a module left over from
// another build is refused instead of misread.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "bullet_world.h"

namespace talus::reference {

struct BulletF32Request {
  std::size_t layout = 0;  ///< BulletF32Layout() of the caller
  const harness::Run* run = nullptr;
  const std::vector<BodyMass>* masses = nullptr;
  BulletTuning tuning = BulletTuning::Defaults;
  BulletHost host;
};

/// A fingerprint of the types that cross the door.
constexpr std::size_t BulletF32Layout() {
  return sizeof(harness::Run) * 1000003u + sizeof(harness::Scenario) * 10007u + sizeof(BodyMass) * 101u +
         sizeof(harness::Setting) * 7u + sizeof(BulletF32Request);
}

/// The entry point's name and type: returns true and sets `world`, or false
/// and sets `error`.
inline constexpr const char* kBulletF32EntryPoint = "talus_bullet_f32_create";
using BulletF32Entry = bool (*)(const BulletF32Request& request, std::unique_ptr<harness::Backend>& world,
                                std::string& error);

}  // namespace talus::reference
