#include "hoilcd/core/util/folder_lock.h"

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/progress.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// The folders whose lock a thread of this process holds, by (st_dev, st_ino), with how many
// FolderLocks of that thread hold it.
struct Holder {
  std::thread::id thread;
  int depth = 0;
};
std::mutex& HeldMutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<std::pair<dev_t, ino_t>, Holder>& Held() {
  static std::map<std::pair<dev_t, ino_t>, Holder> held;
  return held;
}

std::string Errno() { return std::strerror(errno); }

// The process holding an flock on the open file fd, from /proc/locks
// ("3: FLOCK  ADVISORY  WRITE 1234 08:01:5678 0 EOF"), or 0 when it cannot be told.
long LockHolder(int fd) {
  struct stat info {};
  if (::fstat(fd, &info) != 0) return 0;
  std::ifstream locks("/proc/locks");
  std::string line;
  while (std::getline(locks, line)) {
    char kind[16] = {}, mode[16] = {}, access[16] = {};
    long pid = 0;
    unsigned major_id = 0, minor_id = 0;
    unsigned long inode = 0;
    if (line.find("->") != std::string::npos) continue;  // a waiter, not the holder
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    if (std::sscanf(line.c_str() + colon + 1, "%15s %15s %15s %ld %x:%x:%lu", kind, mode, access, &pid, &major_id,
                    &minor_id, &inode) != 7) {
      continue;
    }
    if (std::strcmp(kind, "FLOCK") == 0 && inode == info.st_ino && major_id == major(info.st_dev) &&
        minor_id == minor(info.st_dev)) {
      return pid;
    }
  }
  return 0;
}

}  // namespace

FolderLock::FolderLock(const std::string& dir, IfBusy if_busy) : dir_(dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    fs::create_directories(dir, ec);
    if (ec) throw InputError(dir, "cannot create the folder (" + ec.message() + ")");
    created_dir_ = true;
  }
  struct stat folder {};
  if (::stat(dir.c_str(), &folder) != 0 || !S_ISDIR(folder.st_mode)) {
    throw InputError(dir, "is a file: expected a folder to write into");
  }
  dev_ = folder.st_dev;
  ino_ = folder.st_ino;
  {
    const std::lock_guard<std::mutex> guard(HeldMutex());
    const auto it = Held().find({dev_, ino_});
    if (it != Held().end() && it->second.thread == std::this_thread::get_id()) {
      ++it->second.depth;
      return;
    }
  }
  const std::string path = dir + "/" + kFolderLockFile;
  int unnamed_holders = 0;  // times the lock was busy and /proc/locks named no holder
  for (;;) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0 && errno == ENOENT) {  // the holder we waited for made the folder, and removed it empty
      fs::create_directories(dir, ec);
      if (ec) throw InputError(dir, "cannot create the folder (" + ec.message() + ")");
      created_dir_ = true;
      continue;
    }
    if (fd_ < 0) throw InputError(path, "cannot open the folder's lock file: " + Errno());
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      if (errno != EWOULDBLOCK) {
        const std::string why = Errno();
        ::close(fd_);
        throw InputError(path, "cannot lock the folder's lock file: " + why);
      }
      const long holder = LockHolder(fd_);
      if (holder == 0 && ++unnamed_holders < 3) {  // let go of just now, most likely: try again
        ::close(fd_);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      const std::string who = "another hoilcd process" + (holder > 0 ? " (pid " + std::to_string(holder) + ")" : "");
      if (if_busy == IfBusy::kRefuse) {
        ::close(fd_);
        throw InputError(dir, std::string("is in use by ") + who + ", which holds its lock file " + kFolderLockFile +
                                  "; wait for it to finish, or choose another folder");
      }
      ProgressReporter waiting("waiting for " + who + " to finish with " + dir, 1, "folder");
      while (::flock(fd_, LOCK_EX) != 0) {
        if (errno == EINTR) continue;
        const std::string why = Errno();
        ::close(fd_);
        throw InputError(path, "cannot lock the folder's lock file: " + why);
      }
      waiting.Update();
    }
    // The file locked must still be the folder's lock file: a holder deletes it before letting go,
    // so a waiter may hold a file no longer in the folder, and must lock the new one.
    struct stat locked {
    }, named{};
    if (::fstat(fd_, &locked) == 0 && ::stat(path.c_str(), &named) == 0 && locked.st_dev == named.st_dev &&
        locked.st_ino == named.st_ino) {
      break;
    }
    ::close(fd_);
    fd_ = -1;
  }
  if (::stat(dir.c_str(), &folder) == 0) {  // made again if the holder waited for removed it
    dev_ = folder.st_dev;
    ino_ = folder.st_ino;
  }
  const std::lock_guard<std::mutex> guard(HeldMutex());
  Held()[{dev_, ino_}] = {std::this_thread::get_id(), 1};
}

FolderLock::~FolderLock() {
  {
    const std::lock_guard<std::mutex> guard(HeldMutex());
    const auto it = Held().find({dev_, ino_});
    if (fd_ < 0) {
      if (it != Held().end()) --it->second.depth;
      return;
    }
    if (it != Held().end()) Held().erase(it);
  }
  // Alone (the exclusive lock is ours, or no other reader shares it): the lock file goes too. A
  // failed conversion lets go of the shared lock, which is being let go of anyway.
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) ::unlink((dir_ + "/" + kFolderLockFile).c_str());
  ::close(fd_);
  if (created_dir_) {
    std::error_code ec;
    if (fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
  }
}

void FolderLock::Share() {
  // flock(2) converts in place; a waiting writer may take the lock in between, and this call then
  // waits for it to finish (it found the folder as this holder left it).
  if (fd_ >= 0) {
    while (::flock(fd_, LOCK_SH) != 0) {
      if (errno != EINTR) throw InputError(dir_ + "/" + kFolderLockFile, "cannot share the folder's lock: " + Errno());
    }
  }
}

bool ProcessAlive(long pid) {
  if (pid <= 0 || pid > INT_MAX) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

}  // namespace hoilcd
