// Other processes for the tests of folder handling: the id of one that has ended (its temp files
// are left over), one that lives while the test needs it, and a function run as an unprivileged
// user (root lists any folder, whatever its mode).
#pragma once

#include <functional>
#include <string>

#include <grp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace hoilcd::test {

// The id of a process that ran and has ended (and been reaped).
inline long DeadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return static_cast<long>(pid);
}

// A process that sleeps until this object goes away.
class LiveProcess {
 public:
  LiveProcess() : pid_(::fork()) {
    if (pid_ == 0) {
      for (;;) ::pause();
    }
  }
  ~LiveProcess() {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  LiveProcess(const LiveProcess&) = delete;
  LiveProcess& operator=(const LiveProcess&) = delete;
  long pid() const { return static_cast<long>(pid_); }

 private:
  pid_t pid_;
};

// What `work` returned, run in a child process as user and group nobody (65534) when this one is
// root, else as this user. `dropped` is false when root could not give up its privileges (no
// CAP_SETUID in this container): the caller then skips.
struct Unprivileged {
  bool dropped = false;
  std::string result;
};
inline Unprivileged RunUnprivileged(const std::function<std::string()>& work) {
  int fds[2];
  if (::pipe(fds) != 0) return {};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    constexpr gid_t kNobody = 65534;
    if (::geteuid() == 0 && (::setgroups(0, nullptr) != 0 || ::setgid(kNobody) != 0 || ::setuid(kNobody) != 0)) {
      ::_exit(2);
    }
    std::string result;
    try {
      result = work();
    } catch (const std::exception& e) {
      result = e.what();
    }
    if (::write(fds[1], result.data(), result.size()) < 0) ::_exit(3);
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string result;
  char buffer[512];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) result.append(buffer, static_cast<size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return {WIFEXITED(status) && WEXITSTATUS(status) == 0, result};
}

}  // namespace hoilcd::test
