#include "daemon/drivers/terminal_meter.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace vibscore::drivers {

namespace {

// Eighths of a cell, so the bar moves smoothly rather than in 5% steps.
constexpr std::array<std::string_view, 8> kEighths = {"", "▏", "▎", "▍", "▌", "▋", "▊", "▉"};

bool mentions_utf8(std::string_view value) {
    std::string lower(value);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return lower.find("utf-8") != std::string::npos || lower.find("utf8") != std::string::npos;
}

void write_all(int fd, const std::string& text) {
    // The meter is a convenience: a full pipe or a closed terminal must not disturb playback,
    // so failures are ignored, and only EINTR is retried.
    ssize_t written;
    do {
        written = ::write(fd, text.data(), text.size());
    } while (written < 0 && errno == EINTR);
}

}  // namespace

TerminalMeter::TerminalMeter(int fd, std::string label, Glyphs glyphs)
    : fd_(fd), label_(std::move(label)), glyphs_(glyphs) {}

TerminalMeter::~TerminalMeter() {
    if (drawn_) {
        write_all(fd_, "\n");
    }
}

TerminalMeter::Glyphs TerminalMeter::glyphs_for_environment() {
    // POSIX precedence: the first of these that is set and non-empty decides the character set.
    for (const char* name : {"LC_ALL", "LC_CTYPE", "LANG"}) {
        const char* value = std::getenv(name);
        if (value != nullptr && *value != '\0') {
            return mentions_utf8(value) ? Glyphs::unicode : Glyphs::ascii;
        }
    }
    return Glyphs::ascii;
}

std::string TerminalMeter::line(double strength, double frequency_hz) const {
    const double s = std::isnan(strength) ? 0.0 : std::clamp(strength, 0.0, 1.0);
    const int eighths = static_cast<int>(std::lround(s * kBarCells * 8));

    std::string text = label_ + "  ";
    int cells = 0;
    if (glyphs_ == Glyphs::unicode) {
        text += "▕";
        for (; cells < eighths / 8; ++cells) {
            text += "█";
        }
        if (eighths % 8 != 0) {
            text += kEighths[static_cast<std::size_t>(eighths % 8)];
            ++cells;
        }
    } else {
        text += "[";
        for (; cells < (eighths + 4) / 8; ++cells) {
            text += "#";
        }
    }
    text.append(static_cast<std::size_t>(kBarCells - cells), ' ');
    text += glyphs_ == Glyphs::unicode ? "▏" : "]";

    std::array<char, 32> numbers;
    if (frequency_hz >= 0.0 && std::isfinite(frequency_hz)) {
        std::snprintf(numbers.data(), numbers.size(), " %4.2f %5.0f Hz", s, frequency_hz);
    } else {
        std::snprintf(numbers.data(), numbers.size(), " %4.2f %8s", s, "");
    }
    return text + numbers.data();
}

void TerminalMeter::show(double strength, double frequency_hz) {
    write_all(fd_, "\r" + line(strength, frequency_hz));
    drawn_ = true;
}

}  // namespace vibscore::drivers
