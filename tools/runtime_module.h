// Parts of the tools built as shared modules, loaded by a run only when it needs them (movies through FFmpeg, the
// file formats VTK and OpenVDB read): their libraries number over a hundred, and linked into the executables they
// would be loaded and relocated at every start, --help included.
#pragma once
#include <filesystem>
#include <string>

namespace vr {

// Where the modules are: lib/volrender/ in the folder above the running executable's, so that
// PREFIX/bin/volrender finds PREFIX/lib/volrender/ and the build tree's build/volrender/volrender build/lib/volrender/.
std::filesystem::path moduleFolder();

// The entry `symbol` of module `name` (moduleFolder()/NAME.so), loaded on first use and kept for the process.
// `purpose` says what the module does ("writes movies"). Throws std::runtime_error naming the file looked for, the
// purpose and the loader's reason (dlerror()) when the module cannot be loaded or lacks the entry.
void* moduleEntry(const std::string& name, const char* symbol, const std::string& purpose);

// moduleEntry as a function of the entry's own type: moduleFunction<decltype(entryName)>(...).
template <typename Function>
Function* moduleFunction(const std::string& name, const char* symbol, const std::string& purpose) {
    return reinterpret_cast<Function*>(moduleEntry(name, symbol, purpose));
}

}  // namespace vr
