#include "app/cli_support.h"

#include "core/errors.h"
#include "core/progress_bar.h"
#include "core/resources.h"
#include "volume/direct_mesher.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <fstream>
#include <iostream>

namespace tissuemesh::app {

int run_guarded(const std::string& command, const std::function<void()>& body) {
  const std::string prefix = "tissuemesh " + command + ": error: ";
  try {
    body();
    return 0;
  } catch (const InputError& e) {
    std::cerr << prefix << e.what() << "\n";
    return 2;
  } catch (const OutputError& e) {
    std::cerr << prefix << e.what() << "\n";
    return 2;
  } catch (const MeshingError& e) {
    // The mesher could not deliver a valid mesh for valid input; the reports say where.
    std::cerr << prefix << "meshing failed: " << e.what() << "\n";
    return 1;
  } catch (const SolverError& e) {
    // A solve that failed on valid input (e.g. did not converge): the message says it all.
    std::cerr << prefix << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << prefix << "out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << prefix << "internal failure: " << e.what() << "\n";
    return 1;
  }
}

namespace {
/// Columns of the terminal on stdout (80 when it cannot be told).
int terminal_columns() {
  winsize w{};
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}
}  // namespace

Progress console_progress() {
  // A bar only where someone watches it: a terminal that can redraw a line.
  const char* term = std::getenv("TERM");
  const bool live = isatty(STDOUT_FILENO) && !(term && std::string(term) == "dumb");
  auto bar_open = std::make_shared<bool>(false);
  return Progress([live, bar_open](Progress::Event event, const std::string& stage, const std::string& text, double s,
                                   double fraction) {
    if (live && event == Progress::Event::Note && !std::isnan(fraction)) {
      std::cout << "\r" << progress_bar_line(fraction, s, text, terminal_columns()) << "\033[K" << std::flush;
      *bar_open = true;
      return;
    }
    if (*bar_open) {
      std::cout << "\n";
      *bar_open = false;
    }
    char buf[64];
    switch (event) {
      case Progress::Event::Begin:
        std::cout << "> " << stage << " ..." << std::endl;
        break;
      case Progress::Event::Note:
        std::snprintf(buf, sizeof buf, "%8.2f s", s);
        std::cout << "  " << buf << "  " << text << std::endl;
        break;
      case Progress::Event::End:
        std::snprintf(buf, sizeof buf, "%.2f s", s);
        std::cout << "  " << stage << " done in " << buf << std::endl;
        break;
    }
  });
}

nlohmann::json run_record_common(const Progress& progress, const std::string& cmd) {
  nlohmann::json j;
  j["command_line"] = cmd;
  auto versions = library_versions();
  versions["CGAL"] = cgal_version();
  j["versions"] = versions;
  nlohmann::json timings = nlohmann::json::array();
  double total = 0.0;
  for (const auto& t : progress.timings()) {
    timings.push_back({{"stage", t.name}, {"seconds", t.seconds}});
    total += t.seconds;
  }
  j["timings"] = timings;
  j["total_seconds"] = total;
  j["peak_memory_mib"] = peak_memory_mib();
  return j;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f.flush()) throw OutputError(path.string() + ": cannot write");
}

void add_html_flag(CLI::App& sub, bool& no_html) {
  sub.add_flag("--no-html", no_html,
               "do not write DIR/report.html (the offline page with the mesh in 3D, plots and tables)");
}

void add_model_job_options(CLI::App& sub, ModelJobOptions& options) {
  sub.add_option("MESH", options.mesh, "tetrahedral mesh written by `tissuemesh mesh` (mesh.vtu)")->required();
  sub.add_option("-c,--config", options.config,
                 "config with `materials:` and `model:` (units, element, node sets, gravity, analysis settings); "
                 "e.g. configs/phantom.yaml")
      ->required();
  sub.add_option("-o,--out", options.out, "output directory");
  sub.add_flag("--print-config", options.print_config, "print the effective config (defaults filled in) and exit");
}

bool print_config_or_require_out(bool print_config, const std::string& effective_yaml, const std::string& out) {
  if (print_config) {
    std::cout << effective_yaml;
    return false;
  }
  if (out.empty()) throw InputError("--out DIR is required");
  return true;
}

nlohmann::json vec_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

std::string command_line(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

}  // namespace tissuemesh::app
