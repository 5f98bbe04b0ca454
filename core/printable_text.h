// Text from a file, made fit for a message: a header value or a line quoted back to the user may hold control bytes
// or binary data (a colour table that is a binary LUT printed its bytes to the terminal), and may be megabytes long.
#pragma once
#include <cstdio>
#include <string>
#include <string_view>

namespace vr {

// `text` with each control byte and each byte that is not part of valid UTF-8 written as \xNN (valid UTF-8, such as
// a name in another script, is kept), cut after `most` bytes of it with "...".
inline std::string printableText(std::string_view text, std::size_t most = 200) {
    std::string out;
    const auto escape = [&](unsigned char c) {
        char hex[5];
        std::snprintf(hex, sizeof hex, "\\x%02X", c);
        out += hex;
    };
    std::size_t i = 0;
    for (; i < text.size() && i < most;) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        // The length of the UTF-8 sequence c starts (0: c cannot start one).
        const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 && c >= 0xC2 ? 2 : (c >> 4) == 0xE ? 3
                                          : (c >> 3) == 0x1E && c <= 0xF4  ? 4 : 0;
        bool valid = n > 0 && i + n <= text.size();
        for (std::size_t k = 1; valid && k < n; ++k) valid = (static_cast<unsigned char>(text[i + k]) >> 6) == 0x2;
        if (!valid || (n == 1 && (c < 0x20 || c == 0x7F))) {
            escape(c);
            ++i;
            continue;
        }
        out.append(text.substr(i, n));
        i += n;
    }
    if (i < text.size()) out += "...";
    return out;
}

}  // namespace vr
