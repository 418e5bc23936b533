#include "core/output_dir.h"

#include "core/errors.h"

#include <unistd.h>

#include <mutex>
#include <set>

namespace fs = std::filesystem;

namespace tissuemesh {
namespace {

// The OutputDirs alive in this process, for abandon_all(); the mutex also makes a commit and an
// abandonment exclude each other.
struct Registry {
  std::mutex mutex;
  std::set<OutputDir*> live;
  bool abandoned = false;
};

Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: usable until the process ends
  return *r;
}

// Removes `folder` and what is in it; retried because a thread may still be writing into it.
void remove_tree(const fs::path& folder) {
  std::error_code ec;
  for (int attempt = 0; attempt < 5 && fs::exists(folder, ec); ++attempt) fs::remove_all(folder, ec);
}

}  // namespace

OutputDir::OutputDir(const fs::path& target) : target_(target) {
  std::error_code ec;
  if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
    throw OutputError(target_.string() + ": output path exists and is not a directory");
  if (!fs::exists(target_, ec)) {
    fs::create_directories(target_, ec);
    if (ec) throw OutputError(target_.string() + ": cannot create output directory: " + ec.message());
    created_target_ = true;
  }
  if (::access(target_.c_str(), W_OK) != 0)
    throw OutputError(target_.string() + ": output directory is not writable");
  // Staging inside the target keeps the final rename on one file system.
  staging_ = target_ / (".tissuemesh-staging-" + std::to_string(::getpid()));
  fs::create_directories(staging_, ec);
  if (ec) throw OutputError(target_.string() + ": cannot write into output directory: " + ec.message());
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (r.abandoned) {
    remove_tree(staging_);
    throw OutputError(target_.string() + ": the run is being interrupted");
  }
  r.live.insert(this);
}

OutputDir::~OutputDir() {
  {
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.live.erase(this);
  }
  std::error_code ec;
  fs::remove_all(staging_, ec);
  // A folder we created for a run that failed would be a partial output too.
  if (!committed_ && created_target_ && fs::is_empty(target_, ec)) fs::remove(target_, ec);
}

fs::path OutputDir::stage(const std::string& name) {
  names_.push_back(name);
  const fs::path path = staging_ / name;
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) throw OutputError((target_ / name).parent_path().string() + ": cannot create output folder: " + ec.message());
  return path;
}

void OutputDir::abandon_all() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.abandoned = true;
  for (OutputDir* dir : r.live) {
    if (dir->committed_) continue;
    remove_tree(dir->staging_);
    std::error_code ec;
    if (dir->created_target_ && fs::is_empty(dir->target_, ec)) fs::remove(dir->target_, ec);
  }
}

void OutputDir::commit() {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (registry().abandoned) throw OutputError(target_.string() + ": the run was interrupted");
  // All or nothing: files already in the target that would be replaced are set aside first, and
  // put back if any move fails.
  std::vector<std::string> placed, set_aside;
  std::vector<fs::path> made;  // sub-folders of the target this commit created
  auto roll_back = [&] {
    std::error_code ec;
    for (const auto& name : placed) fs::remove(target_ / name, ec);
    for (const auto& name : set_aside) fs::rename(staging_ / (name + ".previous"), target_ / name, ec);
    for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);  // only if empty
  };
  for (const auto& name : names_) {
    if (!fs::exists(staging_ / name))
      throw OutputError((target_ / name).string() + ": output was never written");
    if (fs::is_directory(target_ / name))
      throw OutputError((target_ / name).string() + ": a folder is in the way of this output file");
  }
  for (const auto& name : names_) {
    std::error_code ec;
    // A name with folders ("calculix/model.inp"): create the missing ones, outermost first.
    std::vector<fs::path> missing;
    for (fs::path dir = (target_ / name).parent_path(); dir != target_ && !fs::exists(dir); dir = dir.parent_path())
      missing.push_back(dir);
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      if (!fs::create_directory(*it, ec) && ec) {
        roll_back();
        throw OutputError(it->string() + ": cannot create output folder: " + ec.message());
      }
      made.push_back(*it);
    }
    if (fs::exists(target_ / name)) {
      fs::rename(target_ / name, staging_ / (name + ".previous"), ec);
      if (ec) {
        roll_back();
        throw OutputError((target_ / name).string() + ": cannot replace existing file: " + ec.message());
      }
      set_aside.push_back(name);
    }
    fs::rename(staging_ / name, target_ / name, ec);
    if (ec) {
      roll_back();
      throw OutputError((target_ / name).string() + ": cannot move output into place: " + ec.message());
    }
    placed.push_back(name);
  }
  committed_ = true;
}

}  // namespace tissuemesh
