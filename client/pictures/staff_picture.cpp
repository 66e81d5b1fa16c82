#include "client/pictures/staff_picture.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>

#include "client/editor/score_edits.hpp"
#include "client/pictures/picture_text.hpp"

namespace vibscore::pictures {

namespace {

using editor::Span;

constexpr double kColumn = 9.0;  // pixels per layout column
constexpr double kLine = 12.0;   // between two strings
constexpr double kMargin = 14.0;
constexpr double kTitle = 30.0;
constexpr double kStem = 3.2 * kLine;
// A system's rows from its top: the clef boxes, the hairpins, room for the stems of notes on
// string 6, the strings, then the ties and the gap to the next system.
constexpr double kClefRow = 18.0;
constexpr double kClefBoxHeight = kClefRow - 3;
constexpr double kDynamicsRow = 16.0;
constexpr double kHairpinOpen = 4.5;  // half a hairpin's open end
constexpr double kStemRoom = 42.0;    // a stem over string 6 ends below the hairpins
constexpr double kBelowStaff = 34.0;  // room for legato arcs and the gap to the next system
constexpr double kSystemHeight = kClefRow + kDynamicsRow + kStemRoom + 5 * kLine + kBelowStaff;
constexpr double kHeadRx = 7.0, kHeadRy = 5.5;
// A head sits this far right of its column's middle, clear of the bar line before it.
constexpr double kHeadShift = 2.5;
static_assert(kStemRoom - kStem > kDynamicsRow / 2 - kHairpinOpen,
              "a stem over string 6 must end below the hairpin row");

void set_rgb(cairo_t* cairo, const double (&rgb)[3]) {
    cairo_set_source_rgb(cairo, rgb[0], rgb[1], rgb[2]);
}

void ellipse(cairo_t* cairo, double x, double y, double rx, double ry) {
    cairo_save(cairo);
    cairo_translate(cairo, x, y);
    cairo_scale(cairo, rx, ry);
    cairo_new_path(cairo);
    cairo_arc(cairo, 0, 0, 1, 0, 2 * M_PI);
    cairo_restore(cairo);
}

bool hollow(Length length) {
    return length == Length::whole || length == Length::half || length == Length::half_dot;
}

int flags(Length length) {
    switch (length) {
        case Length::eighth:
        case Length::eighth_dot:
            return 1;
        case Length::sixteenth:
        case Length::sixteenth_dot:
            return 2;
        case Length::thirty_second:
            return 3;
        default:
            return 0;
    }
}

const Span* symbol_span(const editor::StaffLayout& layout, std::size_t bar, std::size_t symbol) {
    // Spans are in score order, each bar's line before its symbols.
    const auto found = std::lower_bound(
        layout.spans.begin(), layout.spans.end(), std::tuple(bar, symbol, true),
        [](const Span& span, const auto& wanted) {
            return std::tuple(span.bar, span.symbol, span.kind != Span::Kind::bar_line) < wanted;
        });
    return found != layout.spans.end() && found->kind == Span::Kind::symbol && found->bar == bar &&
                   found->symbol == symbol
               ? &*found
               : nullptr;
}

// Marks that may reach into a system's columns from outside them (a hairpin's tip, a tie's arc):
// the columns either side that are drawn too, and clipped.
constexpr int kReach = 2;

}  // namespace

StaffPicture::StaffPicture(const Score& score, const Options& options)
    : score_(score), layout_(editor::layout_staff(score)) {
    double top = kTitle;
    int widest = 0;
    const auto first_at = [&](int column) {
        return static_cast<std::size_t>(
            std::lower_bound(layout_.spans.begin(), layout_.spans.end(), column,
                             [](const Span& span, int x) { return span.x < x; }) -
            layout_.spans.begin());
    };
    for (const auto& [begin, end] : editor::systems(layout_, options.columns_per_system)) {
        systems_.push_back({begin, end, top, first_at(begin), first_at(end)});
        top += kSystemHeight;
        widest = std::max(widest, end - begin);
    }
    find_hairpins();
    find_ties();
    // Wide enough for the title too.
    const SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1),
                             &cairo_surface_destroy);
    const CairoPtr measure(cairo_create(scratch.get()), &cairo_destroy);
    select_font(measure.get(), 14, true);
    cairo_text_extents_t title;
    cairo_text_extents(measure.get(), title_text().c_str(), &title);
    width_ = std::ceil(2 * kMargin + std::max(widest * kColumn, title.x_advance));
    height_ = std::ceil(top + kMargin / 2);
    place_clef_boxes(measure.get());
}

std::string StaffPicture::title_text() const {
    return score_.title.empty() ? "(untitled)" : score_.title;
}

double StaffPicture::column_x(const System& system, double column) const {
    return kMargin + (column - system.begin) * kColumn;
}

double StaffPicture::head_x(const System& system, int column) const {
    return column_x(system, column + 0.5) + kHeadShift;
}

double StaffPicture::string_y(const System& system, int string) const {
    return system.top + kClefRow + kDynamicsRow + kStemRoom +
           (6 - std::clamp(string, 1, 6)) * kLine;
}

void StaffPicture::place_clef_boxes(cairo_t* cairo) {
    select_font(cairo, 10, false);
    for (const auto& system : systems_) {
        for (std::size_t i = system.first_span; i < system.end_span; ++i) {
            const auto& span = layout_.spans[i];
            // The bar line closing a system opens the next bar, whose clef box heads the next
            // system.
            if (span.kind != Span::Kind::bar_line || span.bar >= score_.bars.size() ||
                span.x < system.begin || span.x + 1 >= system.end) {
                continue;
            }
            const auto next =
                std::find_if(layout_.spans.begin() + static_cast<long>(i) + 1, layout_.spans.end(),
                             [](const Span& later) { return later.kind == Span::Kind::bar_line; });
            const double x = std::round(column_x(system, span.x + 1)) + 0.5;
            // Up to a gap before the next bar's box.
            const double room = column_x(system, next->x + 1) - 6 - x;
            const Bar& bar = score_.bars[span.bar];
            const std::string beats = editor::beat_label(Score::beat_count(bar));
            const std::string label =
                fitted_text(cairo,
                            {bar.clef + "  " + beats + (beats == "1" ? " beat" : " beats"),
                             bar.clef + "  " + beats},
                            room - 8);
            clef_boxes_.push_back({span.bar, x, system.top + 0.5,
                                   std::min(text_width(cairo, label) + 8, room), kClefBoxHeight,
                                   label});
        }
    }
}

std::vector<StaffPicture::Point> StaffPicture::head_centres() const {
    std::vector<Point> centres;
    for (const auto& system : systems_) {
        for (std::size_t i = system.first_span; i < system.end_span; ++i) {
            const auto& span = layout_.spans[i];
            if (span.kind != Span::Kind::symbol || span.x < system.begin || span.x >= system.end) {
                continue;
            }
            if (const auto* note = std::get_if<Note>(&score_.bars[span.bar].symbols[span.symbol])) {
                centres.push_back({head_x(system, span.x), string_y(system, note->string)});
            }
        }
    }
    return centres;
}

void StaffPicture::draw(cairo_t* cairo, Layers layers) const {
    if (layers & title) {
        cairo_set_source_rgb(cairo, 0, 0, 0);
        select_font(cairo, 14, true);
        show_text_at(cairo, kMargin, 20, title_text());
    }
    for (const auto& system : systems_) {
        draw_system(cairo, system, layers);
    }
    for (const auto& box : clef_boxes_) {
        draw_clef_box(cairo, box, layers);
    }
}

void StaffPicture::draw_system(cairo_t* cairo, const System& system, Layers layers) const {
    const double left = column_x(system, system.begin);
    const double right = column_x(system, system.end - 1) + 1;
    if (layers & staff_lines) {
        cairo_set_line_width(cairo, 1.0);
        cairo_set_source_rgb(cairo, 0.45, 0.45, 0.45);
        for (int string = 1; string <= 6; ++string) {
            cairo_move_to(cairo, left, string_y(system, string) + 0.5);
            cairo_line_to(cairo, right, string_y(system, string) + 0.5);
        }
        cairo_stroke(cairo);
    }
    for (std::size_t i = system.first_span; i < system.end_span; ++i) {
        const auto& span = layout_.spans[i];
        if (span.x < system.begin || span.x >= system.end) {
            continue;
        }
        if (span.kind == Span::Kind::bar_line) {
            if (layers & bar_lines) {
                const double x = std::round(column_x(system, span.x + 0.5)) + 0.5;
                cairo_set_source_rgb(cairo, 0, 0, 0);
                cairo_set_line_width(cairo, 1.2);
                cairo_move_to(cairo, x, string_y(system, 6));
                cairo_line_to(cairo, x, string_y(system, 1) + 1);
                cairo_stroke(cairo);
            }
            continue;
        }
        if (span.kind != Span::Kind::symbol) {
            continue;
        }
        const Symbol& symbol = score_.bars[span.bar].symbols[span.symbol];
        if (const auto* note = std::get_if<Note>(&symbol)) {
            draw_note(cairo, system, span, *note, layers);
        } else if (const auto* rest = std::get_if<Rest>(&symbol); rest && (layers & rests)) {
            draw_rest(cairo, system, span, *rest);
        }
    }
    // Hairpins and ties may run into the next system: draw each whole, clipped to this one.
    cairo_save(cairo);
    cairo_rectangle(cairo, left - kColumn / 2, system.top, right - left + kColumn, kSystemHeight);
    cairo_clip(cairo);
    if (layers & hairpins) {
        draw_hairpins(cairo, system);
    }
    if (layers & ties) {
        draw_ties(cairo, system);
    }
    cairo_restore(cairo);
}

void StaffPicture::draw_note(cairo_t* cairo, const System& system, const Span& span,
                             const Note& note, Layers layers) const {
    const double x = head_x(system, span.x);
    const double y = string_y(system, note.string);
    const bool open = hollow(note.length);
    if (layers & heads) {
        ellipse(cairo, x, y, kHeadRx, kHeadRy);
        if (open) {
            cairo_set_source_rgb(cairo, 1, 1, 1);
        } else {
            set_rgb(cairo, head_ink);
        }
        cairo_fill_preserve(cairo);
        set_rgb(cairo, head_ink);
        cairo_set_line_width(cairo, 1.4);
        cairo_stroke(cairo);
        if (editor::is_dotted(note.length)) {
            cairo_set_source_rgb(cairo, 0, 0, 0);
            cairo_arc(cairo, x + kHeadRx + 4.5, y - 2.5, 1.7, 0, 2 * M_PI);
            cairo_fill(cairo);
        }
    }
    if (layers & numbers) {
        select_font(cairo, 9, true);
        if (open) {
            cairo_set_source_rgb(cairo, 0, 0, 0);
        } else {
            cairo_set_source_rgb(cairo, 1, 1, 1);
        }
        show_centred(cairo, x, y, std::to_string(note.number));
    }
    if ((layers & stems) && note.length != Length::whole) {
        cairo_set_source_rgb(cairo, 0, 0, 0);
        cairo_set_line_width(cairo, 1.2);
        const double stem_x = x + kHeadRx - 0.6;
        cairo_move_to(cairo, stem_x, y - 1);
        cairo_line_to(cairo, stem_x, y - kStem);
        cairo_stroke(cairo);
        for (int flag = 0; flag < flags(note.length); ++flag) {
            const double top = y - kStem + flag * 5.0;
            cairo_move_to(cairo, stem_x, top);
            cairo_curve_to(cairo, stem_x + 2, top + 4, stem_x + 8, top + 5, stem_x + 6, top + 12);
            cairo_stroke(cairo);
        }
    }
}

void StaffPicture::draw_rest(cairo_t* cairo, const System& system, const Span& span,
                             const Rest& rest) const {
    const double x = column_x(system, span.x + 0.5);
    const double line4 = string_y(system, 4);
    const double line3 = string_y(system, 3);
    const double middle = (line4 + line3) / 2;
    cairo_set_source_rgb(cairo, 0, 0, 0);
    cairo_set_line_width(cairo, 1.6);
    switch (rest.length) {
        case Length::whole:
            cairo_rectangle(cairo, x - 5, line4, 10, 5);  // hangs from a line
            cairo_fill(cairo);
            break;
        case Length::half:
        case Length::half_dot:
            cairo_rectangle(cairo, x - 5, line3 - 5, 10, 5);  // sits on a line
            cairo_fill(cairo);
            break;
        case Length::quarter:
        case Length::quarter_dot:
            cairo_move_to(cairo, x - 2, middle - 10);
            cairo_line_to(cairo, x + 3, middle - 4);
            cairo_line_to(cairo, x - 2, middle + 1);
            cairo_line_to(cairo, x + 3, middle + 6);
            cairo_curve_to(cairo, x - 3, middle + 4, x - 3, middle + 10, x + 1, middle + 11);
            cairo_stroke(cairo);
            break;
        default: {
            // A slanted stem with one blob for each flag of the note of the same length.
            cairo_set_line_width(cairo, 1.3);
            cairo_move_to(cairo, x + 3, middle - 9);
            cairo_line_to(cairo, x - 2, middle + 10);
            cairo_stroke(cairo);
            for (int flag = 0; flag < flags(rest.length); ++flag) {
                const double y = middle - 8 + flag * 5.5;
                cairo_arc(cairo, x - 2 + flag * -1.2, y + 1, 2.0, 0, 2 * M_PI);
                cairo_fill(cairo);
                cairo_move_to(cairo, x - 2 + flag * -1.2, y + 2);
                cairo_line_to(cairo, x + 3 - flag * 1.3, y);
                cairo_stroke(cairo);
            }
        }
    }
    if (editor::is_dotted(rest.length)) {
        cairo_arc(cairo, x + 8, middle - 3, 1.7, 0, 2 * M_PI);
        cairo_fill(cairo);
    }
}

void StaffPicture::draw_clef_box(cairo_t* cairo, const ClefBox& box, Layers layers) const {
    if (layers & clef_boxes) {
        const double beats = Score::beat_count(score_.bars[box.bar]);
        cairo_rectangle(cairo, box.x, box.y, box.width, box.height);
        if (beats < editor::beats_in_a_full_bar) {
            cairo_set_source_rgb(cairo, 0.55, 0.93, 0.96);  // cyan: fewer beats than four
        } else if (beats > editor::beats_in_a_full_bar) {
            cairo_set_source_rgb(cairo, 0.96, 0.62, 0.96);  // magenta: more
        } else {
            cairo_set_source_rgb(cairo, 1, 1, 1);  // white: exactly four
        }
        cairo_fill_preserve(cairo);
        cairo_set_source_rgb(cairo, 0.35, 0.35, 0.35);
        cairo_set_line_width(cairo, 1.0);
        cairo_stroke(cairo);
    }
    if (layers & clef_labels) {
        select_font(cairo, 10, false);
        cairo_set_source_rgb(cairo, 0, 0, 0);
        show_text_at(cairo, box.x + 4, box.y + box.height - 4, box.label);
    }
}

void StaffPicture::find_hairpins() {
    // A run of notes with the same dynamics is one hairpin; rests end it, blanks do not.
    Dynamics run = Dynamics::none;
    std::size_t first_bar = 0, first = 0, last_bar = 0, last = 0;
    const auto finish = [&] {
        if (run != Dynamics::none) {
            hairpins_.push_back({symbol_span(layout_, first_bar, first),
                                 symbol_span(layout_, last_bar, last), run});
        }
    };
    for (std::size_t b = 0; b < score_.bars.size(); ++b) {
        for (std::size_t s = 0; s < score_.bars[b].symbols.size(); ++s) {
            const Symbol& symbol = score_.bars[b].symbols[s];
            if (std::holds_alternative<Blank>(symbol)) {
                continue;
            }
            const auto* note = std::get_if<Note>(&symbol);
            const Dynamics here = note != nullptr ? note->dynamics : Dynamics::none;
            if (here != run) {
                finish();
                run = here;
                first_bar = b;
                first = s;
            }
            last_bar = b;
            last = s;
        }
    }
    finish();
}

void StaffPicture::find_ties() {
    for (std::size_t b = 0; b < score_.bars.size(); ++b) {
        for (std::size_t s = 0; s < score_.bars[b].symbols.size(); ++s) {
            const editor::Position at{b, s};
            const Note* note = editor::note_at(score_, at);
            const auto next_at = editor::symbol_after(score_, at);
            const Note* next = next_at ? editor::note_at(score_, *next_at) : nullptr;
            if (note == nullptr || next == nullptr) {
                continue;
            }
            const bool slur = note->legato != 0 && note->legato == next->legato;
            const bool glide = note->portamento != 0 && note->portamento == next->portamento;
            if (slur || glide) {
                ties_.push_back({layout_.x_of(at), layout_.x_of(*next_at), note, next});
            }
        }
    }
}

void StaffPicture::draw_hairpins(cairo_t* cairo, const System& system) const {
    const double y = system.top + kClefRow + kDynamicsRow / 2;
    // The hairpins that reach this system's columns, in order: they end in column order too.
    auto hairpin = std::lower_bound(
        hairpins_.begin(), hairpins_.end(), system.begin - kReach,
        [](const Hairpin& h, int column) { return h.to->x + h.to->width < column; });
    for (; hairpin != hairpins_.end() && hairpin->from->x <= system.end + kReach; ++hairpin) {
        const Span* from = hairpin->from;
        const Span* to = hairpin->to;
        const double x0 = column_x(system, from->x + 0.2);
        const double x1 = column_x(system, to->x + std::max(to->width - 1, 1));
        const double open = kHairpinOpen;
        cairo_set_source_rgb(cairo, 0.55, 0.35, 0.0);
        cairo_set_line_width(cairo, 1.2);
        if (hairpin->dynamics == Dynamics::crescendo) {
            cairo_move_to(cairo, x1, y - open);
            cairo_line_to(cairo, x0, y);
            cairo_line_to(cairo, x1, y + open);
        } else {
            cairo_move_to(cairo, x0, y - open);
            cairo_line_to(cairo, x1, y);
            cairo_line_to(cairo, x0, y + open);
        }
        cairo_stroke(cairo);
    }
}

void StaffPicture::draw_ties(cairo_t* cairo, const System& system) const {
    const double below = string_y(system, 1) + 8;
    // The ties that reach this system's columns, in order: they end in column order too.
    auto tie = std::lower_bound(ties_.begin(), ties_.end(), system.begin - kReach,
                                [](const Tie& t, int column) { return t.to + 1 < column; });
    for (; tie != ties_.end() && tie->from <= system.end + kReach; ++tie) {
        const Note* note = tie->note;
        const Note* next = tie->next;
        const double x0 = head_x(system, tie->from);
        const double x1 = head_x(system, tie->to);
        if (note->legato != 0 && note->legato == next->legato) {
            // A slur under the staff.
            cairo_set_source_rgb(cairo, 0.0, 0.45, 0.15);
            cairo_set_line_width(cairo, 1.4);
            cairo_move_to(cairo, x0, below);
            cairo_curve_to(cairo, x0 + 4, below + 10, x1 - 4, below + 10, x1, below);
            cairo_stroke(cairo);
        }
        if (note->portamento != 0 && note->portamento == next->portamento) {
            // A glide: a straight line from head to head.
            cairo_set_source_rgb(cairo, 0.0, 0.35, 0.7);
            cairo_set_line_width(cairo, 1.6);
            cairo_move_to(cairo, x0 + kHeadRx + 1, string_y(system, note->string));
            cairo_line_to(cairo, x1 - kHeadRx - 1, string_y(system, next->string));
            cairo_stroke(cairo);
        }
    }
}

}  // namespace vibscore::pictures
