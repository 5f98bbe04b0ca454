// Writes an output so that a reader sees the old file or the complete new one, never a partial one.
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>

namespace vr {

// Calls write(stream) on a temporary file beside `path`, flushes, fsyncs and renames it over `path`.
// On any failure the temporary file is removed, `path` is untouched, and InputError names `path`.
// The temporary is named ".STEM.tmp-PID-RANDOM.EXT" after `path` and the writing process. A process killed while it
// writes (SIGKILL) leaves it behind; the next write of `path` removes such leftovers: those whose process is gone
// or that nobody has written to for 10 minutes, never another file.
void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

// For writers that need a file name (e.g. OpenEXR's): fills the temporary path, then renames it.
void writePathAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& temporary)>& write);

// writePathAtomically for a writer that fills the temporary over a longer time (the frames of a movie, as they are
// rendered): the temporary is named on construction, renamed over `path` by commit(), and removed when the object
// is destroyed uncommitted (a failure on the way), `path` then untouched.
class PendingFile {
public:
    explicit PendingFile(std::filesystem::path path);  // throws InputError when path's folder does not exist
    ~PendingFile();
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;

    const std::filesystem::path& path() const { return path_; }
    const std::filesystem::path& temporary() const { return temporary_; }
    void commit();  // fsyncs and renames the temporary over path; throws InputError naming path

private:
    std::filesystem::path path_, temporary_;
    bool committed_ = false;
};

}  // namespace vr
