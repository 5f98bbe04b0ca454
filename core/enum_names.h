// An enumeration's names in one table, read both ways: to print a value and to parse a flag or a file's field.
// A value's first name is its own; later ones are spellings also accepted.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

#include "core/errors.h"

namespace vr {

template <typename Enum>
struct EnumName {
    Enum value;
    std::string_view name;
};

template <typename Enum, std::size_t N>
constexpr std::string_view nameOf(const EnumName<Enum> (&names)[N], Enum value) {
    for (const EnumName<Enum>& n : names)
        if (n.value == value) return n.name;
    return "unknown";
}

// The value named `name`; else throws InputError "unknown KIND 'NAME' (expected a, b or c)".
template <typename Enum, std::size_t N>
Enum valueNamed(const EnumName<Enum> (&names)[N], std::string_view name, std::string_view kind) {
    for (const EnumName<Enum>& n : names)
        if (n.name == name) return n.value;
    std::string expected;
    std::size_t listed = 0, own = 0;
    for (std::size_t i = 0; i < N; ++i) own += nameOf(names, names[i].value) == names[i].name;
    for (std::size_t i = 0; i < N; ++i) {
        if (nameOf(names, names[i].value) != names[i].name) continue;  // another spelling
        expected += std::string(listed == 0 ? "" : listed + 1 == own ? " or " : ", ") + std::string(names[i].name);
        ++listed;
    }
    throw InputError("unknown " + std::string(kind) + " '" + std::string(name) + "' (expected " + expected + ")");
}

}  // namespace vr
