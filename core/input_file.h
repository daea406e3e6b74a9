// Opening a file that a scene or the command line names (issue 38). Every reader of such a file
// goes through here before it, or a library, opens the file: scenes and includes, meshes, images,
// spectra, volume grids, checkpoints, and any new reader (a glTF loader's .gltf/.glb and buffers).
//
// The file must be a regular file. A device never ends (/dev/zero, /dev/urandom: a reader grows
// a buffer until the machine runs out, and OpenImageIO's format probe spins on it), a FIFO's open
// waits for a writer, and a directory is not data; all three are refused with their kind named,
// before any byte is read. The check stat()s first, so a device is never opened (opening some has
// side effects, e.g. a tape rewinds), then opens with O_NONBLOCK and checks again on the open
// descriptor, so a file swapped for a FIFO in between cannot block either. Reads are bounded by
// the file's size at that moment and by a limit per format (the kMax* constants below), and a
// file read whole is checked against the memory budget (core/memory_budget.h) first.
//
// Usage in a new reader (the glTF loader, for instance):
//
//     const std::string bytes = readInputFile(path, "glTF buffer", kMaxMeshFileBytes);   // our parser
//     checkInputFile(path, "image");  // a library opens `path` itself right after
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace iris {

/// No limit of the format's own (the memory budget still applies to a file read whole).
inline constexpr uint64_t kNoFormatLimit = UINT64_MAX;
/// Scene files and <include>d files: 1 GiB (a scene of 10^6 spheres written out is about 0.3 GiB).
inline constexpr uint64_t kMaxSceneFileBytes = uint64_t(1) << 30;
/// `.spd` spectra: 16 MiB (a 1 nm table over 360-830 nm is about 6 KiB).
inline constexpr uint64_t kMaxSpectrumFileBytes = uint64_t(16) << 20;

/// Check that `path` names a regular file this process can open for reading and return its size
/// in bytes. `kind` names the file in messages ("spectrum file"). Throws iris::Error
/// "path: cannot open <kind>: file not found" (or the system's reason), "path: cannot open <kind>:
/// it is a character device, not a regular file" (block device, FIFO, socket, directory), or
/// "path: <kind> of X exceeds the limit of Y for a <kind>" when the file is larger than `maxBytes`.
uint64_t checkInputFile(const std::string& path, std::string_view kind, uint64_t maxBytes = kNoFormatLimit);

/// The bytes of `path`, after the checks of checkInputFile, read from the descriptor that was
/// checked: at most the size the file had when it was opened (a file that grows meanwhile is read
/// to that size) and at most `maxBytes`. The size is checked against the memory budget before the
/// buffer is allocated (checkMemory: held while the caller parses it, not charged to the scene).
/// Throws iris::Error as checkInputFile does, and "path: read error ..." on a failed read.
std::string readInputFile(const std::string& path, std::string_view kind, uint64_t maxBytes = kNoFormatLimit);

}  // namespace iris
