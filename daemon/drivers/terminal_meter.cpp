#include "daemon/drivers/terminal_meter.hpp"

#include <sys/ioctl.h>
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
    if (region_rows_ > 0) {
        // Save the cursor, let the whole screen scroll again (which homes the cursor), come back,
        // and clear the meter's row so the prompt finds a clean screen.
        write_all(fd_,
                  "\0337\033[r\0338\0337\033[" + std::to_string(region_rows_) + ";1H\033[2K\0338");
    } else if (drawn_) {
        write_all(fd_, "\n");
    }
}

int TerminalMeter::own_row_terminal_rows() const {
    if (fd_ < 0 || ::isatty(fd_) != 1) {
        return 0;
    }
    const char* term = std::getenv("TERM");
    if (term == nullptr || *term == '\0' || std::string_view(term) == "dumb") {
        return 0;
    }
    winsize size{};
    if (::ioctl(fd_, TIOCGWINSZ, &size) != 0 || size.ws_row < 3) {
        return 0;
    }
    return size.ws_row;
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
    const int rows = own_row_terminal_rows();
    if (rows == 0) {
        if (region_rows_ > 0) {
            write_all(fd_, "\0337\033[r\0338");  // no longer a terminal we can keep a row of
            region_rows_ = 0;
        }
        write_all(fd_, "\r" + line(strength, frequency_hz));
        drawn_ = true;
        return;
    }
    std::string text;
    if (region_rows_ != rows) {
        // First draw, or the terminal was resized: a new line pushes what is on the bottom row up
        // into the region (the cursor then sits on the row above the meter's), and the region
        // becomes every row but the last. Setting a region homes the cursor: save and restore it.
        if (region_rows_ == 0) {
            text += "\n\033[A";
        }
        text += "\0337\033[1;" + std::to_string(rows - 1) + "r\0338";
        region_rows_ = rows;
    }
    text +=
        "\0337\033[" + std::to_string(rows) + ";1H\033[2K" + line(strength, frequency_hz) + "\0338";
    write_all(fd_, text);
    drawn_ = true;
}

}  // namespace vibscore::drivers
