// What every subcommand shares: exception -> exit code mapping, progress printing, the run record.
//
// Exit codes (the contract of DESIGN.md): 0 success, 2 bad input (InputError, OutputError, a
// missing file, a bad option), 1 internal failure (anything else).
#pragma once

#include "core/progress.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>

namespace tissuemesh::app {

/// Runs `body`, prints any error as "tissuemesh <command>: error: <message>" on stderr and
/// returns the exit code.
int run_guarded(const std::string& command, const std::function<void()>& body);

/// A Progress that prints one line when a stage starts, its notes, and its wall time at the end.
Progress console_progress();

/// The part of every run record that does not depend on the command: versions, peak memory,
/// stage timings, command line.
nlohmann::json run_record_common(const Progress& progress, const std::string& command_line);

/// The command line as typed (for run records).
std::string command_line(int argc, char** argv);

}  // namespace tissuemesh::app
