// What every subcommand shares: exception -> exit code mapping, progress printing, the run record.
//
// Exit codes (docs/commands.md, "Behaviour common to every command"): 0 success, 2 bad input
// (InputError, OutputError, a missing file, a bad option), 1 failure on valid input (SolverError,
// printed as it is: e.g. a solve that did not converge) and internal failure (anything else,
// printed as "internal failure").
#pragma once

#include "core/number_format.h"  // format_double, used by every command
#include "core/progress.h"

#include <CLI/CLI.hpp>

#include <Eigen/Core>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>

namespace tissuemesh::app {

/// Runs `body`, prints any error as "tissuemesh <command>: error: <message>" on stderr and
/// returns the exit code.
int run_guarded(const std::string& command, const std::function<void()>& body);

/// A Progress that prints one line when a stage starts, its notes, and its wall time at the end.
Progress console_progress();

/// One 3-vector as a JSON array [x, y, z] (run records).
nlohmann::json vec_json(const Eigen::Vector3d& v);

/// The part of every run record that does not depend on the command: versions, peak memory,
/// stage timings, command line.
nlohmann::json run_record_common(const Progress& progress, const std::string& command_line);

/// Writes `text` to `path` (a staged output); OutputError naming the path when it cannot.
void write_text_file(const std::filesystem::path& path, const std::string& text);

/// What `export`, `solve` and `check` all take: MESH, -c CONFIG, -o DIR, --print-config.
struct ModelJobOptions {
  std::string mesh, config, out;
  bool print_config = false;
};

/// Declares --no-html (report.html is written unless it is given) on `sub`.
void add_html_flag(CLI::App& sub, bool& no_html);

/// Declares MESH (required), -c/--config (required), -o/--out and --print-config on `sub`.
void add_model_job_options(CLI::App& sub, ModelJobOptions& options);

/// The preamble of the commands that take -c CONFIG, -o DIR and --print-config: when
/// `print_config`, prints `effective_yaml` and returns false (the command is done); otherwise throws
/// InputError when `out` is empty and returns true.
bool print_config_or_require_out(bool print_config, const std::string& effective_yaml, const std::string& out);

/// The command line as typed (for run records).
std::string command_line(int argc, char** argv);

}  // namespace tissuemesh::app
