// OutputDir: all-or-nothing output of a run.
//
// Files are written into a hidden staging folder next to the target folder; `commit()` moves them
// into place. If the run fails (an exception unwinds before commit), the staging folder is removed
// and the target folder is left as it was: no partial output. An unwritable target throws
// OutputError naming it before any work is done.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tissuemesh {

class OutputDir {
 public:
  /// Creates `target` (and parents) if needed and a staging folder beside it.
  explicit OutputDir(const std::filesystem::path& target);
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  ~OutputDir();

  /// Where to write `name` now (inside the staging folder). `name` may hold folders
  /// ("calculix/model.inp"): they are created in the staging folder now and in the target at
  /// commit (and removed again, when empty, if the commit fails). Stage each name once.
  std::filesystem::path stage(const std::string& name);
  /// Final location of `name` after commit.
  std::filesystem::path final_path(const std::string& name) const { return target_ / name; }
  const std::filesystem::path& target() const { return target_; }

  /// Moves every staged file into the target folder (replacing files of the same name).
  void commit();

  /// Removes the staging folder of every OutputDir not yet committed, and each target folder such
  /// a run created when it is empty: what an interrupted process must do before it exits (the
  /// destructors do not run then). Callable from any thread while others work: a commit in
  /// progress finishes first, and every OutputDir made afterwards is abandoned at once.
  static void abandon_all();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  std::vector<std::string> names_;
  bool created_target_ = false;
  bool committed_ = false;
};

}  // namespace tissuemesh
