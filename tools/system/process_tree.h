#pragma once
// A system under test and everything it starts, so that nothing outlives the
// run. The program starts in a session of its own, marked in its environment
// (DEPOT_SYSTEM_RUN, which its children inherit), killed by the kernel when
// depot dies (parent-death signal), and in a cgroup v2 of its own when one can
// be made here. This process becomes a child subreaper, so what the system
// orphans (a daemon, `setsid cmd &`) is re-parented to depot instead of init.
// A process belongs to the tree when it is in the tree's cgroup, in its
// session or process group, carries its mark, descends from the program, or
// is an orphan depot adopted while the tree ran.
//
// What a depot killed by SIGKILL leaves (its system's children; the program
// itself dies with depot) is stopped by the next run: remove_stale_process_trees.
//
// Threads: a tree belongs to the thread that made it (the parent-death signal
// follows that thread); run one tree at a time per process and start no other
// children meanwhile (orphans adopted then are counted as the tree's).
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/child_process.h"

namespace depot::system {

enum class Tracking {
  kAuto,         // a cgroup when one can be made, and the /proc scan
  kProcessScan,  // the /proc scan only (session, group, mark, parents)
};

class ProcessTree {
 public:
  // Starts spec's program (own_session, parent_death_signal, cgroup and the
  // mark are set here). Throws depot::Error like start_child.
  explicit ProcessTree(ChildSpec spec, Tracking tracking = Tracking::kAuto);
  ~ProcessTree();  // kill_all()
  ProcessTree(const ProcessTree&) = delete;
  ProcessTree& operator=(const ProcessTree&) = delete;

  pid_t pid() const { return pid_; }
  // The tree's cgroup folder ("" when it has none: the scan alone tracks it).
  const std::string& cgroup() const { return cgroup_; }
  // The program's wait status once it has ended (and been reaped); nullopt
  // while it runs. Throws depot::Error when its process was lost.
  std::optional<int> poll();
  // Ctrl-C or a time limit: SIGTERM to every process of the tree, SIGKILL to
  // what is left once the program ended or `grace` passed.
  void stop(std::chrono::milliseconds grace);
  // SIGKILL to every process of the tree until none is left (what the system
  // left running after it ended, too); reaps what depot adopted and removes
  // the cgroup.
  void kill_all();
  // The tree's processes still running (not zombies).
  std::vector<pid_t> members() const;

 private:
  struct Member {
    pid_t pid;
    pid_t parent;
    bool zombie;
  };
  std::vector<Member> scan() const;
  void reap_adopted(const std::vector<Member>& members);

  pid_t pid_ = 0;
  bool reaped_ = false;
  int status_ = 0;
  unsigned long long start_time_ = 0;  // the program's, in clock ticks since boot
  std::string mark_;                   // DEPOT_SYSTEM_RUN's value
  std::string cgroup_;                 // "" = none
  std::set<pid_t> children_before_;    // this process's children before the tree
  std::chrono::steady_clock::time_point last_reap_;
};

// Stops what systems of depot processes that are gone (killed by SIGKILL)
// left running: processes carrying their mark, and their cgroups (removed).
// Returns how many processes were killed.
int remove_stale_process_trees();

// The environment variable that marks a tree's processes.
inline constexpr const char* kSystemRunVariable = "DEPOT_SYSTEM_RUN";

}  // namespace depot::system
