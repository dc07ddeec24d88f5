#pragma once
// Starting another program as a child process: argv without a shell, stdin
// from /dev/null, stdout and stderr into one log file, optionally in its own
// process group or session (so a time limit or Ctrl-C can stop everything it
// started), in a cgroup, with a signal on its parent's death, and with extra
// environment variables and a working folder.
#include <sys/types.h>

#include <map>
#include <string>
#include <vector>

namespace depot {

struct ChildSpec {
  std::vector<std::string> argv;  // argv[0]: a path, or a name looked up on PATH
  std::string log_path;           // stdout and stderr; its folder is created
  bool append_log = false;        // append instead of truncating
  bool own_process_group = false;
  // A session of its own (setsid, which is also a process group of its own):
  // no terminal signal reaches it, and its session id marks what it starts.
  bool own_session = false;
  // Sent to the child when the thread that started it ends, even by SIGKILL
  // (0 = none). The child's own children do not inherit it.
  int parent_death_signal = 0;
  // A cgroup v2 folder the child joins before it runs its program, so that
  // everything it starts is in it too ("" = stay in the caller's).
  std::string cgroup;
  std::string working_dir;                 // "" = the caller's
  std::map<std::string, std::string> env;  // added to (or replacing in) the caller's
};

// Throws depot::Error("<argv[0]>: cannot start: <reason>") when the program
// cannot be found or started (the log file is left as it was opened).
// `joined_cgroup` (when given) tells whether the child joined spec.cgroup: a
// cgroup it may not join (permissions, a domain with controllers) is no
// error, the child then runs in the caller's.
pid_t start_child(const ChildSpec& spec, bool* joined_cgroup = nullptr);

// This process's own program (/proc/self/exe), e.g. to start it again as a
// child; "depot" (looked up on PATH) when the link cannot be read.
std::string own_program_path();

// A waitpid status as a shell reports it: the exit code, or 128 + signal.
int exit_code_of(int status);

}  // namespace depot
