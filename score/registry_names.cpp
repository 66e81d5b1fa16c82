#include "score/registry_names.hpp"

#include <algorithm>

namespace vibscore {

bool is_valid_name(std::string_view name) {
    constexpr std::size_t kMaxNameChars = 64;
    const auto letter_or_digit = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    };
    return !name.empty() && name.size() <= kMaxNameChars && letter_or_digit(name.front()) &&
           std::all_of(name.begin(), name.end(), [&](char c) {
               return letter_or_digit(c) || c == '.' || c == '_' || c == '-';
           });
}

std::optional<std::string> clef_name_in_href(std::string_view href) {
    if (href.find('/') != std::string_view::npos) {
        return std::nullopt;
    }
    if (href.ends_with(kClefSuffix)) {
        href.remove_suffix(kClefSuffix.size());
    } else if (href.ends_with(".xml")) {
        href.remove_suffix(4);
    }
    if (!is_valid_name(href)) {
        return std::nullopt;
    }
    return std::string(href);
}

}  // namespace vibscore
