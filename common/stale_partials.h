#pragma once
// Staged outputs are named "<prefix><pid>" (e.g. "OUT.partial-1234"), and
// scratch folders "<prefix><pid>-<anything>" (e.g. mkdtemp's
// "depot-system-1234-Ab12Cd"). A process killed with SIGKILL cannot remove
// its own; the next run to the same place removes those whose process is gone.
#include <string>

namespace depot {

// True when a process with this id exists (including one of another user).
bool process_is_alive(long pid);

// The pid of an entry named "<prefix><pid>", or -1 when `name` is not one.
long staged_entry_pid(const std::string& name, const std::string& prefix);

// Removes the entries "<prefix><pid>" of `folder` whose process is gone;
// returns how many were removed. Entries of live processes stay.
int remove_stale_partials(const std::string& folder, const std::string& prefix);

// The pid of an entry named "<prefix><pid>-<anything>", or -1.
long scratch_entry_pid(const std::string& name, const std::string& prefix);

// Removes the entries "<prefix><pid>-<anything>" of `folder` whose process is
// gone; returns how many were removed.
int remove_stale_scratch(const std::string& folder, const std::string& prefix);

}  // namespace depot
