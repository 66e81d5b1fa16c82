#include "common/quoted_text.hpp"

#include <algorithm>

namespace vibscore {

namespace {

constexpr std::size_t kShown = 80;

// Up to kShown bytes of `text`, with control characters escaped.
std::string escaped_prefix(std::string_view text) {
    std::size_t cut = std::min(kShown, text.size());
    // Not inside a UTF-8 character: back to its first byte (at most three continuation bytes),
    // so a cut name stays readable.
    const auto continues = [&](std::size_t at) {
        return at < text.size() && (static_cast<unsigned char>(text[at]) & 0xc0) == 0x80;
    };
    for (int back = 0; back < 3 && cut > 0 && continues(cut); ++back) {
        --cut;
    }
    std::string shown;
    for (const char c : text.substr(0, cut)) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f) {
            constexpr std::string_view hex = "0123456789abcdef";
            shown += {'\\', 'x', hex[byte >> 4], hex[byte & 0xf]};
        } else {
            shown += c;
        }
    }
    return shown;
}

std::string size_note(std::string_view text) {
    return text.size() > kShown ? "... (" + std::to_string(text.size()) + " bytes)" : "";
}

}  // namespace

std::string quoted_text(std::string_view text) {
    return "\"" + escaped_prefix(text) + "\"" + size_note(text);
}

std::string shown_text(std::string_view text) {
    return escaped_prefix(text) + size_note(text);
}

}  // namespace vibscore
