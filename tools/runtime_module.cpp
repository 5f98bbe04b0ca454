#include "tools/runtime_module.h"

#include <dlfcn.h>

#include <stdexcept>

namespace vr {
namespace fs = std::filesystem;

fs::path moduleFolder() {
    std::error_code ec;
    const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find the running executable (/proc/self/exe): " + ec.message());
    return executable.parent_path().parent_path() / VR_MODULE_FOLDER;
}

void* moduleEntry(const std::string& name, const char* symbol, const std::string& purpose) {
    const fs::path file = moduleFolder() / (name + ".so");
    const auto fail = [&](const char* reason) {
        // dlerror() starts with the file's path where it names one: said once, in front.
        const std::string prefix = file.string() + ": ";
        std::string why = reason ? reason : "no such entry";
        if (why.starts_with(prefix)) why.erase(0, prefix.size());
        return std::runtime_error(file.string() + ": cannot load the module that " + purpose + ": " + why);
    };
    // RTLD_LOCAL: its symbols stay its own. Never closed: the objects it makes live as long as the process.
    void* module = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) throw fail(dlerror());
    void* entry = dlsym(module, symbol);
    if (!entry) throw fail(dlerror());
    return entry;
}

}  // namespace vr
