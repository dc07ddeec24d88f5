#include "common/stale_partials.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <functional>

namespace fs = std::filesystem;

namespace depot {

bool process_is_alive(long pid) {
  if (pid <= 0) return false;
  // EPERM: it exists but belongs to someone else.
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

long staged_entry_pid(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
  const std::string digits = name.substr(prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) return -1;
  return std::stol(digits);
}

namespace {

int remove_entries_of_dead(const std::string& folder,
                           const std::function<long(const std::string&)>& pid_of) {
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(folder.empty() ? "." : folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    const long pid = pid_of(it->path().filename().string());
    if (pid < 0 || pid == static_cast<long>(::getpid()) || process_is_alive(pid)) continue;
    std::error_code remove_error;
    fs::remove_all(it->path(), remove_error);
    if (!remove_error) ++removed;
  }
  return removed;
}

}  // namespace

int remove_stale_partials(const std::string& folder, const std::string& prefix) {
  return remove_entries_of_dead(
      folder, [&](const std::string& name) { return staged_entry_pid(name, prefix); });
}

long scratch_entry_pid(const std::string& name, const std::string& prefix) {
  const size_t dash = name.find('-', prefix.size());
  if (dash == std::string::npos || dash + 1 >= name.size()) return -1;
  return staged_entry_pid(name.substr(0, dash), prefix);
}

int remove_stale_scratch(const std::string& folder, const std::string& prefix) {
  return remove_entries_of_dead(
      folder, [&](const std::string& name) { return scratch_entry_pid(name, prefix); });
}

}  // namespace depot
