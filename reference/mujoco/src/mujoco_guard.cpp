// MuJoCo's error and warning channels (see mujoco_guard.h).
#include "mujoco_guard.h"

#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>

namespace talus::reference {
namespace {

// The innermost guard of this thread and the last error/warning text.
thread_local std::jmp_buf* t_errorJump = nullptr;
thread_local char t_errorText[1024];

void OnError(const char* message) {
  std::strncpy(t_errorText, message, sizeof(t_errorText) - 1);
  t_errorText[sizeof(t_errorText) - 1] = '\0';
  if (t_errorJump != nullptr) std::longjmp(*t_errorJump, 1);
  std::abort();  // a MuJoCo call outside a guard: a bug in this backend
}

// Warnings are also counted in mjData::warning, which FirstWarning reads;
// the text itself is dropped instead of going to stdout and a log file.
void OnWarning(const char*) {}

// The setjmp frames hold only trivially destructible locals, so the jump
// skips no destructor.
bool StepOrJump(const mjModel* model, mjData* data) {
  std::jmp_buf jump;
  std::jmp_buf* outer = t_errorJump;
  if (setjmp(jump) != 0) {
    t_errorJump = outer;
    return false;
  }
  t_errorJump = &jump;
  mj_step(model, data);
  t_errorJump = outer;
  return true;
}

mjData* MakeDataOrJump(const mjModel* model) {
  std::jmp_buf jump;
  std::jmp_buf* outer = t_errorJump;
  if (setjmp(jump) != 0) {
    t_errorJump = outer;
    return nullptr;
  }
  t_errorJump = &jump;
  mjData* data = mj_makeData(model);
  t_errorJump = outer;
  return data;
}

const char* WarningName(int kind) {
  switch (kind) {
    case mjWARN_INERTIA:
      return "(near) singular inertia matrix";
    case mjWARN_CONTACTFULL:
      return "contact buffer full (nconmax)";
    case mjWARN_CNSTRFULL:
      return "constraint buffer full (njmax)";
    case mjWARN_VGEOMFULL:
      return "visual geom buffer full";
    case mjWARN_BADQPOS:
      return "bad number in qpos";
    case mjWARN_BADQVEL:
      return "bad number in qvel";
    case mjWARN_BADQACC:
      return "bad number in qacc (MuJoCo reset the state)";
    case mjWARN_BADCTRL:
      return "bad number in ctrl";
    default:
      return "unknown warning";
  }
}

}  // namespace

void InstallMujocoHandlers() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    mju_user_error = OnError;
    mju_user_warning = OnWarning;
  });
}

std::string GuardedStep(const mjModel* model, mjData* data) {
  InstallMujocoHandlers();
  if (StepOrJump(model, data)) return {};
  return std::string("MuJoCo error in mj_step: ") + t_errorText;
}

Result<mjData*> GuardedMakeData(const mjModel* model) {
  InstallMujocoHandlers();
  mjData* data = MakeDataOrJump(model);
  if (data == nullptr) return Error{std::string("MuJoCo error in mj_makeData: ") + t_errorText};
  return data;
}

Result<mjModel*> LoadMjcf(const std::string& mjcf) {
  InstallMujocoHandlers();
  // mjVFS holds its file table inline (about 2 MB in 2.2.2): on the heap.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "scenario.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(mjcf.size())) != 0) {
    return Error{"MuJoCo: cannot make the in-memory MJCF file"};
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], mjcf.data(), mjcf.size());
  char error[1024] = "";
  mjModel* model = mj_loadXML(name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (model == nullptr) return Error{std::string("MuJoCo refused the model: ") + error};
  return model;
}

std::string FirstWarning(const mjData* data) {
  for (int kind = 0; kind < mjNWARNING; ++kind) {
    if (data->warning[kind].number > 0) {
      return std::string("MuJoCo warning: ") + WarningName(kind) + " (info " +
             std::to_string(data->warning[kind].lastinfo) + ")";
    }
  }
  return {};
}

}  // namespace talus::reference
