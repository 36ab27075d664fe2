#include "sim/mujoco_guard.h"

#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace cmt {

namespace {

// Per-thread jump target of the innermost active mujoco_call (null outside any) and the message of the error
// that jumped there. Plain arrays: the handler runs inside MuJoCo's C frames and must not allocate.
thread_local std::jmp_buf* tls_jump = nullptr;
thread_local char tls_error[1024] = {0};
thread_local std::string tls_warning;

void error_handler(const char* message) {
  std::snprintf(tls_error, sizeof(tls_error), "%s", message ? message : "(no message)");
  if (tls_jump != nullptr) std::longjmp(*tls_jump, 1);
  // Not inside mujoco_call: returning is undefined behaviour (MuJoCo assumes mju_error does not return) and
  // unwinding through C frames is too, so the only safe choice left is to stop, loudly.
  std::fprintf(stderr, "cmt: fatal MuJoCo error outside a guarded call: %s\n", tls_error);
  std::abort();
}

void warning_handler(const char* message) {
  // Warnings are returned to MuJoCo (it continues); keep the text for callers and log it, since MuJoCo's
  // default would append to MUJOCO_LOG.TXT in the working directory and print to stdout, where JSON goes.
  tls_warning = message ? message : "";
  std::fprintf(stderr, "cmt: MuJoCo warning: %s\n", tls_warning.c_str());
}

}  // namespace

void install_mujoco_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = error_handler;
    mju_user_warning = warning_handler;
  });
}

std::string last_mujoco_warning() { return tls_warning; }

namespace internal {

void run_guarded(void (*fn)(void*), void* context) {
  install_mujoco_handlers();
  std::jmp_buf buffer;
  std::jmp_buf* const saved = tls_jump;
  tls_jump = &buffer;
  if (setjmp(buffer) == 0) {
    try {
      fn(context);
    } catch (...) {
      tls_jump = saved;
      throw;
    }
    tls_jump = saved;
    return;
  }
  // Reached through longjmp from error_handler: MuJoCo's frames are gone, we are back in our own frame.
  tls_jump = saved;
  throw MujocoError(std::string("MuJoCo error: ") + tls_error);
}

}  // namespace internal

namespace {

// The compiled model or a MujocoError with MuJoCo's message. mj_loadXML is not run inside mujoco_call: it is
// C++ inside (a longjmp across it would skip destructors), and MuJoCo's compiler already converts engine
// errors raised while compiling into its error string (it installs its own thread-local handler for that).
mjModel* load(const char* file_name, const mjVFS* vfs, const std::string& label) {
  install_mujoco_handlers();
  char error[1024] = {0};
  mjModel* model = mj_loadXML(file_name, vfs, error, sizeof(error));
  if (model == nullptr) {
    std::string message = error[0] ? error : "unknown error";
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    throw MujocoError("MuJoCo cannot load " + label + ": " + message);
  }
  return model;
}

}  // namespace

std::shared_ptr<const MujocoModel> MujocoModel::load_xml_string(const std::string& xml) {
  // mjVFS is ~2 MB of fixed arrays: heap, not stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  static constexpr char kName[] = "scene.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0)
    throw MujocoError("MuJoCo cannot create an in-memory file for the MJCF text");
  const int index = mj_findFileVFS(vfs.get(), kName);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  mjModel* model = nullptr;
  try {
    model = load(kName, vfs.get(), "the MJCF text");
  } catch (...) {
    mj_deleteVFS(vfs.get());
    throw;
  }
  mj_deleteVFS(vfs.get());
  return std::shared_ptr<const MujocoModel>(new MujocoModel(model));
}

std::shared_ptr<const MujocoModel> MujocoModel::load_xml_file(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw MujocoError("MuJoCo cannot load '" + file.string() + "': no such file");
  // Built by appending: GCC 12 warns falsely (-Wrestrict, PR 105329) on "'" + std::string temporaries.
  std::string label = "'";
  label += file.string();
  label += "'";
  return std::shared_ptr<const MujocoModel>(new MujocoModel(load(file.c_str(), nullptr, label)));
}

MujocoModel::~MujocoModel() { mj_deleteModel(model_); }

MujocoData::MujocoData(std::shared_ptr<const MujocoModel> model) : model_(std::move(model)) {
  if (!model_) throw MujocoError("MujocoData needs a model");
  mjData* data = nullptr;
  const mjModel* m = model_->get();
  mujoco_call([&] { data = mj_makeData(m); });
  if (data == nullptr) throw MujocoError("MuJoCo cannot allocate mjData");
  data_ = data;
}

MujocoData::~MujocoData() {
  if (data_ != nullptr) mj_deleteData(data_);
}

MujocoData& MujocoData::operator=(MujocoData&& other) noexcept {
  if (this != &other) {
    if (data_ != nullptr) mj_deleteData(data_);
    model_ = std::move(other.model_);
    data_ = std::exchange(other.data_, nullptr);
  }
  return *this;
}

}  // namespace cmt
