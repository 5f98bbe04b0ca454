#include "fuzz/support.h"

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <new>

#include "core/errors.h"
#include "preprocess/load/load_volume.h"

// Allocations fail as in an ordinary build: an impossible size (a length field OpenVDB trusts, up to 2^64) gives
// std::bad_alloc, which the loaders turn into InputError, where ASan's own operator new would abort. Sizes that can
// be served still meet libFuzzer's -malloc_limit_mb, so allocating what a header claims stays a finding. (ASan's
// new/delete mismatch check cannot tell these from its own operators, so it is off.)
extern "C" const char* __asan_default_options() { return "allocator_may_return_null=1:alloc_dealloc_mismatch=0"; }

void* operator new(std::size_t bytes) {
    if (void* p = std::malloc(bytes ? bytes : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t bytes) { return operator new(bytes); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace vr::fuzz {
namespace fs = std::filesystem;

const fs::path& scratchDir() {
    static const fs::path dir = [] {
        const char* given = std::getenv("VR_FUZZ_SCRATCH");  // scripts/fuzz.sh: one folder it removes, crashes too
        const fs::path base = given              ? fs::path(given)
                              : fs::is_directory("/dev/shm") ? fs::path("/dev/shm")
                                                             : fs::temp_directory_path();
        fs::path d = base / ("vr_fuzz_" + std::to_string(getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

fs::path writeInput(const std::string& name, std::string_view bytes) {
    const fs::path path = scratchDir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) finding("cannot write the scratch file " + path.string());
    return path;
}

NamedInput splitNamedInput(const uint8_t* data, std::size_t size, std::initializer_list<std::string_view> suffixes) {
    const std::string_view all(reinterpret_cast<const char*>(data), size);
    const std::size_t eol = all.find('\n');
    const std::string_view line = all.substr(0, eol);
    NamedInput input;
    // Letters, digits and ._- only, at most 100 of them: enough for any name the loaders parse, never a path.
    for (char c : line.substr(0, 100))
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') input.name += c;
    if (input.name.empty() || input.name.front() == '.') input.name.insert(0, "f");
    bool named = false;
    for (std::string_view s : suffixes) named = named || input.name.ends_with(s);
    if (!named) input.name += *suffixes.begin();
    input.bytes = eol == std::string_view::npos ? std::string_view() : all.substr(eol + 1);
    return input;
}

void loadExpectingInputError(const fs::path& path) {
    Volume v;
    try {
        v = loadVolume(path);
    } catch (const InputError& e) {
        if (std::getenv("VR_FUZZ_VERBOSE")) std::fprintf(stderr, "InputError: %s\n", e.what());
        return;
    }
    const Vec3i d = v.grid.dims;
    if (d.x <= 0 || d.y <= 0 || d.z <= 0) finding("loadVolume returned non-positive dims");
    if (v.values.size() != v.grid.voxels()) finding("loadVolume returned a volume whose values do not fit its dims");
    for (int a = 0; a < 3; ++a)
        if (!(std::isfinite(v.grid.spacing[a]) && v.grid.spacing[a] > 0) || !std::isfinite(v.grid.origin[a]))
            finding("loadVolume returned a non-positive or non-finite spacing or origin");
    for (float f : v.values)
        if (!std::isfinite(f)) finding("loadVolume returned a non-finite voxel");
    if (std::getenv("VR_FUZZ_VERBOSE")) std::fprintf(stderr, "loaded %dx%dx%d\n", d.x, d.y, d.z);
}

void finding(const std::string& what) {
    std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
    std::abort();
}

}  // namespace vr::fuzz
