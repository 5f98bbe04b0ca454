// Writes an output so that a reader sees the old file or the complete new one, never a partial one.
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>

namespace vr {

// Calls write(stream) on a temporary file beside `path`, flushes, fsyncs and renames it over `path`.
// On any failure the temporary file is removed, `path` is untouched, and InputError names `path`.
void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

// For writers that need a file name (e.g. OpenImageIO): fills the temporary path, then renames it.
void writePathAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& temporary)>& write);

}  // namespace vr
