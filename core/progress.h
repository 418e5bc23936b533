// Progress: stage timing and progress lines for long work.
//
// The libraries never print. They open a stage (`auto s = progress.stage("mesh")`), optionally
// report notes inside it, and the stage records its wall time when it ends. The program (app/)
// passes a sink that prints each event; tests pass none. Timings go into every run's JSON record.
// A note may say how far the stage has got (a fraction in [0, 1]: remeshing rounds, load
// increments, sweep samples); a terminal sink draws it as a bar with the time left.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace tissuemesh {

struct StageTiming {
  std::string name;
  double seconds = 0.0;
};

class Progress {
 public:
  enum class Event { Begin, Note, End };
  /// `stage` name, `text` (note text, empty otherwise), `seconds` since the stage began,
  /// `fraction` of the stage done (Note only; NaN when the note does not say).
  using Sink = std::function<void(Event, const std::string& stage, const std::string& text,
                                  double seconds, double fraction)>;

  explicit Progress(Sink sink = {}) : sink_(std::move(sink)) {}

  class Stage {
   public:
    Stage(Progress& owner, std::string name);
    Stage(const Stage&) = delete;
    Stage& operator=(const Stage&) = delete;
    ~Stage();
    /// A line inside the stage (e.g. "12345 tets"), with the time elapsed so far.
    void note(const std::string& text);
    /// A note that also says how far the stage has got: `fraction` in [0, 1] (clamped).
    void note(const std::string& text, double fraction);
    double elapsed() const;

   private:
    Progress& owner_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
  };

  Stage stage(std::string name) { return Stage(*this, std::move(name)); }
  const std::vector<StageTiming>& timings() const { return timings_; }

 private:
  Sink sink_;
  std::vector<StageTiming> timings_;
};

}  // namespace tissuemesh
