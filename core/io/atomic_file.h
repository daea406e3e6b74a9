// Atomic file output: every file iris writes (images, checkpoints, table caches) appears either
// complete or not at all, and a failed write (full disk, unwritable folder, I/O error) leaves the
// previous file untouched and no temporary behind. The data goes to a temporary file in the same
// folder ("<path>.tmp-<pid>-<n>", unique per process and call, so concurrent writers of one path
// never share it), which is fsync'ed and renamed over the path; the folder is fsync'ed so the
// rename survives a crash (the POSIX rename(2) guarantee; see also the "ext4 data loss"
// discussion around rename-without-fsync).
//
// Fault injection for tests: IRIS_FAULT_DISK_FULL_AFTER=N makes every atomic write fail with
// ENOSPC once its file would exceed N bytes, as a disk with N bytes free would; and
// IRIS_FAULT_KILL_WRITING=N makes a process writing through writeFileAtomically (checkpoints,
// table caches, PNG) kill itself with SIGKILL once N bytes of the temporary are written, leaving
// the temporary behind as a kill -9 would; IRIS_FAULT_SIGNAL_BEFORE_RENAME=INT|TERM|KILL raises that
// signal when the temporary is complete, just before the rename; IRIS_FAULT_UNWRITABLE=PATH makes
// every atomic write of exactly PATH fail with EROFS (docs/testing.md).
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace iris {

/// Write `bytes` to `path` atomically. Throws iris::Error "path: <reason>" on failure.
void writeFileAtomically(const std::string& path, std::string_view bytes);

/// Let `writeTemp` write the file at the temporary path it is given (e.g. through a library that
/// only writes to paths), then make it durable and rename it over `path`. If `writeTemp` throws,
/// the temporary is removed and the exception propagates; other failures throw iris::Error.
void writeFileAtomicallyWith(const std::string& path, const std::function<void(const std::string& tempPath)>& writeTemp);

/// The temporary path the next atomic write of `path` by this process would use (unique per call).
std::string atomicTempPath(const std::string& path);

}  // namespace iris
