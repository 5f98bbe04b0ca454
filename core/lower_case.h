// Text in lower case (ASCII), for the names and header values that files and users spell in any case.
#pragma once
#include <cctype>
#include <string>

namespace vr {

inline std::string lowerCase(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

}  // namespace vr
