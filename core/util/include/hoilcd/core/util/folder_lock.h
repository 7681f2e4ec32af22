// One process at a time in an output folder: an advisory lock (flock(2)) on DIR/hoilcd.lock, which
// every command that writes a dataset, shard, merge, suite, sweep or generate folder holds while it
// writes. The second process is refused by name, or waits where waiting is the point (a dataset in
// a cache that several suites share). The lock file is deleted when the last holder lets go; one
// left by a killed process is taken over. A holder may go on reading under a shared lock (Share).
#pragma once

#include <string>

#include <sys/types.h>

namespace hoilcd {

// The lock file's name inside the folder it locks: hoilcd's own, never counted as a user's file.
inline constexpr const char* kFolderLockFile = "hoilcd.lock";

class FolderLock {
 public:
  enum class IfBusy {
    kRefuse,  // InputError(dir, "is in use by another hoilcd process (pid N) ...")
    kWait,    // wait for the other process to let go, saying so on the progress line
  };

  // Creates dir (and its parents) when missing, then locks it. A thread that already holds the
  // lock of this folder takes it again at once (a render inside `hoilcd run`'s locked cache
  // folder); another thread of this process is a second holder, refused or waiting like another
  // process. InputError(dir, ...) when the folder cannot be created or its lock file not opened.
  FolderLock(const std::string& dir, IfBusy if_busy);
  // Lets go of the lock; the last holder deletes the lock file (the next makes its own) and removes
  // the folder again when its lock created it and it is still empty.
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  // From writing to reading: other readers may share the lock, a writer waits (or is refused)
  // until the last one lets go. For a folder kept while it is read after its writes (a cached
  // dataset while it is benched, so that no --drop-datasets deletes it meanwhile). Nothing for a
  // lock this thread held already.
  void Share();

  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  int fd_ = -1;               // the lock file, flocked; -1 when this thread held the lock already
  bool created_dir_ = false;  // this lock made the folder
  dev_t dev_ = 0;             // the folder's identity (st_dev, st_ino): the key of this thread's locks
  ino_t ino_ = 0;
};

// Whether a process with this id runs (kill(pid, 0)): a temp file "NAME.tmp.PID" of a live process
// is still being written, one of a dead process is left over.
bool ProcessAlive(long pid);

}  // namespace hoilcd
