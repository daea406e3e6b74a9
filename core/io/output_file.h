// Output files that are checked before the work and cannot lose it after (issue 38 item 4): a
// render of ten minutes to `-o /nonexistent/dir/out.exr` rendered, then failed, and lost the image.
//
// checkOutputPath runs before the scene is loaded: the path must not be a directory or another
// non-regular file (the atomic writer renames over the path, so `-o /dev/null` as root would replace
// the device), and its folder must exist and take a new file (a probe file is created and removed
// there, as the atomic writer's temporary will be: this also catches read-only mounts and full
// quotas that permission bits do not show). writeWithFallback runs at the end: if the write still
// fails (the folder was removed, the disk filled up), the same data goes to a fallback path and the
// error names it, so that nothing computed is lost.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace iris {

/// Throws iris::Error "<option> <path>: <reason>" ("-o /x/y.exr: the folder /x does not exist") if
/// `path` cannot be written as described above. `option` names where the path came from.
void checkOutputPath(const std::string& path, std::string_view option);

/// The folder for temporary and cache files: $TMPDIR when set and not empty, else /tmp. Unlike
/// std::filesystem::temp_directory_path it does not throw for a TMPDIR that is not a folder: the
/// write there fails instead, with an error that names the path.
std::string temporaryFolder();

/// Where writeWithFallback tries next, in order: the current folder, then $TMPDIR (or /tmp), each as
/// "iris-rescued-<pid>-<file name>" (the current folder is skipped when it is the path's own folder).
std::vector<std::string> fallbackPaths(const std::string& path);

/// write(path); if that throws iris::Error, write(p) for each of fallbackPaths(path) until one
/// succeeds, then throw iris::Error "<the first error>; written to <p> instead" (or "...; not
/// written to a fallback either (<p1>, <p2>)"), so the caller still reports a failure.
void writeWithFallback(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace iris
