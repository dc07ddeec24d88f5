#include "common/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "common/error.h"

extern char** environ;

namespace depot {
namespace {

// The caller's environment with the spec's variables set over it.
std::vector<std::string> child_environment(const ChildSpec& spec) {
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    const std::string name = entry.substr(0, entry.find('='));
    if (!spec.env.count(name)) env_strings.push_back(entry);
  }
  for (const auto& [name, value] : spec.env) env_strings.push_back(name + "=" + value);
  return env_strings;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (auto& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

pid_t spawn_child(const ChildSpec& spec, std::vector<char*>& argv, std::vector<char*>& envp) {
  const std::string& program = spec.argv[0];
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, spec.log_path.c_str(),
                                   O_WRONLY | O_CREAT | (spec.append_log ? O_APPEND : O_TRUNC),
                                   0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (!spec.working_dir.empty())
    posix_spawn_file_actions_addchdir_np(&actions, spec.working_dir.c_str());
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (spec.own_process_group) {
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
  }
  pid_t pid = 0;
  // A name without '/' is looked up on PATH (posix_spawnp), like a shell does.
  const int rc =
      program.find('/') == std::string::npos
          ? posix_spawnp(&pid, program.c_str(), &actions, &attributes, argv.data(), envp.data())
          : posix_spawn(&pid, program.c_str(), &actions, &attributes, argv.data(), envp.data());
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) fail(program, std::string("cannot start: ") + std::strerror(rc));
  return pid;
}

// A program name looked up on the caller's PATH as posix_spawnp does; the
// name itself when it holds a '/' or is found nowhere (execve then says why).
std::string resolve_program(const std::string& program) {
  if (program.find('/') != std::string::npos) return program;
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/bin:/usr/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + program;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return program;
}

// What the forked child reports through its pipe before exec.
enum ChildStep : int { kCgroup = 1, kSetup = 2, kExec = 3 };
struct ChildReport {
  int step;
  int error;
};

// In the forked child: only async-signal-safe calls (the parent may have
// threads whose locks were copied held).
[[noreturn]] void child_failed(int pipe_fd, ChildStep step) {
  const ChildReport report{step, errno};
  [[maybe_unused]] const ssize_t n = write(pipe_fd, &report, sizeof(report));
  _exit(127);
}

void move_fd(int from, int to, int pipe_fd) {
  if (dup2(from, to) < 0) child_failed(pipe_fd, kSetup);
}

// A descriptor above stderr, so that setting up the child's 0, 1 and 2 never
// overwrites one still to be copied (a caller may have closed its stdin).
int above_stderr(int fd) {
  if (fd < 0 || fd > STDERR_FILENO) return fd;
  const int moved = fcntl(fd, F_DUPFD_CLOEXEC, STDERR_FILENO + 1);
  close(fd);
  return moved;
}

// fork + exec for what posix_spawn cannot do: a new session, the parent's
// death signal, joining a cgroup before the program runs (so nothing it
// starts can escape it).
pid_t fork_child(const ChildSpec& spec, std::vector<char*>& argv, std::vector<char*>& envp,
                 bool* joined_cgroup) {
  const std::string& program = spec.argv[0];
  const std::string path = resolve_program(program);
  const int log_fd = above_stderr(
      open(spec.log_path.c_str(),
           O_WRONLY | O_CREAT | O_CLOEXEC | (spec.append_log ? O_APPEND : O_TRUNC), 0644));
  if (log_fd < 0) fail(program, std::string("cannot start: ") + std::strerror(errno));
  const int null_fd = above_stderr(open("/dev/null", O_RDONLY | O_CLOEXEC));
  const int cgroup_fd = spec.cgroup.empty()
                            ? -1
                            : open((spec.cgroup + "/cgroup.procs").c_str(), O_WRONLY | O_CLOEXEC);
  int report_pipe[2] = {-1, -1};
  auto close_all = [&] {
    for (int fd : {log_fd, null_fd, cgroup_fd, report_pipe[0], report_pipe[1]})
      if (fd >= 0) close(fd);
  };
  if (null_fd >= 0 && pipe2(report_pipe, O_CLOEXEC) == 0)
    for (int& fd : report_pipe) fd = above_stderr(fd);
  if (null_fd < 0 || report_pipe[0] < 0 || report_pipe[1] < 0) {
    const int error = errno;
    close_all();
    fail(program, std::string("cannot start: ") + std::strerror(error));
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = report_pipe[1];
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    for (int sig = 1; sig < NSIG; ++sig)
      if (sig != SIGKILL && sig != SIGSTOP) sigaction(sig, &default_action, nullptr);
    if (spec.own_session) {
      if (setsid() < 0) child_failed(out, kSetup);
    } else if (spec.own_process_group && setpgid(0, 0) < 0) {
      child_failed(out, kSetup);
    }
    if (spec.parent_death_signal != 0) {
      if (prctl(PR_SET_PDEATHSIG, spec.parent_death_signal) != 0) child_failed(out, kSetup);
      if (getppid() != parent) _exit(128 + spec.parent_death_signal);  // it died already
    }
    if (cgroup_fd >= 0 && write(cgroup_fd, "0", 1) != 1) {
      // Not fatal: the parent tracks the child without its cgroup.
      const ChildReport report{kCgroup, errno};
      [[maybe_unused]] const ssize_t n = write(out, &report, sizeof(report));
    }
    move_fd(null_fd, STDIN_FILENO, out);
    move_fd(log_fd, STDOUT_FILENO, out);
    move_fd(log_fd, STDERR_FILENO, out);
    if (!spec.working_dir.empty() && chdir(spec.working_dir.c_str()) != 0)
      child_failed(out, kSetup);
    execve(path.c_str(), argv.data(), envp.data());
    child_failed(out, kExec);
  }
  const int fork_error = errno;
  close(report_pipe[1]);
  report_pipe[1] = -1;
  if (pid < 0) {
    close_all();
    fail(program, std::string("cannot start: ") + std::strerror(fork_error));
  }
  // The pipe closes on exec: reports before that are all there is.
  bool joined = cgroup_fd >= 0;
  int fatal_error = 0;
  ChildReport report{};
  ssize_t n = 0;
  while ((n = read(report_pipe[0], &report, sizeof(report))) != 0) {
    if (n < 0 && errno == EINTR) continue;
    if (n != static_cast<ssize_t>(sizeof(report))) break;
    if (report.step == kCgroup)
      joined = false;
    else
      fatal_error = report.error;
  }
  close_all();
  if (joined_cgroup) *joined_cgroup = joined;
  if (fatal_error != 0) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    fail(program, std::string("cannot start: ") + std::strerror(fatal_error));
  }
  return pid;
}

}  // namespace

pid_t start_child(const ChildSpec& spec, bool* joined_cgroup) {
  if (joined_cgroup) *joined_cgroup = false;
  if (spec.argv.empty() || spec.argv[0].empty()) fail("start_child", "no program given");
  const std::filesystem::path log_folder = std::filesystem::path(spec.log_path).parent_path();
  if (!log_folder.empty()) std::filesystem::create_directories(log_folder);

  std::vector<std::string> argv_strings = spec.argv;
  std::vector<char*> argv = pointers(argv_strings);
  std::vector<std::string> env_strings = child_environment(spec);
  std::vector<char*> envp = pointers(env_strings);
  if (spec.own_session || spec.parent_death_signal != 0 || !spec.cgroup.empty())
    return fork_child(spec, argv, envp, joined_cgroup);
  return spawn_child(spec, argv, envp);
}

std::string own_program_path() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("depot") : exe.string();
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 255;
}

}  // namespace depot
