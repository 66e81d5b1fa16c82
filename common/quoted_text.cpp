#include "common/quoted_text.hpp"

namespace vibscore {

std::string quoted_text(std::string_view text) {
    constexpr std::size_t shown = 80;
    std::string quoted = "\"";
    for (const char c : text.substr(0, shown)) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f) {
            constexpr std::string_view hex = "0123456789abcdef";
            quoted += {'\\', 'x', hex[byte >> 4], hex[byte & 0xf]};
        } else {
            quoted += c;
        }
    }
    quoted += '"';
    if (text.size() > shown) {
        quoted += "... (" + std::to_string(text.size()) + " bytes)";
    }
    return quoted;
}

}  // namespace vibscore
