#include "client/editor/clef_editor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "client/editor/status_line.hpp"
#include "daemon/render/waveform.hpp"
#include "score/limits.hpp"

namespace vibscore::editor {

namespace {

// Steps that suit each value: frequencies in 5 Hz, fine 1 Hz; amplitudes and levels 0.1, fine
// 0.01; tempo 10 ms, fine 1 ms; point times 0.05 of the quarter note, fine 0.01.
constexpr double kHz = 5.0, kFineHz = 1.0;
constexpr double kAmplitude = 0.1, kFineAmplitude = 0.01;
constexpr double kTempo = 0.010, kFineTempo = 0.001;
constexpr double kTime = 0.05, kFineTime = 0.01;
constexpr int kFewestPoints = 2;

// A value stepped and kept to its range, rounded to the fine step so repeated steps stay exact.
double stepped_value(double value, double step, double fine, double lowest, double highest) {
    const double moved = std::round((value + step) / fine) * fine;
    return std::clamp(moved, lowest, highest);
}

std::string number_text(double value, const char* format) {
    char text[32];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

// Number `number` (1-based) against its neighbours: a number is meant to play at least as
// strong as the one below it.
std::string out_of_order(const std::vector<double>& numbers, int number) {
    const auto at = [&](int n) { return numbers[static_cast<std::size_t>(n - 1)]; };
    const auto named = [&](int n) {
        return "n" + std::to_string(n) + " " + number_text(at(n), "%.2f");
    };
    // Steps of 0.01 are exact only to rounding: equal numbers are in order.
    constexpr double kSame = 1e-9;
    if (number < static_cast<int>(numbers.size()) && at(number) > at(number + 1) + kSame) {
        return named(number) + " is above " + named(number + 1);
    }
    if (number > 1 && at(number) < at(number - 1) - kSame) {
        return named(number) + " is below " + named(number - 1);
    }
    return "";
}

}  // namespace

ClefEditor::ClefEditor(std::string id, Clef clef)
    : id_(std::move(id)), clef_(std::move(clef)), original_(clef_) {
    string_ = std::min(3, std::max(1, strings()));
    number_ = std::min(5, std::max(1, numbers()));
}

int ClefEditor::string_of_field(int field) const {
    return field >= 1 && field <= strings() ? strings() - field + 1 : 0;
}

int ClefEditor::number_of_field(int field) const {
    return field > strings() && field < fields() ? field - strings() : 0;
}

ClefEditor::Outcome ClefEditor::change(int direction) {
    if (field_ == 0) {
        clef_.tempo = stepped_value(clef_.tempo, direction * (fine_ ? kFineTempo : kTempo),
                                    kFineTempo, limits::min_tempo_s, limits::max_tempo_s);
        return Outcome::hear;
    }
    if (const int string = string_of_field(field_); string > 0) {
        if (waveform()) {
            return Outcome::editing;  // a waveform changes by its points
        }
        string_ = string;  // heard on it, and the numbers after it are heard on it
        auto& frequency = clef_.strings[static_cast<std::size_t>(string - 1)].frequency;
        frequency = stepped_value(frequency, direction * (fine_ ? kFineHz : kHz), kFineHz, kFineHz,
                                  limits::max_frequency_hz);
        return Outcome::hear;
    }
    number_ = number_of_field(field_);
    auto& amplitude = clef_.numbers[static_cast<std::size_t>(number_ - 1)];
    amplitude = stepped_value(amplitude, direction * (fine_ ? kFineAmplitude : kAmplitude),
                              kFineAmplitude, 0.0, limits::max_amplitude);
    notice_ = out_of_order(clef_.numbers, number_);
    return Outcome::hear;
}

ClefEditor::Outcome ClefEditor::move_point(double dt, double dlevel) {
    auto& all = points();
    auto& point = all[static_cast<std::size_t>(point_)];
    // A point moves in time between its neighbours, so the points stay in time order.
    const double earliest = point_ > 0 ? all[static_cast<std::size_t>(point_ - 1)].time : 0.0;
    const double latest = point_ + 1 < static_cast<int>(all.size())
                              ? all[static_cast<std::size_t>(point_ + 1)].time
                              : 1.0;
    const double fine = fine_ ? kFineTime : kTime;
    point.time = stepped_value(point.time, dt * fine, kFineTime, earliest, latest);
    const double level_step = fine_ ? kFineAmplitude : kAmplitude;
    point.level = stepped_value(point.level, dlevel * level_step, kFineAmplitude, 0.0, 1.0);
    return Outcome::hear;
}

ClefEditor::Outcome ClefEditor::press(Button button) {
    switch (level_) {
        case Level::fields:
            switch (button) {
                case Button::up:
                case Button::down:
                    field_ = ((field_ + (button == Button::up ? -1 : 1)) % fields() + fields()) %
                             fields();
                    if (const int number = number_of_field(field_); number > 0) {
                        number_ = number;
                    }
                    return Outcome::editing;
                case Button::right:
                case Button::left:
                    return change(button == Button::right ? +1 : -1);
                case Button::select:
                    if (const int string = string_of_field(field_); string > 0) {
                        string_ = string;  // heard, or its points edited
                    }
                    if (waveform() && string_of_field(field_) > 0 && !points().empty()) {
                        level_ = Level::points;
                        point_ = 0;
                    }
                    return Outcome::hear;
                case Button::back:
                    level_ = Level::fields_more;
                    return Outcome::editing;
            }
            break;
        case Level::fields_more:
            level_ = Level::fields;
            switch (button) {
                case Button::up:
                    fine_ = !fine_;
                    return Outcome::editing;
                case Button::down:
                    return Outcome::hear;
                case Button::select:
                    return Outcome::save_as;
                case Button::back:
                    return Outcome::close;
                case Button::left:
                case Button::right:
                    return Outcome::editing;
            }
            break;
        case Level::points:
            switch (button) {
                case Button::up:
                    return move_point(0.0, +1.0);
                case Button::down:
                    return move_point(0.0, -1.0);
                case Button::right:
                    return move_point(+1.0, 0.0);
                case Button::left:
                    return move_point(-1.0, 0.0);
                case Button::select:
                    point_ = (point_ + 1) % static_cast<int>(points().size());
                    return Outcome::editing;
                case Button::back:
                    level_ = Level::points_more;
                    return Outcome::editing;
            }
            break;
        case Level::points_more: {
            level_ = Level::points;
            auto& all = points();
            switch (button) {
                case Button::up: {
                    // A point halfway to the next one (or to the end of the quarter note).
                    const auto& here = all[static_cast<std::size_t>(point_)];
                    const ClefPoint next = point_ + 1 < static_cast<int>(all.size())
                                               ? all[static_cast<std::size_t>(point_ + 1)]
                                               : ClefPoint{1.0, here.level};
                    all.insert(all.begin() + point_ + 1,
                               {(here.time + next.time) / 2, (here.level + next.level) / 2});
                    ++point_;
                    return Outcome::hear;
                }
                case Button::down:
                    if (static_cast<int>(all.size()) > kFewestPoints) {
                        all.erase(all.begin() + point_);
                        point_ = std::min(point_, static_cast<int>(all.size()) - 1);
                        return Outcome::hear;
                    }
                    return Outcome::editing;
                case Button::left:
                    point_ =
                        (point_ - 1 + static_cast<int>(all.size())) % static_cast<int>(all.size());
                    return Outcome::editing;
                case Button::right:
                    fine_ = !fine_;
                    return Outcome::editing;
                case Button::select:
                    return Outcome::editing;
                case Button::back:
                    level_ = Level::fields;
                    return Outcome::editing;
            }
            break;
        }
    }
    return Outcome::editing;
}

std::string sparkline(const Clef& clef, int string, int width) {
    static const char* const kBlocks[] = {"▁", "▂", "▃", "▄", "▅", "▆", "▇", "█"};
    if (string < 1 || string > static_cast<int>(clef.strings.size()) || width <= 0) {
        return "";
    }
    const auto& points = clef.strings[static_cast<std::size_t>(string - 1)].points;
    if (points.empty()) {
        return "";
    }
    const render::Waveform waveform(clef.type, points);
    std::string line;
    for (int x = 0; x < width; ++x) {
        const double tau = width == 1 ? 0.0 : static_cast<double>(x) / (width - 1);
        const double level = std::clamp(waveform.level(tau), 0.0, 1.0);
        line += kBlocks[std::clamp(static_cast<int>(std::lround(level * 7)), 0, 7)];
    }
    return line;
}

std::vector<std::string> ClefEditor::lines(int width, int height,
                                           const std::vector<std::string>& feel) const {
    std::vector<std::string> rows;
    const auto mark = [&](int field) { return field == field_ ? ">" : " "; };
    const std::string type(to_string(clef_.type));
    if (level_ == Level::points || level_ == Level::points_more) {
        rows.push_back(fit("clef " + id_ + " s" + std::to_string(string_) + " (" + type + ")" +
                               (modified() ? " *" : ""),
                           width));
        // The waveform over the quarter note, the point under the cursor marked under it.
        const int plot_width = std::max(8, std::min(width - 2, 64));
        rows.push_back(" " + sparkline(clef_, string_, plot_width));
        std::string marks(static_cast<std::size_t>(plot_width + 1), ' ');
        const auto& all = points();
        for (int i = 0; i < static_cast<int>(all.size()); ++i) {
            const auto x = static_cast<std::size_t>(
                1 + std::lround(all[static_cast<std::size_t>(i)].time * (plot_width - 1)));
            marks[std::min(x, marks.size() - 1)] = i == point_ ? '^' : '\'';
        }
        rows.push_back(marks);
        const auto& point = all[static_cast<std::size_t>(point_)];
        rows.push_back(fit(
            " point " + std::to_string(point_ + 1) + "/" + std::to_string(all.size()) + "  time " +
                number_text(point.time, "%.2f") + "  level " + number_text(point.level, "%.2f"),
            width));
    } else {
        rows.push_back(fit("clef " + id_ + " (" + type + ")" + (modified() ? " *" : ""), width));
        rows.push_back(
            fit(mark(0) + std::string("tempo ") + number_text(clef_.tempo, "%.3f") + " s", width));
        for (int field = 1; field <= strings(); ++field) {
            const int string = string_of_field(field);
            std::string row = mark(field) + std::string("s") + std::to_string(string) + " ";
            if (waveform()) {
                row += sparkline(clef_, string, std::max(8, std::min(width - 16, 32)));
            } else {
                row += number_text(clef_.strings[static_cast<std::size_t>(string - 1)].frequency,
                                   "%.0f Hz");
            }
            if (static_cast<std::size_t>(string - 1) < feel.size()) {
                row += "  " + feel[static_cast<std::size_t>(string - 1)];
            }
            rows.push_back(fit(row, width));
        }
        // The numbers three to a row, or more where the screen is wider.
        const int per_row = std::max(1, std::min(9, width / 10));
        std::string row;
        for (int n = 1; n <= numbers(); ++n) {
            row += mark(strings() + n) + std::string("n") + std::to_string(n) + " " +
                   number_text(clef_.numbers[static_cast<std::size_t>(n - 1)], "%.2f") + " ";
            if (n % per_row == 0 || n == numbers()) {
                rows.push_back(fit(row, width));
                row.clear();
            }
        }
    }
    // Keep the field under the cursor in sight when the window is short (and the notice's
    // line, the last).
    const bool noticed =
        !notice_.empty() && (level_ == Level::fields || level_ == Level::fields_more);
    if (noticed) {
        --height;
    }
    if (static_cast<int>(rows.size()) > height && height > 0) {
        int at = 0;
        for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
            if (rows[static_cast<std::size_t>(i)].starts_with(">")) {
                at = i;
            }
        }
        const int first = std::clamp(at - height / 2, 0, static_cast<int>(rows.size()) - height);
        rows = std::vector<std::string>(rows.begin() + first, rows.begin() + first + height);
    }
    if (noticed) {
        rows.push_back(fit("!" + notice_, width));
    }
    return rows;
}

std::string ClefEditor::hint() const {
    switch (level_) {
        case Level::fields:
            if (waveform() && string_of_field(field_) > 0) {
                return "\u2191\u2193field S:points B:more";
            }
            return "\u2191\u2193field \u2190\u2192" + std::string(fine_ ? "fine" : "value") +
                   " S:hear B:more";
        case Level::fields_more:
            return std::string("\u2191") + (fine_ ? "coarse" : "fine") +
                   " \u2193hear S:save as B:close";
        case Level::points:
            return "\u2191\u2193level \u2190\u2192time S:next B:more";
        case Level::points_more:
            return std::string("\u2191add \u2193delete \u2190prev \u2192") +
                   (fine_ ? "coarse" : "fine") + " B:done";
    }
    return {};
}

}  // namespace vibscore::editor
