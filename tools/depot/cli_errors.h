#pragma once
// The one error format of the program: "depot: error: <where>: <problem>" on
// one line of stderr, with a non-zero exit. Command-line parsing errors
// (CLI11), project errors and filesystem errors all pass through here.
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

namespace depot::cli {

inline constexpr int kExitError = 1;  // the work failed (bad input file, ...)
inline constexpr int kExitUsage = 2;  // the command line was wrong
inline constexpr int kExitInterrupt = 130;

// The subcommand path that was being parsed, e.g. "sim render".
std::string command_path(const CLI::App& app);

// Prints the error line for a command-line error and returns the exit code
// (0 for --help and --version, which print their text instead).
int report_parse_error(CLI::App& app, const CLI::ParseError& e);

// Prints the error line for a failure while running a command; exits with
// kExitInterrupt when Ctrl-C (or SIGTERM) stopped the work, else kExitError.
int report_failure(const std::exception& e);

// A command-line error found while a command checks its options (before any
// work): the same line and exit code (kExitUsage) as CLI11's own parse
// errors, e.g. "depot: error: slam run: --save-map: is the same file as -o".
[[noreturn]] void fail_usage(const std::string& where, const std::string& what);

// Collapses a message to one line (newlines become "; ").
std::string one_line(const std::string& text);

}  // namespace depot::cli
