#include "tools/system/process_tree.h"

#include <dirent.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot::system {
namespace {

constexpr const char* kCgroupPrefix = "depot-system-";

// Trees alive in this process: only while one runs alone are adopted orphans
// surely its own.
std::atomic<int>& live_trees() {
  static std::atomic<int> n{0};
  return n;
}

struct ProcStat {
  pid_t pid = 0, ppid = 0, pgrp = 0, sid = 0;
  char state = '?';
  unsigned long long start = 0;  // clock ticks since boot
};

std::optional<ProcStat> read_stat(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(in, text)) return std::nullopt;
  // "pid (comm) state ppid pgrp session ..." where comm may hold ") ".
  const size_t close = text.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(text.substr(close + 1));
  ProcStat s;
  s.pid = pid;
  long skip = 0;
  fields >> s.state >> s.ppid >> s.pgrp >> s.sid;
  for (int i = 0; i < 15; ++i) fields >> skip;  // tty_nr .. itrealvalue
  fields >> s.start;
  if (!fields) return std::nullopt;
  return s;
}

std::vector<ProcStat> list_processes() {
  std::vector<ProcStat> out;
  DIR* dir = opendir("/proc");
  if (!dir) return out;
  while (const dirent* e = readdir(dir)) {
    char* end = nullptr;
    const long pid = std::strtol(e->d_name, &end, 10);
    if (pid <= 0 || *end != '\0') continue;
    if (auto s = read_stat(static_cast<pid_t>(pid))) out.push_back(*s);
  }
  closedir(dir);
  return out;
}

// This process's start time, which with its pid names it for good (a pid
// alone may be reused). Kept per pid: a forked child is another process.
unsigned long long own_start_time() {
  static std::atomic<pid_t> cached_pid{0};
  static std::atomic<unsigned long long> cached_start{0};
  if (cached_pid.load() != getpid()) {
    const auto s = read_stat(getpid());
    cached_start = s ? s->start : 0ULL;
    cached_pid = getpid();
  }
  return cached_start.load();
}

// This process and its ancestors: never part of a tree, whatever they carry
// (depot may itself run inside a system of an outer depot).
std::set<pid_t> self_and_ancestors(const std::map<pid_t, ProcStat>& by_pid) {
  std::set<pid_t> out;
  for (pid_t p = getpid(); p > 0 && out.insert(p).second;) {
    auto it = by_pid.find(p);
    if (it == by_pid.end()) break;
    p = it->second.ppid;
  }
  return out;
}

// The value of kSystemRunVariable in a process's environment ("" if none or
// unreadable).
std::string read_mark(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/environ", std::ios::binary);
  const std::string key = std::string(kSystemRunVariable) + "=";
  std::string entry;
  while (std::getline(in, entry, '\0'))
    if (entry.compare(0, key.size(), key) == 0) return entry.substr(key.size());
  return "";
}

// A mark is "<depot pid>:<its start time>:<tree number>".
std::string make_mark(int tree) {
  return std::to_string(getpid()) + ":" + std::to_string(own_start_time()) + ":" +
         std::to_string(tree);
}

// True unless the process is surely gone: its pid is free or now names a
// process started at another time.
bool owner_alive(long pid, unsigned long long start) {
  if (pid <= 0) return false;
  if (pid == getpid()) return true;
  if (const auto s = read_stat(static_cast<pid_t>(pid))) return s->start == start;
  return kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

bool owner_of_mark_alive(const std::string& mark) {
  long pid = 0;
  unsigned long long start = 0;
  int tree = 0;
  if (std::sscanf(mark.c_str(), "%ld:%llu:%d", &pid, &start, &tree) != 3) return true;
  return owner_alive(pid, start);
}

// ---- cgroup v2 ----

std::string unescape_mount_path(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 3 < s.size()) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 3), nullptr, 8));
      i += 3;
    } else {
      out += s[i];
    }
  }
  return out;
}

// This process's own cgroup v2 folder, where a tree's cgroup goes ("" when
// there is no cgroup v2 hierarchy or it is not writable here).
std::string own_cgroup_folder() {
  std::ifstream cgroup("/proc/self/cgroup");
  std::string line, relative;
  bool found = false;
  while (std::getline(cgroup, line))
    if (line.compare(0, 3, "0::") == 0) {
      relative = line.substr(3);
      found = true;
    }
  if (!found) return "";
  std::ifstream mounts("/proc/self/mountinfo");
  while (std::getline(mounts, line)) {
    // "id parent major:minor root mount-point options ... - fstype source ..."
    const size_t dash = line.find(" - ");
    if (dash == std::string::npos) continue;
    std::istringstream after(line.substr(dash + 3));
    std::string fstype;
    after >> fstype;
    if (fstype != "cgroup2") continue;
    std::istringstream before(line.substr(0, dash));
    std::string id, parent, device, root, mount_point;
    before >> id >> parent >> device >> root >> mount_point;
    root = unescape_mount_path(root);
    if (relative.compare(0, root.size(), root) != 0) continue;
    const std::string rest = root == "/" ? relative : relative.substr(root.size());
    const fs::path folder =
        fs::path(unescape_mount_path(mount_point)) / fs::path(rest).relative_path();
    std::error_code ec;
    if (fs::is_regular_file(folder / "cgroup.procs", ec) && access(folder.c_str(), W_OK) == 0)
      return folder.lexically_normal().string();
  }
  return "";
}

bool write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.flush();
  return static_cast<bool>(out);
}

std::vector<pid_t> cgroup_processes(const std::string& cgroup) {
  std::vector<pid_t> out;
  std::ifstream in(cgroup + "/cgroup.procs");
  long pid = 0;
  while (in >> pid)
    if (pid > 0) out.push_back(static_cast<pid_t>(pid));
  return out;
}

bool cgroup_populated(const std::string& cgroup) {
  std::ifstream in(cgroup + "/cgroup.events");
  std::string key;
  int value = 0;
  while (in >> key >> value)
    if (key == "populated") return value != 0;
  return !cgroup_processes(cgroup).empty();
}

// SIGKILL to every process in the cgroup at once (cgroup.kill, Linux 5.14),
// or frozen so none can fork while each is killed.
void kill_cgroup(const std::string& cgroup) {
  std::error_code ec;
  if (fs::exists(cgroup + "/cgroup.kill", ec) && write_file(cgroup + "/cgroup.kill", "1")) return;
  const bool frozen = write_file(cgroup + "/cgroup.freeze", "1");
  for (pid_t pid : cgroup_processes(cgroup)) kill(pid, SIGKILL);
  if (frozen) write_file(cgroup + "/cgroup.freeze", "0");
}

// Kills what is in a cgroup and removes it; gives up (leaving it) after a
// while if its processes do not go.
void remove_cgroup(const std::string& cgroup) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (true) {
    std::error_code ec;
    if (!fs::exists(cgroup, ec)) return;
    if (!cgroup_populated(cgroup) && rmdir(cgroup.c_str()) == 0) return;
    if (std::chrono::steady_clock::now() > deadline) return;
    kill_cgroup(cgroup);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::string make_cgroup(int tree) {
  const std::string parent = own_cgroup_folder();
  if (parent.empty()) return "";
  const std::string path =
      (fs::path(parent) / (kCgroupPrefix + std::to_string(getpid()) + "-" +
                           std::to_string(own_start_time()) + "-" + std::to_string(tree)))
          .string();
  return mkdir(path.c_str(), 0755) == 0 ? path : "";
}

}  // namespace

ProcessTree::ProcessTree(ChildSpec spec, Tracking tracking) {
  static std::atomic<int> next_tree{0};
  const int tree = next_tree++;
  // Orphans of the system come to us rather than to init, to be found.
  prctl(PR_SET_CHILD_SUBREAPER, 1);
  for (const ProcStat& p : list_processes())
    if (p.ppid == getpid()) children_before_.insert(p.pid);
  mark_ = make_mark(tree);
  spec.env[kSystemRunVariable] = mark_;
  spec.own_session = true;
  spec.parent_death_signal = SIGKILL;
  if (tracking == Tracking::kAuto) cgroup_ = make_cgroup(tree);
  spec.cgroup = cgroup_;
  bool joined = false;
  try {
    pid_ = start_child(spec, &joined);
  } catch (const Error&) {
    if (!cgroup_.empty()) rmdir(cgroup_.c_str());
    throw;
  }
  if (!joined && !cgroup_.empty()) {
    rmdir(cgroup_.c_str());
    cgroup_.clear();
  }
  if (const auto s = read_stat(pid_)) start_time_ = s->start;
  last_reap_ = std::chrono::steady_clock::now();
  ++live_trees();
}

ProcessTree::~ProcessTree() {
  kill_all();
  --live_trees();
}

std::vector<ProcessTree::Member> ProcessTree::scan() const {
  const std::vector<ProcStat> all = list_processes();
  std::map<pid_t, ProcStat> by_pid;
  for (const ProcStat& p : all) by_pid[p.pid] = p;
  const std::set<pid_t> excluded = self_and_ancestors(by_pid);
  const pid_t self = getpid();
  const bool alone = live_trees().load() <= 1;
  std::set<pid_t> in;
  if (!cgroup_.empty())
    for (pid_t p : cgroup_processes(cgroup_)) in.insert(p);
  for (const ProcStat& p : all) {
    // Our session's members pin its id: the id cannot name another
    // session while one of them lives (the program itself once reaped may).
    const bool program = p.pid == pid_ && !reaped_;
    const bool session =
        p.pid != pid_ && (p.sid == pid_ || p.pgrp == pid_) && p.start >= start_time_;
    const bool adopted = alone && p.ppid == self && p.pid != pid_ && !children_before_.count(p.pid);
    if (program || session || adopted || read_mark(p.pid) == mark_) in.insert(p.pid);
  }
  // And everything below them.
  for (bool grew = true; grew;) {
    grew = false;
    for (const ProcStat& p : all)
      if (!in.count(p.pid) && in.count(p.ppid)) grew = in.insert(p.pid).second;
  }
  std::vector<Member> out;
  for (pid_t pid : in) {
    if (excluded.count(pid)) continue;
    auto it = by_pid.find(pid);
    if (it == by_pid.end()) continue;  // gone meanwhile
    out.push_back({pid, it->second.ppid, it->second.state == 'Z'});
  }
  return out;
}

std::vector<pid_t> ProcessTree::members() const {
  std::vector<pid_t> out;
  for (const Member& m : scan())
    if (!m.zombie) out.push_back(m.pid);
  return out;
}

void ProcessTree::reap_adopted(const std::vector<Member>& members) {
  for (const Member& m : members)
    if (m.parent == getpid() && m.pid != pid_ && m.zombie) waitpid(m.pid, nullptr, WNOHANG);
}

std::optional<int> ProcessTree::poll() {
  if (reaped_) return status_;
  int status = 0;
  const pid_t done = waitpid(pid_, &status, WNOHANG);
  if (done == pid_) {
    reaped_ = true;
    status_ = status;
    return status_;
  }
  if (done < 0 && errno != EINTR) fail("process " + std::to_string(pid_), "lost");
  // Orphans that ended while it runs would stay zombies of ours until then.
  const auto now = std::chrono::steady_clock::now();
  if (now - last_reap_ > std::chrono::seconds(1)) {
    last_reap_ = now;
    reap_adopted(scan());
  }
  return std::nullopt;
}

void ProcessTree::stop(std::chrono::milliseconds grace) {
  for (const Member& m : scan())
    if (!m.zombie) kill(m.pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (!reaped_ && std::chrono::steady_clock::now() < deadline) {
    try {
      if (poll()) break;
    } catch (const Error&) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill_all();
}

void ProcessTree::kill_all() {
  if (pid_ <= 0) return;
  // Bounded only against a hang: SIGKILL cannot be refused, but a process
  // in uninterruptible sleep (a dead NFS server) can take long to go.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (true) {
    if (!cgroup_.empty()) kill_cgroup(cgroup_);
    const std::vector<Member> members = scan();
    bool running = false;
    for (const Member& m : members)
      if (!m.zombie) {
        kill(m.pid, SIGKILL);
        running = true;
      }
    if (!reaped_) {
      int status = 0;
      const pid_t done = waitpid(pid_, &status, WNOHANG);
      if (done == pid_ || (done < 0 && errno == ECHILD)) {
        reaped_ = true;
        status_ = done == pid_ ? status : status_;
      }
    }
    reap_adopted(members);
    const bool cgroup_busy = !cgroup_.empty() && cgroup_populated(cgroup_);
    if ((!running && reaped_ && !cgroup_busy) || std::chrono::steady_clock::now() > deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!cgroup_.empty()) {
    remove_cgroup(cgroup_);
    cgroup_.clear();
  }
}

int remove_stale_process_trees() {
  int killed = 0;
  // Cgroups named for depot processes that are gone: everything in them.
  const std::string parent = own_cgroup_folder();
  std::error_code ec;
  if (!parent.empty())
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      long pid = 0;
      unsigned long long start = 0;
      int tree = 0;
      if (name.compare(0, std::strlen(kCgroupPrefix), kCgroupPrefix) != 0 ||
          std::sscanf(name.c_str() + std::strlen(kCgroupPrefix), "%ld-%llu-%d", &pid, &start,
                      &tree) != 3 ||
          owner_alive(pid, start))
        continue;
      killed += static_cast<int>(cgroup_processes(it->path().string()).size());
      remove_cgroup(it->path().string());
    }
  // Processes carrying the mark of a depot that is gone (also where no
  // cgroup could be made); until they are gone, since their children carry
  // it too and may be started while the first are being killed.
  std::set<pid_t> marked;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    const std::vector<ProcStat> all = list_processes();
    std::map<pid_t, ProcStat> by_pid;
    for (const ProcStat& p : all) by_pid[p.pid] = p;
    const std::set<pid_t> excluded = self_and_ancestors(by_pid);
    bool found = false;
    for (const ProcStat& p : all) {
      if (p.state == 'Z' || excluded.count(p.pid)) continue;
      const std::string mark = read_mark(p.pid);
      if (mark.empty() || owner_of_mark_alive(mark)) continue;
      if (kill(p.pid, SIGKILL) == 0) {
        marked.insert(p.pid);
        found = true;
      }
    }
    if (!found) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  killed += static_cast<int>(marked.size());
  return killed;
}

}  // namespace depot::system
