// Errors a user can cause (bad files, bad flags). The CLI prints what() and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace vr {

// Bad input: the message names the file (or flag) and the problem.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

inline InputError fileError(const std::string& path, const std::string& problem) {
    return InputError(path + ": " + problem);
}

}  // namespace vr
