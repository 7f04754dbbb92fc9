// The Bullet backends' registration (talus/reference/bullet_backend.h): mass
// properties are computed here, once, and handed to a world of either build;
// the double-precision world is linked in, the single-precision one lives in
// the talus_bullet_f32 module, loaded on first use (bullet_world.h says why).
#include "talus/reference/bullet_backend.h"

#include <dlfcn.h>

#include "bullet_f32_module.h"
#include "bullet_world.h"

namespace talus::reference {
namespace {

using harness::Run;

constexpr BulletHost kHost{&harness::Combine, &harness::CombineRuleName};

Result<std::vector<BodyMass>> Masses(const Run& run, const std::string& backend) {
  std::vector<BodyMass> masses;
  for (const harness::BodySpec& spec : run.scenario.bodies) {
    auto mass = ComputeBodyMass(spec);
    if (!mass) return Error{backend + ": " + mass.GetError().message};
    masses.push_back(mass.Value());
  }
  return masses;
}

Result<std::unique_ptr<harness::Backend>> CreateDouble(const Run& run, BulletTuning tuning) {
  // Mass properties first: a bad hull fails before anything is built.
  auto masses = Masses(run, "bullet");
  if (!masses) return masses.GetError();
  return CreateBulletWorld(run, masses.Value(), tuning, kHost);
}

#ifdef TALUS_BULLET_F32_MODULE
// The module, opened once per process and never closed (its worlds may
// outlive any caller). RTLD_LOCAL keeps its symbols out of the global scope;
// RTLD_DEEPBIND makes its own references, and those of the single-precision
// Bullet libraries it pulls in, bind to those libraries first, never to the
// double-precision ones this program already has.
class BulletF32Module {
 public:
  static const BulletF32Module& Get() {
    static const BulletF32Module module;
    return module;
  }
  [[nodiscard]] BulletF32Entry Entry() const { return m_entry; }
  [[nodiscard]] const std::string& LoadError() const { return m_error; }

 private:
  BulletF32Module() {
    void* handle = dlopen(TALUS_BULLET_F32_MODULE, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
    if (handle == nullptr) {
      m_error = std::string("bullet-f32: cannot load ") + TALUS_BULLET_F32_MODULE + ": " + dlerror();
      return;
    }
    m_entry = reinterpret_cast<BulletF32Entry>(dlsym(handle, kBulletF32EntryPoint));
    if (m_entry == nullptr)
      m_error = std::string("bullet-f32: ") + TALUS_BULLET_F32_MODULE + ": no " + kBulletF32EntryPoint;
  }
  BulletF32Entry m_entry = nullptr;
  std::string m_error;
};

Result<std::unique_ptr<harness::Backend>> CreateSingle(const Run& run, BulletTuning tuning) {
  const BulletF32Module& module = BulletF32Module::Get();
  if (module.Entry() == nullptr) return Error{module.LoadError()};
  auto masses = Masses(run, "bullet-f32");
  if (!masses) return masses.GetError();
  const BulletF32Request request{BulletF32Layout(), &run, &masses.Value(), tuning, kHost};
  std::unique_ptr<harness::Backend> world;
  std::string error;
  if (!module.Entry()(request, world, error)) return Error{error};
  return world;
}
#endif

}  // namespace

bool BulletSinglePrecisionAvailable() {
#ifdef TALUS_BULLET_F32_MODULE
  return true;
#else
  return false;
#endif
}

void RegisterBulletBackends(harness::BackendRegistry& registry) {
  // Bullet keeps process-wide globals (gContactAddedCallback, its
  // profiler); the single-precision module has its own copies but shares
  // the lane, as it always has.
  const harness::ThreadSafety bullet = harness::ThreadSafety::SharesStateOf("bullet");
  registry.Register("bullet",
                    "Bullet 3 (double): discrete dynamics world, sequential impulse solver (defaults)",
                    bullet, [](const Run& run) { return CreateDouble(run, BulletTuning::Defaults); });
  registry.Register("bullet-tuned", "Bullet 3 (double), tuned: 1 mm collision margin, hulls shrunk by it",
                    bullet, [](const Run& run) { return CreateDouble(run, BulletTuning::Tuned); });
#ifdef TALUS_BULLET_F32_MODULE
  registry.Register("bullet-f32", "Bullet 3 (single precision, the default build): defaults", bullet,
                    [](const Run& run) { return CreateSingle(run, BulletTuning::Defaults); });
  registry.Register("bullet-f32-tuned",
                    "Bullet 3 (single precision, the default build), tuned: 1 mm margin, hulls shrunk by it",
                    bullet, [](const Run& run) { return CreateSingle(run, BulletTuning::Tuned); });
#endif
}

}  // namespace talus::reference
