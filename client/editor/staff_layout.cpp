#include "client/editor/staff_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <tuple>

#include "client/editor/score_edits.hpp"

namespace vibscore::editor {

namespace {

constexpr const char* kStaffLine = "─";
constexpr const char* kBarLine = "│";
constexpr const char* kSustain = "━";
constexpr const char* kDot = "·";
constexpr const char* kRest = "▬";
constexpr const char* kPlayback = "●";
constexpr const char* kCursorMark = "▲";
constexpr const char* kBlockMark = "═";
constexpr int kEndWidth = 2;

int plain_width(Length length) {
    switch (length) {
        case Length::whole:
            return 7;
        case Length::half:
        case Length::half_dot:
            return 6;
        case Length::quarter:
        case Length::quarter_dot:
            return 5;
        case Length::eighth:
        case Length::eighth_dot:
            return 4;
        case Length::sixteenth:
        case Length::sixteenth_dot:
        case Length::thirty_second:
            return 3;
    }
    return 3;
}

class Painter {
  public:
    explicit Painter(StaffLayout& layout) : layout_(layout) {}

    void put(int row, int x, const char* glyph, Ink ink) {
        if (x >= 0 && x < layout_.width) {
            auto& cell = layout_.rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)];
            cell.glyph = glyph;
            cell.ink = ink;
        }
    }
    void text(int row, int x, const std::string& text, Ink ink) {
        // Labels are ASCII: one byte, one column.
        for (std::size_t i = 0; i < text.size(); ++i) {
            const char glyph[2] = {text[i], '\0'};
            put(row, x + static_cast<int>(i), glyph, ink);
        }
    }
    void overlay(int row, int x, std::uint8_t mark) {
        if (x >= 0 && x < layout_.width) {
            layout_.rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)].overlay |=
                mark;
        }
    }
    const std::string& glyph(int row, int x) const {
        return layout_.rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)].glyph;
    }

  private:
    StaffLayout& layout_;
};

// Spans are in score order, each bar's line before its symbols and end
// position: ordered by (bar, symbol, not a bar line). So a position's span is
// found by halving, not by a walk from the start that made laying out (and
// drawing) a long score quadratic.
const Span* span_at(const StaffLayout& layout, Position at) {
    const auto key = [](const Span& span) {
        return std::tuple(span.bar, span.symbol, span.kind != Span::Kind::bar_line);
    };
    const auto wanted = std::tuple(at.bar, at.symbol, true);
    const auto found =
        std::lower_bound(layout.spans.begin(), layout.spans.end(), wanted,
                         [&](const Span& span, const auto& value) { return key(span) < value; });
    if (found != layout.spans.end() && found->kind != Span::Kind::bar_line &&
        found->bar == at.bar && found->symbol == at.symbol) {
        return &*found;
    }
    return nullptr;
}

// The columns a note's sound covers on the staff: from its head to before its
// trailing gap.
int sound_end(const Span& span) {
    return span.x + std::max(span.width - 2, 1);
}

void draw_dynamics(const Score& score, const StaffLayout& layout, Painter& paint) {
    std::optional<Position> run_first;
    std::optional<Position> run_last;
    Dynamics run = Dynamics::none;
    const auto finish = [&] {
        if (run == Dynamics::none || !run_first) {
            return;
        }
        const int x0 = layout.x_of(*run_first);
        const int x1 = sound_end(*span_at(layout, *run_last));
        for (int x = x0; x <= x1; ++x) {
            paint.put(row_dynamics, x, "─", Ink::dynamics);
        }
        if (run == Dynamics::crescendo) {
            paint.put(row_dynamics, x0, "<", Ink::dynamics);
        } else {
            paint.put(row_dynamics, x1, ">", Ink::dynamics);
        }
        run = Dynamics::none;
    };
    for (std::size_t b = 0; b < score.bars.size(); ++b) {
        for (std::size_t s = 0; s < score.bars[b].symbols.size(); ++s) {
            const Symbol& symbol = score.bars[b].symbols[s];
            if (std::holds_alternative<Blank>(symbol)) {
                continue;  // a blank does not end a hairpin
            }
            const auto* note = std::get_if<Note>(&symbol);
            const Dynamics here = note != nullptr ? note->dynamics : Dynamics::none;
            if (here != run) {
                finish();
                run = here;
                run_first = Position{b, s};
            }
            run_last = Position{b, s};
        }
    }
    finish();
}

void draw_ties(const Score& score, const StaffLayout& layout, Painter& paint) {
    for (std::size_t b = 0; b < score.bars.size(); ++b) {
        for (std::size_t s = 0; s < score.bars[b].symbols.size(); ++s) {
            const Position at{b, s};
            const Note* note = note_at(score, at);
            const auto next_at = symbol_after(score, at);
            const Note* next = next_at ? note_at(score, *next_at) : nullptr;
            if (note == nullptr || next == nullptr) {
                continue;
            }
            const int x0 = layout.x_of(at);
            const int x1 = layout.x_of(*next_at);
            if (note->legato != 0 && note->legato == next->legato) {
                for (int x = x0 + 1; x < x1; ++x) {
                    paint.put(row_ties, x, "─", Ink::tie);
                }
                paint.put(row_ties, x0, paint.glyph(row_ties, x0) == "╯" ? "┴" : "╰", Ink::tie);
                paint.put(row_ties, x1, "╯", Ink::tie);
            } else if (note->portamento != 0 && note->portamento == next->portamento) {
                for (int x = x0; x <= x1; ++x) {
                    paint.put(row_ties, x, "~", Ink::tie);
                }
            }
        }
    }
}

}  // namespace

int symbol_width(const Symbol& symbol) {
    if (std::holds_alternative<Blank>(symbol)) {
        return 2;
    }
    const Length length = length_of(symbol);
    return plain_width(length) + (is_dotted(length) ? 1 : 0);
}

std::string length_label(Length length) {
    switch (length) {
        case Length::whole:
            return "1";
        case Length::half_dot:
            return "2.";
        case Length::half:
            return "2";
        case Length::quarter_dot:
            return "4.";
        case Length::quarter:
            return "4";
        case Length::eighth_dot:
            return "8.";
        case Length::eighth:
            return "8";
        case Length::sixteenth_dot:
            return "16.";
        case Length::sixteenth:
            return "16";
        case Length::thirty_second:
            return "32";
    }
    return "?";
}

std::string beat_label(double beats) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", beats);
    std::string label = text;
    label.erase(label.find_last_not_of('0') + 1);
    if (label.back() == '.') {
        label.pop_back();
    }
    return label;
}

int StaffLayout::x_of(Position at) const {
    const Span* span = span_at(*this, at);
    return span == nullptr ? -1 : span->x;
}

StaffLayout layout_staff(const Score& score, const LayoutOptions& options) {
    StaffLayout layout;
    struct BarBox {
        int x;
        std::string text;
        Ink ink;
    };
    std::vector<BarBox> boxes;
    int x = 0;
    for (std::size_t b = 0; b < score.bars.size(); ++b) {
        const Bar& bar = score.bars[b];
        layout.spans.push_back({Span::Kind::bar_line, b, 0, x, 1});
        ++x;
        double beats = Score::beat_count(bar);
        if (options.entering && options.entering->bar == b &&
            options.entering->symbol < bar.symbols.size() &&
            !std::holds_alternative<Blank>(bar.symbols[options.entering->symbol])) {
            beats -= vibscore::beats(length_of(bar.symbols[options.entering->symbol]));
        }
        const Ink ink = beats < beats_in_a_full_bar   ? Ink::clef_fewer
                        : beats > beats_in_a_full_bar ? Ink::clef_more
                                                      : Ink::clef_exact;
        boxes.push_back({x, "[" + bar.clef + " " + beat_label(beats) + "]", ink});
        const int start = x;
        for (std::size_t s = 0; s < bar.symbols.size(); ++s) {
            const int width = symbol_width(bar.symbols[s]);
            layout.spans.push_back({Span::Kind::symbol, b, s, x, width});
            x += width;
        }
        if (options.end_positions) {
            layout.spans.push_back({Span::Kind::end, b, bar.symbols.size(), x, kEndWidth});
            x += kEndWidth;
        }
        // Room for the clef box over the bar.
        const int needed = static_cast<int>(boxes.back().text.size()) + 1;
        if (x - start < needed) {
            if (options.end_positions) {
                layout.spans.back().width += needed - (x - start);
            }
            x = start + needed;
        }
    }
    layout.spans.push_back({Span::Kind::bar_line, score.bars.size(), 0, x, 1});
    const int staff_width = x + 1;
    layout.width = staff_width;
    if (options.cursor && !options.cursor_label.empty()) {
        // Room for the cursor's label after the last bar line when the cursor is
        // near it.
        if (const Span* span = span_at(layout, *options.cursor)) {
            layout.width =
                std::max(layout.width, span->x + 2 + static_cast<int>(options.cursor_label.size()));
        }
    }
    layout.rows.assign(staff_rows,
                       std::vector<Cell>(static_cast<std::size_t>(layout.width), Cell{}));

    Painter paint(layout);
    for (int row = row_top_string; row < row_top_string + 6; ++row) {
        for (int column = 0; column < staff_width; ++column) {
            paint.put(row, column, kStaffLine, Ink::line);
        }
    }
    for (const auto& box : boxes) {
        paint.text(row_clef, box.x, box.text, box.ink);
    }
    for (const auto& span : layout.spans) {
        if (span.kind == Span::Kind::bar_line) {
            for (int row = row_top_string; row < row_top_string + 6; ++row) {
                paint.put(row, span.x, kBarLine, Ink::line);
            }
            continue;
        }
        if (span.kind != Span::Kind::symbol) {
            continue;
        }
        const Symbol& symbol = score.bars[span.bar].symbols[span.symbol];
        if (const auto* note = std::get_if<Note>(&symbol)) {
            const int row = row_of_string(std::clamp(note->string, 1, 6));
            const std::string head = std::to_string(note->number);
            paint.text(row, span.x, head.substr(0, 1), Ink::head);
            int from = span.x + 1;
            if (is_dotted(note->length)) {
                paint.put(row, from++, kDot, Ink::head);
            }
            for (int column = from; column <= sound_end(span) && column > span.x; ++column) {
                paint.put(row, column, kSustain, Ink::sustain);
            }
            paint.text(row_lengths, span.x, length_label(note->length), Ink::length);
        } else if (const auto* rest = std::get_if<Rest>(&symbol)) {
            for (const int string : {4, 3}) {
                paint.put(row_of_string(string), span.x, kRest, Ink::rest);
                if (is_dotted(rest->length)) {
                    paint.put(row_of_string(string), span.x + 1, kDot, Ink::rest);
                }
            }
            paint.text(row_lengths, span.x, length_label(rest->length), Ink::length);
        }
    }
    draw_dynamics(score, layout, paint);
    draw_ties(score, layout, paint);

    if (options.block) {
        for (const auto& span : layout.spans) {
            const Position at{span.bar, span.symbol};
            if (span.kind == Span::Kind::symbol && options.block->first <= at &&
                at < options.block->end) {
                for (int column = span.x; column < span.x + span.width; ++column) {
                    for (int row = row_top_string; row < row_top_string + 6; ++row) {
                        paint.overlay(row, column, overlay_selected);
                    }
                    paint.put(row_playback, column, kBlockMark, Ink::mark);
                }
            }
        }
    }
    if (options.cursor) {
        if (const Span* span = span_at(layout, *options.cursor)) {
            for (int row = row_top_string; row < row_top_string + 6; ++row) {
                paint.overlay(row, span->x, overlay_cursor_column);
            }
            paint.overlay(row_of_string(std::clamp(options.cursor_string, 1, 6)), span->x,
                          overlay_cursor);
            paint.put(row_playback, span->x, kCursorMark, Ink::mark);
            paint.text(row_playback, span->x + 1, options.cursor_label, Ink::mark);
        }
    }
    if (options.playing) {
        if (const Span* span = span_at(layout, *options.playing)) {
            paint.put(row_playback, span->x, kPlayback, Ink::playback);
            for (int row = row_top_string; row < row_top_string + 6; ++row) {
                paint.overlay(row, span->x, overlay_playing);
            }
        }
    }
    return layout;
}

int scroll_to_show(int first, int width, int x, int total_width) {
    if (width <= 0) {
        return 0;
    }
    const int margin = std::min(6, width / 4);
    if (x < first + margin) {
        first = x - margin;
    } else if (x >= first + width - margin) {
        first = x - width + margin + 1;
    }
    return std::clamp(first, 0, std::max(0, total_width - width));
}

std::vector<std::pair<int, int>> systems(const StaffLayout& layout, int width) {
    std::vector<std::pair<int, int>> ranges;
    width = std::max(width, 2);
    std::vector<int> bar_lines;
    for (const auto& span : layout.spans) {
        if (span.kind == Span::Kind::bar_line) {
            bar_lines.push_back(span.x);
        }
    }
    int begin = 0;
    while (begin < layout.width - 1) {
        // The furthest bar line that still fits; a bar wider than the page is cut.
        // Bar lines are in column order: found by halving, so a long score's
        // systems take n log n.
        int end = begin;
        const auto after = std::upper_bound(bar_lines.begin(), bar_lines.end(), begin + width - 1);
        if (after != bar_lines.begin() && *std::prev(after) > begin) {
            end = *std::prev(after) + 1;
        }
        const bool at_bar_line = end != begin;
        if (!at_bar_line) {
            end = std::min(begin + width, layout.width);
        }
        ranges.emplace_back(begin, end);
        if (end >= layout.width) {
            break;
        }
        // The next system starts with the bar line this one ended on.
        begin = at_bar_line ? end - 1 : end;
    }
    return ranges;
}

}  // namespace vibscore::editor
