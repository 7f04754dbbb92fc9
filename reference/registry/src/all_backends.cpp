// The one backend registry (all_backends.h): each peer library registers
// its own backends, with their thread safety, into one registry.
#include "talus/reference/all_backends.h"

#include "talus/reference/bullet_backend.h"
#include "talus/reference/mujoco_backend.h"
#include "talus/reference/ode_backend.h"
#include "talus/reference/talus_backend.h"

namespace talus::reference {

harness::BackendRegistry MakeAllBackends(int talusThreads) {
  harness::BackendRegistry r;
  RegisterTalusBackends(r, {.threads = talusThreads});
  RegisterBulletBackends(r);
  RegisterOdeBackends(r);
  RegisterMujocoBackends(r);
  return r;
}

const harness::BackendRegistry& AllBackends() {
  static const harness::BackendRegistry registry = MakeAllBackends(1);
  return registry;
}

}  // namespace talus::reference
