#include "atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <random>

#include "errors.h"

namespace vr {
namespace fs = std::filesystem;

static fs::path temporaryBeside(const fs::path& path) {
    std::random_device rd;
    fs::path tmp = path;
    // Keep the extension last so that writers choosing a format by extension still see it.
    tmp.replace_filename("." + path.stem().string() + ".tmp" + std::to_string(rd() % 1000000) +
                         path.extension().string());
    return tmp;
}

static void syncFile(const fs::path& p) {
    int fd = ::open(p.c_str(), O_RDONLY);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
}

void writePathAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(parent)) throw fileError(path.string(), "cannot write: folder " + parent.string() + " does not exist");
    fs::path tmp = temporaryBeside(path);
    try {
        write(tmp);
        if (!fs::exists(tmp)) throw fileError(path.string(), "cannot write: nothing was written");
        syncFile(tmp);
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (ec) throw fileError(path.string(), "cannot write: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
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
