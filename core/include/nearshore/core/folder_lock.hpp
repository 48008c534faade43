#pragma once
// FolderLock: one writer per output folder. Two bakes into one folder at once would each write
// frames under the other's manifest and leave a mixed sequence that looks complete (issue 13); a
// loops run that writes its tables into a folder a bake is rewriting would vouch for frames that
// are about to change. Whoever writes a folder holds its lock for the whole run.
//
// The lock is flock(LOCK_EX | LOCK_NB) on FOLDER/.nearshore.lock, which holds the holder's PID and
// command line so the refused writer can name it. flock locks belong to the open file, so the
// kernel drops the lock when its holder exits or is killed: a crashed bake never leaves a folder
// locked, and there is no stale-lock heuristic. The file itself stays (removing it while another
// process waits on it would let two holders in); it is emptied when the lock is released, so two
// finished folders hold the same bytes. Readers ignore it: the manifest lists the sequence's files.
#include <filesystem>
#include <string>
#include <string_view>

namespace nearshore {

/// Name of the lock file inside a locked folder.
inline constexpr std::string_view kFolderLockFile = ".nearshore.lock";

class FolderLock {
 public:
  /// Takes the exclusive lock on `folder` (which must exist) at once, or throws nearshore::Error
  /// naming the folder and the process that holds it (PID and command). `purpose` says what the
  /// holder does ("baking harbour.toml"); it is written into the lock file for the refused ones.
  /// Also throws Error when the lock file cannot be created (a read-only folder), naming the reason.
  FolderLock(const std::filesystem::path& folder, std::string_view purpose);
  /// Empties the lock file and releases the lock.
  ~FolderLock();
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&& other) noexcept;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  const std::filesystem::path& folder() const { return folder_; }

 private:
  void release() noexcept;
  std::filesystem::path folder_;
  int descriptor_ = -1;
};

/// What the lock file of `folder` says about its holder ("PID 1234 (`nearshore bake ...`, baking
/// case.toml)"), or an empty string when there is no lock file or it is empty (released, or the
/// holder has not written it yet). A holder that was killed leaves its line behind, so this is
/// for messages and tests only: whether the folder is locked is the flock's answer alone.
std::string folder_lock_holder(const std::filesystem::path& folder);

}  // namespace nearshore
