#pragma once
/// @file
/// RAII ownership of MuJoCo's compiled model (immutable, shared) and per-episode data.

#include <mujoco/mujoco.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace sortcell::sim {

/// A compiled MJCF model. Immutable after loading; many Data may share one Model.
class Model {
 public:
  /// A file held in memory: its name (no directory) and its content.
  struct VirtualFile {
    std::string name;
    std::string text;
  };

  /// Loads and compiles an MJCF (or URDF) file. `assets` (e.g. AssetFiles of the textures folder)
  /// are found by their file name alone, whatever folder the model names them in: MuJoCo's virtual
  /// file system ignores folders, so an object model's texture resolves from a scene anywhere.
  /// @throws std::invalid_argument naming the file if it is missing, unreadable or does not compile
  ///         (with MuJoCo's message, which names the element and line).
  static Model FromFile(const std::string& path, const std::vector<VirtualFile>& assets = {});

  /// Compiles files held in memory (MuJoCo's virtual file system); the first is the main file, the
  /// others are includes and assets (found by name, as FromFile's `assets`).
  /// Includes of other virtual files use their bare names; includes of files on disk must be
  /// absolute paths (MuJoCo 2.2 prefixes includes with the main file's directory, which is empty
  /// here). `name` names the model in error messages.
  /// @throws std::invalid_argument with `name` and MuJoCo's message if it does not compile.
  static Model FromVirtualFiles(const std::vector<VirtualFile>& files, const std::string& name);

  /// Every regular file of `dir` (not its subfolders), read into memory by name; none if `dir` does
  /// not exist.
  /// @throws std::runtime_error naming a file that cannot be read.
  static std::vector<VirtualFile> AssetFiles(const std::filesystem::path& dir);

  const mjModel* get() const { return model_.get(); }
  const mjModel* operator->() const { return model_.get(); }
  /// Write access, for scene variations (sim/scene_variation.h) applied before any Data is made.
  mjModel* mutable_get() { return model_.get(); }
  /// The file (or name) this model came from.
  const std::string& source() const { return source_; }
  /// The compiler's warning text, empty when the model compiled cleanly.
  const std::string& compile_warning() const { return compile_warning_; }

  /// Id of a named element. @throws std::invalid_argument naming the model, kind and name if absent.
  int Id(mjtObj type, const std::string& name) const;

 private:
  struct Deleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  Model(mjModel* model, std::string source, std::string warning);
  std::unique_ptr<mjModel, Deleter> model_;
  std::string source_;
  std::string compile_warning_;
};

/// Simulation state for one model.
class Data {
 public:
  explicit Data(const Model& model);
  mjData* get() { return data_.get(); }
  const mjData* get() const { return data_.get(); }
  mjData* operator->() { return data_.get(); }
  const mjData* operator->() const { return data_.get(); }

 private:
  struct Deleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  std::unique_ptr<mjData, Deleter> data_;
};

/// Outcome of advancing the simulation: kOk, or kDiverged when MuJoCo flagged an unstable state
/// (2.2 silently resets a diverged state and only bumps d->warning[]).
struct StepStatus {
  enum Code { kOk, kDiverged, kWarning } code = kOk;
  std::string detail;  ///< The warning's name and count when code != kOk.
};

/// Resets `data` to the scene's keyframe "observe" (the cell's start: arm at its observe pose, objects
/// in place) if it has one, else to the default state. Returns whether the keyframe exists.
bool ResetToObserve(const Model& model, Data& data);

/// Steps `n` times and checks d->warning[] for counters that grew during these steps; a state MuJoCo
/// reset (time back at the start) is kDiverged even when the counters do not show it.
StepStatus Step(const Model& model, Data& data, int n = 1);

/// Names of the free bodies (the movable objects), in body order.
std::vector<std::string> FreeBodyNames(const Model& model);

}  // namespace sortcell::sim
