#include "sim/model.h"

#include <algorithm>
#include <array>
#include <optional>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "sim/mujoco_handlers.h"

namespace sortcell::sim {
namespace {

constexpr int kErrorSize = 2048;

// MuJoCo's messages span several lines; error messages of this program are one line.
std::string OneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  std::string squeezed;
  for (char c : text) {
    if (c == ' ' && !squeezed.empty() && squeezed.back() == ' ') continue;
    squeezed += c;
  }
  return squeezed;
}

// MuJoCo's virtual file system holding `files`; null when there are none.
std::unique_ptr<mjVFS, void (*)(mjVFS*)> MakeVfs(const std::vector<Model::VirtualFile>& files,
                                                 const std::string& name) {
  std::unique_ptr<mjVFS, void (*)(mjVFS*)> vfs(nullptr, [](mjVFS* v) {
    mj_deleteVFS(v);
    delete v;
  });
  if (files.empty()) return vfs;
  vfs.reset(new mjVFS);  // Large (file tables); keep it off the stack.
  mj_defaultVFS(vfs.get());
  for (const Model::VirtualFile& file : files) {
    if (mj_makeEmptyFileVFS(vfs.get(), file.name.c_str(), static_cast<int>(file.text.size())) != 0) {
      throw std::runtime_error("scene '" + name + "': cannot add '" + file.name + "' to MuJoCo's virtual files");
    }
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file.name.c_str())], file.text.data(), file.text.size());
  }
  return vfs;
}

}  // namespace

std::vector<Model::VirtualFile> Model::AssetFiles(const std::filesystem::path& dir) {
  std::vector<VirtualFile> files;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw std::runtime_error("asset '" + entry.path().string() + "': cannot be read");
    files.push_back({entry.path().filename().string(), std::move(content)});
  }
  std::sort(files.begin(), files.end(), [](const VirtualFile& a, const VirtualFile& b) { return a.name < b.name; });
  return files;
}

Model::Model(mjModel* model, std::string source, std::string warning)
    : model_(model), source_(std::move(source)), compile_warning_(std::move(warning)) {}

Model Model::FromFile(const std::string& path, const std::vector<VirtualFile>& assets) {
  InstallMujocoHandlers();
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw std::invalid_argument("scene '" + path + "': file not found");
  if (fs::is_directory(path, ec)) {
    throw std::invalid_argument("scene '" + path + "': is a directory, expected an MJCF file");
  }
  if (!std::ifstream(path).good()) throw std::invalid_argument("scene '" + path + "': cannot be read");
  const auto vfs = MakeVfs(assets, path);
  std::array<char, kErrorSize> error{};
  mjModel* m = mj_loadXML(path.c_str(), vfs.get(), error.data(), kErrorSize);
  if (m == nullptr) {
    throw std::invalid_argument("scene '" + path + "': " + OneLine(error.data()));
  }
  return Model(m, path, OneLine(error.data()));
}

Model Model::FromVirtualFiles(const std::vector<VirtualFile>& files, const std::string& name) {
  InstallMujocoHandlers();
  if (files.empty()) throw std::invalid_argument("scene '" + name + "': no files to compile");
  const auto vfs = MakeVfs(files, name);
  std::array<char, kErrorSize> error{};
  mjModel* m = mj_loadXML(files.front().name.c_str(), vfs.get(), error.data(), kErrorSize);
  if (m == nullptr) throw std::invalid_argument("scene '" + name + "': " + OneLine(error.data()));
  return Model(m, name, OneLine(error.data()));
}

int Model::Id(mjtObj type, const std::string& name) const {
  const int id = mj_name2id(model_.get(), type, name.c_str());
  if (id < 0) {
    const char* kind = type == mjOBJ_BODY     ? "body"
                       : type == mjOBJ_CAMERA ? "camera"
                       : type == mjOBJ_SITE   ? "site"
                       : type == mjOBJ_JOINT  ? "joint"
                       : type == mjOBJ_GEOM   ? "geom"
                                              : "element";
    throw std::invalid_argument("scene '" + source_ + "': no " + kind + " named '" + name + "'");
  }
  return id;
}

Data::Data(const Model& model) : data_(mj_makeData(model.get())) {
  if (!data_) throw std::runtime_error("scene '" + model.source() + "': mj_makeData failed");
}

bool ResetToObserve(const Model& model, Data& data) {
  const int observe = mj_name2id(model.get(), mjOBJ_KEY, "observe");
  if (observe >= 0) {
    mj_resetDataKeyframe(model.get(), data.get(), observe);
  } else {
    mj_resetData(model.get(), data.get());
  }
  return observe >= 0;
}

StepStatus Step(const Model& model, Data& data, int n) {
  std::array<int, mjNWARNING> before{};
  for (int i = 0; i < mjNWARNING; ++i) before[i] = data->warning[i].number;
  std::optional<double> reset_at;
  for (int k = 0; k < n && !reset_at; ++k) {
    const double t = data->time;
    mj_step(model.get(), data.get());
    // A diverged state is reset by mj_resetData, which also clears the warning counters before it
    // counts the new one: a second divergence leaves the counter where the first left it. Time going
    // back to the start is the sign that always shows.
    if (data->time <= t) reset_at = t;
  }

  static constexpr std::array<const char*, mjNWARNING> kNames = {"inertia", "contactfull", "cnstrfull", "vgeomfull",
                                                                 "badqpos", "badqvel",     "badqacc",   "badctrl"};
  StepStatus status;
  for (int i = 0; i < mjNWARNING; ++i) {
    const int grew = data->warning[i].number - before[i];
    if (grew <= 0) continue;
    // mj_checkPos/Vel/Acc reset the state after these: the run has diverged.
    const bool diverged = i == mjWARN_BADQPOS || i == mjWARN_BADQVEL || i == mjWARN_BADQACC;
    if (diverged || status.code == StepStatus::kOk) {
      status.code = diverged ? StepStatus::kDiverged : StepStatus::kWarning;
      status.detail =
          std::string(kNames[i]) + " x" + std::to_string(grew) + " at t=" + std::to_string(data->time) + " s";
    }
    if (diverged) break;
  }
  if (reset_at && status.code != StepStatus::kDiverged) {
    status.code = StepStatus::kDiverged;
    status.detail = "state reset by MuJoCo (bad qpos, qvel or qacc) at t=" + std::to_string(*reset_at) + " s";
  }
  return status;
}

std::vector<std::string> FreeBodyNames(const Model& model) {
  std::vector<std::string> names;
  const mjModel* m = model.get();
  for (int b = 1; b < m->nbody; ++b) {
    if (m->body_jntnum[b] >= 1 && m->jnt_type[m->body_jntadr[b]] == mjJNT_FREE) {
      names.emplace_back(mj_id2name(m, mjOBJ_BODY, b));
    }
  }
  return names;
}

}  // namespace sortcell::sim
