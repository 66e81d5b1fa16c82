#include "client/editor/ncurses_view.hpp"

#include <curses.h>

#include <algorithm>
#include <clocale>
#include <cstdlib>
#include <stdexcept>

#include "client/editor/menu.hpp"
#include "client/editor/staff_layout.hpp"
#include "client/editor/staff_options.hpp"
#include "client/editor/status_line.hpp"

namespace vibscore::editor {

namespace {

// Colour pairs: one per ink for each background an overlay can give it.
enum Background { bg_default, bg_cursor, bg_selected, bg_playing, backgrounds };
constexpr int kInks = static_cast<int>(Ink::mark) + 1;

short foreground(Ink ink) {
    switch (ink) {
        case Ink::line:
        case Ink::length:
        case Ink::blank:
        case Ink::head:
        case Ink::rest:
            return COLOR_WHITE;
        case Ink::sustain:
            return COLOR_CYAN;
        case Ink::dynamics:
            return COLOR_YELLOW;
        case Ink::tie:
            return COLOR_GREEN;
        case Ink::clef_fewer:
        case Ink::clef_exact:
        case Ink::clef_more:
            return COLOR_BLACK;
        case Ink::playback:
            return COLOR_RED;
        case Ink::mark:
            return COLOR_WHITE;
    }
    return COLOR_WHITE;
}

short background(Ink ink, Background overlay) {
    switch (overlay) {
        case bg_cursor:
            return COLOR_BLUE;
        case bg_selected:
            return COLOR_YELLOW;
        case bg_playing:
            return COLOR_RED;
        default:
            break;
    }
    switch (ink) {
        case Ink::clef_fewer:
            return COLOR_CYAN;
        case Ink::clef_exact:
            return COLOR_WHITE;
        case Ink::clef_more:
            return COLOR_MAGENTA;
        default:
            return -1;
    }
}

short pair_of(Ink ink, Background overlay) {
    return static_cast<short>(1 + static_cast<int>(ink) * backgrounds + overlay);
}

attr_t attributes(const Cell& cell) {
    Background overlay = bg_default;
    if (cell.overlay & overlay_playing) {
        overlay = bg_playing;
    } else if (cell.overlay & overlay_selected) {
        overlay = bg_selected;
    } else if (cell.overlay & overlay_cursor_column) {
        overlay = bg_cursor;
    }
    attr_t attr = has_colors() ? COLOR_PAIR(pair_of(cell.ink, overlay)) : A_NORMAL;
    if (cell.ink == Ink::head || cell.ink == Ink::rest || cell.ink == Ink::mark) {
        attr |= A_BOLD;
    }
    if (cell.ink == Ink::line || cell.ink == Ink::length) {
        attr |= A_DIM;
    }
    if (!has_colors() && (cell.overlay & (overlay_cursor_column | overlay_selected))) {
        attr |= A_UNDERLINE;
    }
    if (cell.overlay & overlay_cursor) {
        attr |= A_REVERSE | A_BOLD;
    }
    return attr;
}

}  // namespace

Screen::Screen() {
    std::setlocale(LC_ALL, "");
    // Escape is the Back key: do not wait long to tell it from an arrow key's sequence.
    setenv("ESCDELAY", "25", 0);
    if (initscr() == nullptr) {
        throw std::runtime_error("cannot start the terminal (TERM not set?)");
    }
    raw();  // Ctrl-C, Ctrl-Z, Ctrl-S ... are editing keys here
    noecho();
    keypad(stdscr, TRUE);
    nodelay(stdscr, TRUE);
    curs_set(0);
    if (has_colors()) {
        start_color();
        use_default_colors();
        for (int ink = 0; ink < kInks; ++ink) {
            for (int overlay = 0; overlay < backgrounds; ++overlay) {
                const auto i = static_cast<Ink>(ink);
                const auto o = static_cast<Background>(overlay);
                init_pair(pair_of(i, o), foreground(i), background(i, o));
            }
        }
    }
}

Screen::~Screen() {
    endwin();
}

std::optional<int> Screen::key() {
    int code = getch();
    while (code == KEY_RESIZE) {
        code = getch();  // the next draw uses the new size
    }
    if (code == ERR) {
        return std::nullopt;
    }
    return code;
}

void Screen::draw(const EditorModel& model, const ButtonScheme& scheme, const ViewStatus& status) {
    int rows = 0;
    int cols = 0;
    getmaxyx(stdscr, rows, cols);
    werase(stdscr);

    const LayoutOptions options = staff_options(model, scheme, status.playing);
    const auto layout = layout_staff(model.score(), options);

    // 40x12: eleven staff rows and a status line; taller screens get a title and a hint line.
    const bool roomy = rows >= staff_rows + 3;
    const int top = roomy ? 1 : 0;
    const int staff_height = std::min(static_cast<int>(staff_rows), rows - 1 - top);
    const Position focus = status.playing ? *status.playing : model.cursor();
    const int focus_x = std::max(layout.x_of(focus), 0);
    first_column_ = scroll_to_show(first_column_, cols, focus_x, layout.width);

    if (const ClefEditor* clef = scheme.clef_editor()) {
        // A clef's window where the staff was: the field under the cursor marked '>'.
        const auto lines = clef->lines(cols, staff_height, status.feel);
        for (int row = 0; row < static_cast<int>(lines.size()); ++row) {
            const auto& line = lines[static_cast<std::size_t>(row)];
            attrset(line.starts_with(">") ? A_BOLD : A_NORMAL);
            mvaddstr(top + row, 0, line.c_str());
        }
    } else {
        for (int row = 0; row < staff_height; ++row) {
            move(top + row, 0);
            for (int x = first_column_; x < first_column_ + cols && x < layout.width; ++x) {
                const Cell& cell =
                    layout.rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)];
                attrset(attributes(cell));
                addstr(cell.glyph.c_str());
            }
        }
    }
    attrset(A_NORMAL);

    const std::string dirty = model.modified() ? "*" : "";
    const std::string news = !status.message.empty() ? status.message : model.message();
    const StatusParts parts = status_of(model, scheme, news, status.playing);
    const std::string hint =
        parts.entering.empty() ? parts.hint : parts.entering + " " + parts.hint;
    if (roomy) {
        const auto& bars = model.score().bars;
        const std::string title =
            dirty + status.name + (model.score().title.empty() ? "" : " - " + model.score().title) +
            "  bar " + std::to_string(model.cursor().bar + 1) + "/" + std::to_string(bars.size());
        attrset(A_BOLD);
        mvaddstr(0, 0, fit(title, cols).c_str());
        attrset(A_NORMAL);
        mvaddstr(rows - 2, 0, fit(parts.message, cols).c_str());
        if (rows >= staff_rows + 4 && cols >= columns_of(keyboard_hint())) {
            attrset(A_DIM);
            mvaddstr(rows - 3, 0, keyboard_hint().c_str());
        }
        attrset(A_DIM);
        mvaddstr(rows - 1, 0, fit(hint, cols).c_str());
        attrset(A_NORMAL);
    } else {
        mvaddstr(rows - 1, 0, status_line(parts, cols).c_str());
    }
    const auto menu = scheme.menu_view(model);
    if (!menu.lines.empty()) {
        draw_menu(menu, rows, cols);
    }
    refresh();
}

void Screen::draw_menu(const ButtonScheme::MenuView& menu, int rows, int cols) {
    int widest = columns_of(menu.title);
    for (const auto& line : menu.lines) {
        widest = std::max(widest, columns_of(line));
    }
    const int width = std::min(widest + 4, cols);
    // Lines wider than the screen are wrapped, never cut: an event's name shows whole.
    const auto drawn = menu_rows(menu.lines, width - 3);
    const int count = static_cast<int>(drawn.size());
    const int visible = std::max(1, std::min(count, rows - 3));
    const int height = visible + 2;
    const int left = std::max(0, cols - width);
    const int top = std::max(0, (rows - 1 - height) / 2);
    // The rows around the highlighted line's first row.
    int at = 0;
    for (int row = 0; row < count; ++row) {
        if (drawn[static_cast<std::size_t>(row)].line == menu.highlighted) {
            at = row;
            break;
        }
    }
    const int first = std::clamp(at - visible / 2, 0, count - visible);
    for (int row = 0; row < height; ++row) {
        mvaddstr(top + row, left, std::string(static_cast<std::size_t>(width), ' ').c_str());
    }
    attrset(A_BOLD);
    mvaddstr(
        top, left,
        ("+" + fit(" " + menu.title + " ", width - 2) +
         std::string(static_cast<std::size_t>(std::max(0, width - 2 - columns_of(menu.title) - 2)),
                     '-') +
         "+")
            .c_str());
    attrset(A_NORMAL);
    for (int i = 0; i < visible; ++i) {
        const auto& row = drawn[static_cast<std::size_t>(first + i)];
        const bool chosen = row.line == menu.highlighted;
        const bool starts =
            first + i == 0 || drawn[static_cast<std::size_t>(first + i - 1)].line != row.line;
        attrset(chosen ? A_REVERSE : A_NORMAL);
        mvaddstr(top + 1 + i, left,
                 ("|" + std::string(chosen && starts ? ">" : " ") + row.text).c_str());
        attrset(A_NORMAL);
    }
    mvaddstr(
        top + height - 1, left,
        ("+" + std::string(static_cast<std::size_t>(std::max(0, width - 2)), '-') + "+").c_str());
}

}  // namespace vibscore::editor
