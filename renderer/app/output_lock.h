// The advisory lock (flock(2)) a running `kiln batch` holds on its output folder, through the
// file .kiln-batch.lock inside it. It covers the folder's whole subtree: a second batch on the
// folder or on a folder inside it is refused (or waits), and so is a `kiln render -o` or another
// batch's output anywhere below it, so two runs never mix their outputs. App layer only.
#pragma once

#include <string>

namespace kiln {

// The lock file's name inside an output folder.
extern const char* const output_lock_name;

// Holds the lock on a folder for its lifetime; removes the lock file when released.
class output_folder_lock {
 public:
  // Takes the lock on folder (which exists). Another holder of it or of a folder above it: throws
  // kiln::error (input) naming the folder and the holder's pid, or, with wait, waits for it (a signal stops
  // the wait: kind interrupted). Throws kiln::error (io) when the lock file cannot be created, and (input)
  // when what is at its name is not a lock file kiln made (a symbolic link, a hard link, a FIFO, a file
  // holding anything but a pid): that is refused and left as it is, and nothing is written through it.
  output_folder_lock(const std::string& folder, bool wait);
  ~output_folder_lock();
  output_folder_lock(const output_folder_lock&) = delete;
  output_folder_lock& operator=(const output_folder_lock&) = delete;

 private:
  int fd_ = -1;
  std::string path_;
};

// Throws kiln::error (input) when path lies in a folder, or below one, whose lock a running batch
// holds; with own_folder (a batch's own --out-dir, whose lock is its own), only the folders below
// own_folder are looked at. Takes no lock itself, creates nothing, and follows no symbolic link at
// a lock file's name.
void check_not_in_locked_folder(const std::string& path, const std::string& own_folder = "");

}  // namespace kiln
