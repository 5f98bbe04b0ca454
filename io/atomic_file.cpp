#include "io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <random>
#include <string>

#include "core/errors.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// The temporary of `path` written by process `pid`: ".STEM.tmp-PID-RANDOM.EXT", hidden, beside the output, with
// the extension kept last so that writers choosing a format by extension still see it.
fs::path temporaryBeside(const fs::path& path) {
    char tag[32];
    std::snprintf(tag, sizeof tag, "%ld-%08x", long(getpid()), unsigned(std::random_device()()));
    fs::path tmp = path;
    tmp.replace_filename("." + path.stem().string() + ".tmp-" + tag + path.extension().string());
    return tmp;
}

// The owning pid when `name` is a temporary of `path` as temporaryBeside() names them, else nothing.
std::optional<long> temporaryOwner(const std::string& name, const fs::path& path) {
    const std::string prefix = "." + path.stem().string() + ".tmp-", suffix = path.extension().string();
    if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix))
        return std::nullopt;
    const std::string tag = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    const std::size_t dash = tag.find('-');
    if (dash == 0 || dash == std::string::npos || dash > 10 || tag.size() - dash - 1 != 8) return std::nullopt;
    for (std::size_t i = 0; i < tag.size(); ++i)
        if (i != dash && !(i < dash ? std::isdigit(static_cast<unsigned char>(tag[i]))
                                    : std::isxdigit(static_cast<unsigned char>(tag[i]))))
            return std::nullopt;
    return std::stol(tag.substr(0, dash));
}

// Removes what earlier writes of `path` left when they were killed (SIGKILL runs no cleanup): temporaries whose
// owning process is gone, or that nobody has written to for longer than a live writer would pause (their pid
// reused, or written from another machine). Anything else in the folder is left alone, as is a failure to remove.
void removeStaleTemporaries(const fs::path& path, const fs::path& folder) {
    constexpr auto kAbandoned = std::chrono::minutes(10);
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::optional<long> owner = temporaryOwner(it->path().filename().string(), path);
        std::error_code fileEc;
        if (!owner || *owner == long(getpid()) || !it->is_regular_file(fileEc)) continue;
        const bool ownerGone = ::kill(pid_t(*owner), 0) != 0 && errno == ESRCH;
        const auto written = it->last_write_time(fileEc);
        if (ownerGone || (!fileEc && fs::file_time_type::clock::now() - written > kAbandoned))
            fs::remove(it->path(), fileEc);
    }
}

void syncFile(const fs::path& p) {
    int fd = ::open(p.c_str(), O_RDONLY);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
}

}  // namespace

PendingFile::PendingFile(fs::path path) : path_(std::move(path)) {
    const fs::path parent = path_.parent_path().empty() ? fs::path(".") : path_.parent_path();
    if (!fs::is_directory(parent))
        throw fileError(path_.string(), "cannot write: folder " + parent.string() + " does not exist");
    removeStaleTemporaries(path_, parent);
    temporary_ = temporaryBeside(path_);
}

PendingFile::~PendingFile() {
    if (committed_) return;
    std::error_code ignored;
    fs::remove(temporary_, ignored);
}

void PendingFile::commit() {
    if (!fs::exists(temporary_)) throw fileError(path_.string(), "cannot write: nothing was written");
    syncFile(temporary_);
    std::error_code ec;
    fs::rename(temporary_, path_, ec);
    if (ec) throw fileError(path_.string(), "cannot write: " + ec.message());
    committed_ = true;
}

void writePathAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    PendingFile file(path);
    write(file.temporary());
    file.commit();
}

void writeFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
    writePathAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw fileError(path.string(), std::string("cannot write: ") + std::strerror(errno));
        write(out);
        out.flush();
        if (!out) throw fileError(path.string(), "cannot write: output error (disk full?)");
    });
}

}  // namespace vr
