// The talus_bullet_f32 module's entry point (bullet_f32_module.h): the only
// symbol it exports.
#include "bullet_f32_module.h"

using talus::reference::BulletF32Request;

extern "C" __attribute__((visibility("default"))) bool talus_bullet_f32_create(
    const BulletF32Request& request, std::unique_ptr<talus::harness::Backend>& world, std::string& error) {
  if (request.layout != talus::reference::BulletF32Layout()) {
    error = "bullet-f32: the module was built from other sources than this program (rebuild both)";
    return false;
  }
  auto created =
      talus::reference::CreateBulletWorld(*request.run, *request.masses, request.tuning, request.host);
  if (!created) {
    error = created.GetError().message;
    return false;
  }
  world = std::move(created).Value();
  return true;
}
