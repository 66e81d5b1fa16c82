// The mode table (client/editor/mode_table.cpp): every mode has its record, every button in it
// does something or is unused on purpose, and every mode says on the status line what the
// buttons do. The second half reaches each mode as a person does and holds the record to what
// the editor then does.
#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>

#include "client/editor/status_line.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Action;
using editor::Button;
using editor::ButtonScheme;
using editor::Command;
using editor::Mode;
using editor::Request;

TEST(ModeTable, HasOneRecordForEveryModeInTheOrderOfMode) {
    ASSERT_EQ(ButtonScheme::modes().size(), static_cast<std::size_t>(editor::mode_count));
    for (int i = 0; i < editor::mode_count; ++i) {
        const auto mode = static_cast<Mode>(i);
        EXPECT_EQ(ButtonScheme::mode_record(mode).mode, mode) << "record " << i;
    }
    // The last mode has a record; the sentinel after it is no mode.
    EXPECT_EQ(ButtonScheme::modes().back().mode, Mode::playing);
    EXPECT_EQ(static_cast<int>(Mode::playing) + 1, editor::mode_count);
}

TEST(ModeTable, NamesEveryModeOnce) {
    std::set<std::string_view> names;
    for (const auto& record : ButtonScheme::modes()) {
        EXPECT_FALSE(record.name.empty()) << static_cast<int>(record.mode);
        EXPECT_TRUE(names.insert(record.name).second) << record.name;
    }
}

TEST(ModeTable, EveryButtonOfEveryModeDoesOneThingOrIsUnusedOnPurpose) {
    for (const auto& record : ButtonScheme::modes()) {
        for (const Button button : editor::all_buttons) {
            const auto& use = record.buttons[static_cast<std::size_t>(button)];
            const std::string where =
                std::string(record.name) + ", " + std::string(editor::to_string(button));
            // Words exactly for the buttons that do something: the unused say nothing.
            EXPECT_EQ(use.used(), !use.does.empty()) << where;
            // An action of the table or a step of the scheme's, never both.
            EXPECT_FALSE(use.action != Action::end && use.step != nullptr) << where;
            if (use.action != Action::end) {
                EXPECT_LT(static_cast<int>(use.action), editor::action_count) << where;
            }
            if (use.then) {
                EXPECT_LT(static_cast<int>(*use.then), editor::mode_count) << where;
            }
        }
    }
}

TEST(ModeTable, EveryModeHasAStatusTextFixedOrLiveButNotBoth) {
    for (const auto& record : ButtonScheme::modes()) {
        EXPECT_NE(record.hint.empty(), record.live_hint == nullptr) << record.name;
        EXPECT_LE(editor::columns_of(std::string(record.hint)), 40) << record.hint;
    }
}

TEST(ModeTable, ListsSayHowManyChoicesUpAndDownMoveThrough) {
    // A list (Up and Down choose, Left and Right unused) needs its count of lines.
    for (const auto& record : ButtonScheme::modes()) {
        const auto& up = record.buttons[static_cast<std::size_t>(Button::up)];
        const bool a_list = up.does == "choose" && record.mode != Mode::menu;
        EXPECT_EQ(a_list, record.choices != nullptr) << record.name;
    }
}

// Each mode as a person reaches it, from a fresh score.
struct Way {
    Mode mode;
    std::function<void(editor::Editor&)> go;
};

Clef a_clef() {
    Clef clef;
    clef.tempo = 0.2;
    clef.numbers = {0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    for (const double hz : {155.0, 170.0, 185.0, 200.0, 215.0, 235.0}) {
        clef.strings.push_back({hz, {}});
    }
    return clef;
}

void with_clefs(editor::Editor& editor) {
    editor.scheme.set_clef_book(editor::ClefBook({{testing::kLra, a_clef(), true}}));
    editor.scheme.command(Command{Action::edit_clefs}, editor.model);
}

void with_an_event(editor::Editor& editor) {
    editor.scheme.set_events({{"phone-incoming-call", "", "", false}});
}

const std::vector<Way>& ways() {
    using namespace testing::buttons;
    static const std::vector<Way> all{
        {Mode::browse, [](editor::Editor&) {}},
        {Mode::browse_choices, [](editor::Editor& e) { testing::press(e, {B}); }},
        {Mode::entry, [](editor::Editor& e) { testing::press(e, {S}); }},
        {Mode::menu,
         [](editor::Editor& e) {
             testing::press(e, {B, S});
         }},
        {Mode::clef_menu,
         [](editor::Editor& e) { e.scheme.command(Command{Action::choose_clef}, e.model); }},
        {Mode::open_menu,
         [](editor::Editor& e) {
             e.scheme.set_openable({"heartbeat", "ring"});
             e.scheme.command(Command{Action::open}, e.model);
         }},
        {Mode::quit_menu,
         [](editor::Editor& e) {
             testing::type(e, "5");
             e.scheme.command(Command{Action::quit}, e.model);
         }},
        {Mode::name_entry,
         [](editor::Editor& e) { e.scheme.command(Command{Action::save_as}, e.model); }},
        {Mode::replace_menu,
         [](editor::Editor& e) {
             e.scheme.set_destination("mine", false);
             e.scheme.set_taken({{"mine", editor::TakenName::What::stored}});
             e.scheme.command(Command{Action::save}, e.model);
         }},
        {Mode::tapping,
         [](editor::Editor& e) { e.scheme.command(Command{Action::tap_rhythm}, e.model); }},
        {Mode::use_for,
         [](editor::Editor& e) {
             with_an_event(e);
             e.scheme.command(Command{Action::save_as}, e.model);
         }},
        {Mode::assigned,
         [](editor::Editor& e) {
             with_an_event(e);
             e.scheme.show_assigned("phone-incoming-call", "ring");
         }},
        {Mode::no_events,
         [](editor::Editor& e) { e.scheme.command(Command{Action::use_for_event}, e.model); }},
        {Mode::clef_list, [](editor::Editor& e) { with_clefs(e); }},
        {Mode::clef_edit,
         [](editor::Editor& e) {
             with_clefs(e);
             testing::press(e, {S});
         }},
        {Mode::clef_name,
         [](editor::Editor& e) {
             with_clefs(e);
             testing::press(e, {S, B, S});
         }},
        {Mode::clef_close,
         [](editor::Editor& e) {
             with_clefs(e);
             testing::press(e, {S, D, R, B, B});
         }},
        {Mode::playing, [](editor::Editor& e) { e.scheme.set_playing(true); }},
    };
    return all;
}

TEST(ModeTable, EveryModeIsReachedByTheWaysBelowSoEachRecordIsHeldToTheEditor) {
    std::set<Mode> reached;
    for (const auto& way : ways()) {
        auto editor = testing::fresh_editor();
        way.go(editor);
        ASSERT_EQ(editor.scheme.mode(), way.mode)
            << ButtonScheme::mode_record(way.mode).name << " not reached";
        reached.insert(way.mode);
    }
    EXPECT_EQ(reached.size(), static_cast<std::size_t>(editor::mode_count));
}

TEST(ModeTable, EachModeShowsANonEmptyStatusTextAndAMenuExactlyWhenItsRecordHasOne) {
    for (const auto& way : ways()) {
        auto editor = testing::fresh_editor();
        way.go(editor);
        const auto& record = ButtonScheme::mode_record(way.mode);
        EXPECT_FALSE(editor.scheme.hint(editor.model).empty()) << record.name;
        const auto menu = editor.scheme.menu_view(editor.model);
        EXPECT_EQ(record.menu != nullptr, !menu.title.empty()) << record.name;
        EXPECT_EQ(record.keyboard == ButtonScheme::Keyboard::typing, editor.scheme.typing_a_name())
            << record.name;
        EXPECT_EQ(record.clef_window, editor.scheme.clef_editor() != nullptr) << record.name;
    }
}

TEST(ModeTable, AnUnusedButtonChangesNothing) {
    for (const auto& way : ways()) {
        const auto& record = ButtonScheme::mode_record(way.mode);
        for (const Button button : editor::all_buttons) {
            auto editor = testing::fresh_editor();
            way.go(editor);
            const auto before = editor;
            const Request request = editor.press(button);
            if (!record.buttons[static_cast<std::size_t>(button)].used()) {
                EXPECT_EQ(request, Request{}) << record.name << ", " << editor::to_string(button);
                EXPECT_TRUE(editor == before) << record.name << ", " << editor::to_string(button);
            }
        }
    }
}

TEST(ModeTable, ThenGoesToItsModeBeforeTheActionOrStep) {
    // Browse's other choices go back to browsing whatever they do: Left goes to the first bar.
    auto editor = testing::fresh_editor();
    testing::press(editor, {testing::buttons::B, testing::buttons::L});
    EXPECT_EQ(editor.scheme.mode(), Mode::browse);
}

}  // namespace
}  // namespace vibscore
