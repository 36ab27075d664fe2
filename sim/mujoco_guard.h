// Safe use of the MuJoCo 2.2 C library from C++: its fatal errors become C++ exceptions instead of exit(1),
// and models and data are owned by RAII wrappers.
//
// MuJoCo reports fatal errors through mju_error, whose default prints, writes MUJOCO_LOG.TXT and calls
// exit(1). The documented contract of the replacement handler (mju_user_error) is that it must not return:
// MuJoCo is written assuming mju_error never returns. Throwing a C++ exception from the handler would unwind
// through C frames of libmujoco, which is undefined behaviour (and skips MuJoCo's own bookkeeping). So we do
// what MuJoCo's own Python bindings do (python/mujoco/errors.h): mujoco_call() sets a jump point (setjmp) on
// the calling thread before entering MuJoCo, the handler copies the message and longjmps back there, and only
// then, in our own C++ frame, a MujocoError is thrown. See docs/mujoco-scene.md "Error handling".
#pragma once

#include <mujoco/mujoco.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace cmt {

// A MuJoCo fatal error (mju_error) or a failed load; what() is MuJoCo's message.
class MujocoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Installs the process-wide mju_user_error / mju_user_warning handlers (once, thread-safe). Called by every
// function below; call it yourself only if you use MuJoCo directly before any of them.
void install_mujoco_handlers();

// The last MuJoCo warning raised on this thread (warnings are also written to stderr), or "".
std::string last_mujoco_warning();

namespace internal {
void run_guarded(void (*fn)(void*), void* context);
}  // namespace internal

// Runs `fn` (which calls MuJoCo) so that a MuJoCo fatal error inside it throws MujocoError from here instead
// of exiting the process. Because the error path is a longjmp across `fn`'s frames, `fn` must not create
// objects with non-trivial destructors (strings, vectors, locks) between its start and its MuJoCo calls: keep
// it to plain MuJoCo calls, e.g. mujoco_call([&] { mj_step(m, d); }). Nested calls are fine. A MuJoCo error
// raised outside any mujoco_call on a thread cannot be returned from safely: it is written to stderr and the
// process aborts (a crash with MuJoCo's message rather than MuJoCo's silent exit(1)).
// After a MujocoError the mjData that was being worked on is in an undefined state (MuJoCo's frames,
// including its stack bookkeeping, were abandoned mid-way): mj_resetData it (or drop it) before using it
// again.
template <class F>
void mujoco_call(F&& fn) {
  using Fn = std::remove_reference_t<F>;
  internal::run_guarded([](void* c) { (*static_cast<Fn*>(c))(); },
                        const_cast<void*>(static_cast<const void*>(&fn)));
}

// An immutable compiled model. MuJoCo's model is read-only during simulation, so one instance is shared
// across threads (one MujocoData per thread).
class MujocoModel {
 public:
  // Compiles MJCF text (through an in-memory MuJoCo VFS, no temporary file). Throws MujocoError with MuJoCo's
  // parser/compiler message on failure.
  static std::shared_ptr<const MujocoModel> load_xml_string(const std::string& xml);
  // Compiles an MJCF file. Throws MujocoError naming the file.
  static std::shared_ptr<const MujocoModel> load_xml_file(const std::filesystem::path& file);

  ~MujocoModel();
  MujocoModel(const MujocoModel&) = delete;
  MujocoModel& operator=(const MujocoModel&) = delete;

  // Non-const because parts of MuJoCo's C API take mjModel*. Do not modify a model that is already shared;
  // tests that tweak parameters (margins) load a fresh model for that.
  mjModel* get() const { return model_; }

 private:
  explicit MujocoModel(mjModel* model) : model_(model) {}
  mjModel* model_;
};

// Simulation state for one thread; keeps its model alive.
class MujocoData {
 public:
  // Throws MujocoError if MuJoCo cannot allocate the data.
  explicit MujocoData(std::shared_ptr<const MujocoModel> model);
  ~MujocoData();
  MujocoData(const MujocoData&) = delete;
  MujocoData& operator=(const MujocoData&) = delete;
  MujocoData(MujocoData&& other) noexcept
      : model_(std::move(other.model_)), data_(std::exchange(other.data_, nullptr)) {}
  MujocoData& operator=(MujocoData&& other) noexcept;

  mjData* get() const { return data_; }
  const mjModel* model() const { return model_->get(); }
  const std::shared_ptr<const MujocoModel>& shared_model() const { return model_; }

 private:
  std::shared_ptr<const MujocoModel> model_;
  mjData* data_ = nullptr;
};

}  // namespace cmt
