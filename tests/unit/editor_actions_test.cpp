// The action table (client/editor/actions.*): one record per action gives its name, keys, menu
// line and who does it, and the keyboard, the menu and the dispatch all read it.
#include <gtest/gtest.h>

#include <set>

#include "client/editor/actions.hpp"
#include "client/editor/menu.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Action;
using editor::action_records;
using editor::Command;
using editor::record_of;
using testing::fresh_editor;
using testing::highlighted;
using testing::to_menu_entry;

using namespace testing::buttons;

TEST(EditorActions, EveryActionHasOneRecordDoneByTheModelOrTheSession) {
    ASSERT_EQ(action_records().size(), static_cast<std::size_t>(editor::action_count));
    for (const auto& record : action_records()) {
        EXPECT_EQ(&record_of(record.action), &record);
        EXPECT_NE(record.model == nullptr, record.session == nullptr) << record.name;
        EXPECT_FALSE(record.name.empty());
        EXPECT_EQ(editor::to_string(record.action), record.name);
    }
}

TEST(EditorActions, EachKeyOfARecordNamesItsActionWithItsValue) {
    std::size_t keys = 0;
    for (const auto& record : action_records()) {
        for (const auto& binding : record.keys) {
            if (binding.code == 0) {
                break;
            }
            ++keys;
            const auto input = editor::key_input(binding.code);
            ASSERT_TRUE(input) << record.name;
            EXPECT_EQ(std::get<Command>(*input), (Command{record.action, binding.value}))
                << record.name << " key " << binding.code;
        }
    }
    EXPECT_EQ(keys, 57u);  // docs/editor.md's keyboard table: 38 keys, 1-9, Shift+1..0
    EXPECT_EQ(editor::key_input('7'), (editor::KeyInput{Command{Action::insert_note, 7}}));
    EXPECT_EQ(
        editor::key_input(')'),
        (editor::KeyInput{Command{Action::set_length, static_cast<int>(Length::thirty_second)}}));
    EXPECT_FALSE(editor::key_input('Z'));
}

TEST(EditorActions, TheMenuIsTheRecordsInTheMenuInTheirGroups) {
    auto editor = fresh_editor();
    const auto menu = editor::main_menu(editor.model);
    std::size_t in_menu = 0;
    for (const auto& record : action_records()) {
        in_menu += record.in_menu() && record.shown != editor::Shown::marked ? 1 : 0;
    }
    ASSERT_EQ(menu.size(), in_menu);
    for (std::size_t i = 0; i < menu.size(); ++i) {
        const auto& record = record_of(menu[i].action);
        EXPECT_EQ(menu[i].label, record.label);
        EXPECT_EQ(menu[i].group, record.group);
        if (i > 0) {
            EXPECT_LE(menu[i - 1].group, menu[i].group) << record.label;
        }
    }
    // Marking swaps "mark block" for "unmark block" in the same place.
    editor.model.mark_block();
    const auto marked = editor::main_menu(editor.model);
    ASSERT_EQ(marked.size(), menu.size());
    for (std::size_t i = 0; i < menu.size(); ++i) {
        if (menu[i].action == Action::mark_block) {
            EXPECT_EQ(marked[i].action, Action::clear_block);
            EXPECT_EQ(marked[i].label, "unmark block");
        } else {
            EXPECT_EQ(marked[i].action, menu[i].action);
        }
    }
}

TEST(EditorActions, AMenuLineDoesWhatItsKeyDoes) {
    // The same record behind both: crescendo from the menu and from 'c' give one score.
    auto from_menu = fresh_editor();
    auto from_key = fresh_editor();
    testing::type(from_menu, "5");
    testing::type(from_key, "5");
    to_menu_entry(from_menu, "crescendo  <");
    testing::press(from_menu, {S});
    testing::type(from_key, "c");
    EXPECT_EQ(from_menu.model.score(), from_key.model.score());
    EXPECT_EQ(std::get<Note>(from_key.model.score().bars[0].symbols[0]).dynamics,
              Dynamics::crescendo);
}

TEST(EditorActions, TheModelRefusesTheSessionsActionsAndSaysWhy) {
    auto editor = fresh_editor();
    for (const auto& record : action_records()) {
        if (record.session != nullptr) {
            EXPECT_FALSE(editor.model.apply({record.action}));
            EXPECT_EQ(editor.model.message(),
                      std::string(record.name) + " is not an editing function");
        }
    }
    EXPECT_FALSE(editor.model.apply({Action::end}));
    EXPECT_EQ(editor.model.message(), "no such editing function");
    // A length by its index: the last there is and the first beyond, on both sides.
    EXPECT_TRUE(editor.model.apply({Action::set_length, length_count - 1}));
    EXPECT_EQ(editor.model.current_length(), Length::thirty_second);
    EXPECT_FALSE(editor.model.apply({Action::set_length, length_count}));
    EXPECT_EQ(editor.model.message(), "no such length");
    EXPECT_TRUE(editor.model.apply({Action::set_length, 0}));
    EXPECT_EQ(editor.model.current_length(), Length::whole);
    EXPECT_FALSE(editor.model.apply({Action::set_length, -1}));
}

TEST(EditorActions, EachIsDoneByTheModelOrByTheSession) {
    EXPECT_TRUE(editor::each_action_done_by_one());
}

}  // namespace
}  // namespace vibscore
