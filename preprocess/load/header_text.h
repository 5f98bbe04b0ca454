// Values in the text headers of NRRD and MetaImage files.
#pragma once
#include <sstream>
#include <string>
#include <vector>

namespace vr {

// Without the spaces, tabs and carriage returns around it.
inline std::string trimmed(const std::string& s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The whitespace-separated words of `text`.
inline std::vector<std::string> words(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> out;
    for (std::string word; in >> word;) out.push_back(word);
    return out;
}

// The whitespace-separated integers that make up all of `text`, or none where anything else is in it, a token
// such as "10+0" too (read as 10 and +0 it split one size in two, where VTK's readers take 10: found by fuzz_nrrd).
inline std::vector<long long> integers(const std::string& text) {
    std::vector<long long> values;
    for (const std::string& token : words(text)) {
        std::istringstream one(token);
        long long v;
        if (!(one >> v) || one.peek() != std::char_traits<char>::eof()) return {};
        values.push_back(v);
    }
    return values;
}

}  // namespace vr
