#include <optional>

#include "client/editor/button_scheme.hpp"

// The mode table: one record per mode, saying what each of the six buttons does in it, what
// the status line says and what is drawn. docs/editor.md's table of the six buttons is this
// table in words.
namespace vibscore::editor {

namespace {

using Use = ButtonScheme::ButtonUse;
using Step = ButtonScheme::Step;
using Buttons = std::array<Use, std::size(all_buttons)>;

// A button this mode leaves alone: pressing it changes nothing.
constexpr Use unused() {
    return {};
}
// The action table's action (what the menu and the keyboard do for it).
constexpr Use act(std::string_view does, Action action, std::optional<Mode> then = std::nullopt) {
    return {does, then, action, nullptr};
}
// A step of the scheme's own.
constexpr Use step(std::string_view does, Step step) {
    return {does, std::nullopt, Action::end, step};
}
// Only to another mode.
constexpr Use to(std::string_view does, Mode mode) {
    return {does, mode, Action::end, nullptr};
}

// The six, named in the order of Button, so a row reads as the hint does.
constexpr Buttons buttons(Use up, Use down, Use left, Use right, Use select, Use back) {
    return {up, down, left, right, select, back};
}
// A layer with buttons of its own (entering, a name, a clef's window): all six go to it.
constexpr Buttons all_to(std::string_view does, Step step_of_layer) {
    const Use use = step(does, step_of_layer);
    return {use, use, use, use, use, use};
}

constexpr bool in_mode_order(std::span<const ButtonScheme::ModeRecord> records) {
    if (records.size() != static_cast<std::size_t>(mode_count)) {
        return false;
    }
    for (std::size_t i = 0; i < records.size(); ++i) {
        if (records[i].mode != static_cast<Mode>(i)) {
            return false;
        }
    }
    return true;
}

}  // namespace

std::span<const ButtonScheme::ModeRecord> ButtonScheme::modes() {
    using K = Keyboard;
    using S = ButtonScheme;
    // Up and Down through a list, Left and Right nothing: every list of choices.
    constexpr Use up = step("choose", &S::list_step);
    constexpr Use down = step("choose", &S::list_step);

    static constexpr ModeRecord kModes[] = {
        {.mode = Mode::browse,
         .name = "browse",
         .buttons =
             buttons(act("string up", Action::move_up), act("string down", Action::move_down),
                     act("left", Action::move_left), act("right", Action::move_right),
                     step("new note or change", &S::begin_entry_step),
                     step("play, go to, menu", &S::open_choices)),
         .live_hint = &S::browse_hint,
         .news_shown = true},
        // Going back to the start, to the end and playing are what a composer does between
        // every few symbols, so they are two presses from browsing rather than a walk through
        // the menu.
        {.mode = Mode::browse_choices,
         .name = "browse's other choices",
         .buttons = buttons(act("play all", Action::play_from_start, Mode::browse),
                            act("play bar", Action::play_or_stop, Mode::browse),
                            act("first", Action::to_first_bar, Mode::browse),
                            act("last", Action::to_last_bar, Mode::browse), to("menu", Mode::menu),
                            to("turn back", Mode::browse)),
         .hint = "\u2191play all \u2193play bar \u2190first \u2192last S:menu"},
        {.mode = Mode::entry,
         .name = "entering",
         .buttons = all_to("entry steps (entry_steps.hpp)", &S::entry),
         .live_hint = &S::entry_hint,
         .news_shown = true},
        {.mode = Mode::menu,
         .name = "menu",
         .buttons = buttons(step("choose", &S::menu_step), step("choose", &S::menu_step),
                            step("group", &S::menu_group), step("group", &S::menu_group),
                            step("ok", &S::menu_choose), to("close", Mode::browse)),
         .hint = "\u2191\u2193choose \u2190\u2192group Sel:ok Back:close",
         .menu = &S::main_menu_view},
        {.mode = Mode::clef_menu,
         .name = "bar clef",
         .buttons = buttons(up, down, unused(), unused(), step("ok", &S::choose_bar_clef),
                            step("close", &S::list_back_to_menu)),
         .hint = "\u2191\u2193choose  Sel:ok  Back:close",
         .menu = &S::clef_menu_view,
         .choices = &S::bar_clef_choices},
        {.mode = Mode::open_menu,
         .name = "open",
         .buttons = buttons(up, down, unused(), unused(), step("ok", &S::choose_score),
                            step("close", &S::list_back_to_menu)),
         .hint = "\u2191\u2193choose  Sel:ok  Back:close",
         .menu = &S::open_menu_view,
         .choices = &S::score_choices},
        {.mode = Mode::quit_menu,
         .name = "unsaved changes",
         .buttons = buttons(up, down, unused(), unused(), step("ok", &S::choose_quit),
                            step("close", &S::list_back_to_browse)),
         .hint = "\u2191\u2193choose  Sel:ok  Back:close",
         .menu = &S::quit_menu_view,
         .choices = &S::three_choices},
        {.mode = Mode::name_entry,
         .name = "save as",
         .buttons = all_to("name entry (name_entry.hpp)", &S::name_press),
         .live_hint = &S::name_hint,
         .menu = &S::name_view,
         .keyboard = K::typing},
        {.mode = Mode::replace_menu,
         .name = "name taken",
         .buttons = buttons(up, down, unused(), unused(), step("ok", &S::replace_choose),
                            to("cancel", Mode::browse)),
         .live_hint = &S::replace_hint,
         .menu = &S::replace_view,
         .choices = &S::three_choices},
        {.mode = Mode::tapping,
         .name = "tapping",
         .buttons = buttons(step("done", &S::finish_tapping), step("rest", &S::tap_rest),
                            step("drop", &S::drop_tapping), unused(), step("note", &S::tap_note),
                            step("done", &S::finish_tapping)),
         .live_hint = &S::tapping_hint},
        {.mode = Mode::use_for,
         .name = "use for",
         .buttons = buttons(up, down, unused(), unused(), step("ok", &S::use_for_choose),
                            to("close", Mode::browse)),
         .live_hint = &S::use_for_hint,
         .menu = &S::use_for_view,
         .choices = &S::event_choices},
        {.mode = Mode::assigned,
         .name = "assigned",
         .buttons = buttons(up, down, unused(), unused(), step("ok", &S::assigned_choose),
                            to("close", Mode::browse)),
         .hint = "\u2191\u2193choose Sel:ok",
         .menu = &S::assigned_view,
         .choices = &S::two_choices},
        {.mode = Mode::no_events,
         .name = "no events",
         .buttons = buttons(unused(), unused(), unused(), unused(), to("close", Mode::browse),
                            to("close", Mode::browse)),
         .hint = "Sel/Back:close",
         .menu = &S::no_events_view},
        {.mode = Mode::clef_list,
         .name = "edit clefs",
         .buttons = buttons(up, down, unused(), unused(), step("edit", &S::clef_list_choose),
                            to("close", Mode::menu)),
         .hint = "\u2191\u2193choose Sel:edit Back:close",
         .menu = &S::clef_list_view,
         .choices = &S::clef_choices,
         .keyboard = K::clef_open},
        {.mode = Mode::clef_edit,
         .name = "clef",
         .buttons = all_to("clef window (clef_editor.hpp)", &S::clef_edit_press),
         .live_hint = &S::clef_edit_hint,
         .keyboard = K::clef_open,
         .clef_window = true},
        {.mode = Mode::clef_name,
         .name = "save clef as",
         .buttons = all_to("name entry (name_entry.hpp)", &S::clef_name_press),
         .live_hint = &S::name_hint,
         .menu = &S::clef_name_view,
         .keyboard = K::typing,
         .clef_window = true},
        {.mode = Mode::clef_close,
         .name = "clef changed",
         .buttons = buttons(up, down, unused(), unused(), step("ok", &S::clef_close_choose),
                            to("cancel", Mode::clef_edit)),
         .hint = "\u2191\u2193choose Sel:ok",
         .menu = &S::clef_close_view,
         .choices = &S::three_choices,
         .keyboard = K::clef_open,
         .clef_window = true},
        {.mode = Mode::playing,
         .name = "playing",
         .buttons = all_to("stop", &S::stop),
         .hint = "playing: any button stops",
         .keyboard = K::stop},
    };
    static_assert(in_mode_order(kModes), "one record per Mode, in the order of Mode");
    return kModes;
}

}  // namespace vibscore::editor
