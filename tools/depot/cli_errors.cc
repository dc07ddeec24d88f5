#include "tools/depot/cli_errors.h"

#include <cstdio>
#include <filesystem>

#include "common/error.h"
#include "common/interrupt.h"
#include "common/staged_names.h"

namespace depot::cli {

std::string one_line(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n') {
      while (!out.empty() && out.back() == ' ') out.pop_back();
      if (!out.empty() && out.back() != ';') out += "; ";
    } else if (c != '\r') {
      out += c;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out;
}

namespace {

// The deepest subcommand that was parsed (the root when none was).
const CLI::App* deepest_command(const CLI::App& app) {
  const CLI::App* current = &app;
  while (!current->get_subcommands().empty()) current = current->get_subcommands().front();
  return current;
}

}  // namespace

std::string command_path(const CLI::App& app) {
  std::string path;
  const CLI::App* current = &app;
  while (!current->get_subcommands().empty()) {
    current = current->get_subcommands().front();
    path += (path.empty() ? "" : " ") + current->get_name();
  }
  return path;
}

int report_parse_error(CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  const std::string where = command_path(app);
  std::string problem = one_line(e.what());
  // "depot fly": CLI11 only says a subcommand is required; name the word.
  const CLI::App* command = deepest_command(app);
  const std::vector<std::string> extra = command->remaining();
  if (!command->get_subcommands({}).empty() && !extra.empty() && extra.front()[0] != '-') {
    std::string known;
    for (const CLI::App* sub : command->get_subcommands({}))
      known += (known.empty() ? "" : ", ") + sub->get_name();
    problem = "unknown command '" + extra.front() + "' (expected " + known + ")";
  }
  std::fprintf(stderr, "depot: error: %s%s%s (see depot %s%s--help)\n", where.c_str(),
               where.empty() ? "" : ": ", problem.c_str(), where.c_str(), where.empty() ? "" : " ");
  return kExitUsage;
}

void fail_usage(const std::string& where, const std::string& what) {
  if (where.empty()) throw CLI::ValidationError(what);
  throw CLI::ValidationError(where, what);
}

int report_failure(const std::exception& e) {
  // Whatever the work threw on its way out, it stopped because it was told to.
  const int code = interrupt_flag().load() ? kExitInterrupt : kExitError;
  // std::filesystem errors carry the paths apart from the text.
  if (const auto* fe = dynamic_cast<const std::filesystem::filesystem_error*>(&e)) {
    std::string message = fe->code().message();
    std::fprintf(
        stderr, "depot: error: %s: %s\n",
        fe->path1().empty() ? "file system" : with_final_names(fe->path1().string()).c_str(),
        one_line(message).c_str());
    return code;
  }
  // A staged output's temporary name is gone by now: name the final one.
  std::fprintf(stderr, "depot: error: %s\n", one_line(with_final_names(e.what())).c_str());
  return code;
}

}  // namespace depot::cli
