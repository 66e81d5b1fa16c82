#include "client/number_options.hpp"

#include <charconv>
#include <cmath>

#include "common/number_text.hpp"

namespace vibscore::client {

CLI::Validator number_between(double lowest, double highest, NumberKind kind) {
    const std::string bounds = std::isinf(highest)
                                   ? number_text(lowest) + " or more"
                                   : number_text(lowest) + " to " + number_text(highest);
    return CLI::Validator(
        [lowest, highest, bounds, kind](std::string& text) -> std::string {
            double value = 0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data(), end, value);
            if (text.empty() || error != std::errc() || stop != end || !std::isfinite(value)) {
                return "not a number: " + text;
            }
            if (kind == NumberKind::whole && text.find_first_of(".eE") != std::string::npos) {
                return "not a whole number: " + text;
            }
            if (value < lowest || value > highest) {
                return text + " is out of range (" + bounds + ")";
            }
            return {};
        },
        "NUMBER " + bounds);
}

}  // namespace vibscore::client
