// Every backend the testbed ships (Talus's variants, Bullet, both ODE
// steppers, MuJoCo's two configurations) in one registry, shared by the testbed suites.
#pragma once

#include "talus/harness/backend/backend.h"
#include "talus/reference/bullet_backend.h"
#include "talus/reference/mujoco_backend.h"
#include "talus/reference/ode_backend.h"
#include "talus/reference/talus_backend.h"

namespace talus::harness::testing {

inline const BackendRegistry& AllBackends() {
  static const BackendRegistry registry = [] {
    BackendRegistry r;
    reference::RegisterTalusBackends(r);
    reference::RegisterBulletBackends(r);
    reference::RegisterOdeBackends(r);
    reference::RegisterMujocoBackends(r);
    return r;
  }();
  return registry;
}

}  // namespace talus::harness::testing
