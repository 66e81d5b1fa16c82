// Save-as with the six buttons: a name typed with them (NameEntry), a free name proposed, and a
// question before a taken name (a shipped score) is replaced.
#include <gtest/gtest.h>

#include "client/editor/name_entry.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Button;
using editor::ButtonScheme;
using editor::NameEntry;
using editor::Request;
using testing::fresh_editor;
using testing::highlighted;
using testing::press;
using testing::to_menu_entry;

using namespace testing::buttons;

NameEntry::Outcome press_all(NameEntry& entry, std::initializer_list<Button> buttons) {
    NameEntry::Outcome outcome = NameEntry::Outcome::typing;
    for (const auto button : buttons) {
        outcome = entry.press(button);
    }
    return outcome;
}

TEST(EditorNameEntry, AFreeNameFollowsTheNameAndItsNumber) {
    EXPECT_EQ(editor::free_name("ringtone", {"alarm", "ringtone"}), "ringtone-2");
    EXPECT_EQ(editor::free_name("ringtone", {"ringtone", "ringtone-2"}), "ringtone-3");
    EXPECT_EQ(editor::free_name("ringtone-2", {"ringtone", "ringtone-2"}), "ringtone-3");
    EXPECT_EQ(editor::free_name("tacton-1", {"tacton-1"}), "tacton-2");
    EXPECT_EQ(editor::free_name("My Song", {}), "tacton-2");
    EXPECT_EQ(editor::free_name("", {}), "tacton-2");
    const std::string longest(64, 'a');
    EXPECT_EQ(editor::free_name(longest, {longest}), std::string(62, 'a') + "-2");
}

TEST(EditorNameEntry, AFreeNameOfTheLongestNameStaysWithin64CharactersAtTwoDigits) {
    // -2 ... -9 taken for a 64-character name: the next free one is -10, cut to fit 64, never
    // a 65-character name that save-as would then refuse.
    const std::string longest(64, 'a');
    std::vector<std::string> taken{longest};
    for (int n = 2; n <= 9; ++n) {
        taken.push_back(std::string(62, 'a') + "-" + std::to_string(n));
    }
    const auto ten = editor::free_name(longest, taken);
    EXPECT_EQ(ten, std::string(61, 'a') + "-10");
    EXPECT_EQ(ten.size(), 64u);
    EXPECT_TRUE(editor::is_registry_name(ten));
    // One character shorter: -10 fits without cutting the name.
    const std::string shorter(61, 'a');
    std::vector<std::string> taken_shorter{shorter};
    for (int n = 2; n <= 9; ++n) {
        taken_shorter.push_back(shorter + "-" + std::to_string(n));
    }
    EXPECT_EQ(editor::free_name(shorter, taken_shorter), shorter + "-10");
}

TEST(EditorNameEntry, SelectKeepsTheProposedNameAtOnce) {
    NameEntry entry;
    entry.start("ringtone-2");
    EXPECT_EQ(entry.shown(), "ringtone-[2]");
    EXPECT_EQ(entry.hint(), "\u21913 \u21931 \u2190\u2192move S:save B:more");
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::done);
    EXPECT_EQ(entry.name(), "ringtone-2");
}

TEST(EditorNameEntry, UpAndDownStepTheCharacterLeftAndRightMoveAndRightAtTheEndAddsOne) {
    NameEntry entry;
    entry.start("ab");
    press_all(entry, {D, D, D});  // b a _ .: down steps back through the characters, wrapping
    EXPECT_EQ(entry.name(), "a.");
    press_all(entry, {U, U, U, U});  // . _ a b c
    EXPECT_EQ(entry.name(), "ac");
    press_all(entry, {R, U, U});  // a new character at the end, stepped from 'a' to 'c'
    EXPECT_EQ(entry.name(), "acc");
    press_all(entry, {L, L, L, D});  // the cursor stops at the first character
    EXPECT_EQ(entry.cursor(), 0u);
    EXPECT_EQ(entry.name(), "_cc");
    // A name starting with '_' is not a registry name: Select does not take it, and says why.
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::typing);
    EXPECT_EQ(entry.problem(), "a name starts with a letter or digit");
    EXPECT_EQ(press_all(entry, {U, S}), NameEntry::Outcome::done);
    EXPECT_EQ(entry.name(), "acc");
}

TEST(EditorNameEntry, BackOffersDeleteInsertAndCancel) {
    NameEntry entry;
    entry.start("abc");
    press_all(entry, {L, B});
    EXPECT_TRUE(entry.more());
    EXPECT_EQ(entry.hint(), "\u2193delete \u2191insert S:type B:cancel");
    press_all(entry, {D});  // 'b' goes
    EXPECT_EQ(entry.name(), "ac");
    EXPECT_FALSE(entry.more());
    press_all(entry, {B, U});  // a copy of the character under the cursor goes in before it
    EXPECT_EQ(entry.name(), "acc");
    press_all(entry, {B, S});  // back to typing, nothing changed
    EXPECT_FALSE(entry.more());
    EXPECT_EQ(entry.name(), "acc");
    EXPECT_EQ(press_all(entry, {B, B}), NameEntry::Outcome::cancelled);
}

TEST(EditorNameEntry, TheLastCharacterIsNotDeletedAndNamesStopAt64) {
    NameEntry entry;
    entry.start("a");
    press_all(entry, {B, D});
    EXPECT_EQ(entry.name(), "a");
    entry.start(std::string(64, 'a'));
    press_all(entry, {R});
    EXPECT_EQ(entry.name().size(), 64u);
    EXPECT_TRUE(editor::is_registry_name(entry.name()));
    EXPECT_FALSE(editor::is_registry_name(std::string(65, 'a')));
    EXPECT_FALSE(editor::is_registry_name("A"));
    EXPECT_FALSE(editor::is_registry_name("-a"));
}

constexpr auto Shipped = editor::TakenName::What::shipped;
constexpr auto Stored = editor::TakenName::What::stored;

// An editor on the shipped "ringtone", as `vibscore edit ringtone` opens it.
editor::Editor opened_ringtone() {
    auto editor = fresh_editor();
    editor.scheme.set_openable({"alarm", "ringtone"});
    editor.scheme.set_taken({{"alarm", Shipped}, {"ringtone", Shipped}});
    editor.scheme.set_destination("ringtone", false);
    return editor;
}

TEST(EditorSaveAs, TheProposedFreeNameIsOneSelectAway) {
    auto editor = opened_ringtone();
    press(editor, {S, S, B, B});  // a change
    to_menu_entry(editor, "save as...");
    press(editor, {S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::name_entry);
    const auto view = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(view.title, "save as");
    EXPECT_EQ(view.lines, std::vector<std::string>{"ringtone-[2]"});
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save_as, "ringtone-2"}));
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorSaveAs, ATypedNameIsSavedUnder) {
    auto editor = opened_ringtone();
    to_menu_entry(editor, "save as...");
    press(editor, {S, U, U});  // ringtone-4
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u21915 \u21933 \u2190\u2192move S:save B:more");
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save_as, "ringtone-4"}));
}

TEST(EditorSaveAs, SavingOverTheOpenedShippedScoreAsksFirst) {
    auto editor = opened_ringtone();
    press(editor, {S, S, B, B});
    to_menu_entry(editor, "save");
    EXPECT_EQ(editor.press(S).kind, Request::Kind::none);
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::replace_menu);
    const auto view = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(view.title, "ringtone is shipped");
    EXPECT_EQ(view.lines,
              (std::vector<std::string>{"save as another name", "store yours over it", "cancel"}));
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u2191\u2193choose Sel:ok (shipped file stays)");
    // The first choice, one Select, is the free name, one Select more to save.
    press(editor, {S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::name_entry);
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save_as, "ringtone-2"}));
}

TEST(EditorSaveAs, ReplacingIsAskedOnceAndCancelSavesNothing) {
    auto editor = opened_ringtone();
    to_menu_entry(editor, "save");
    press(editor, {S, D, D});
    EXPECT_EQ(highlighted(editor), "cancel");
    EXPECT_EQ(editor.press(S).kind, Request::Kind::none);
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    to_menu_entry(editor, "save");
    press(editor, {S, D});
    EXPECT_EQ(editor.press(S).kind, Request::Kind::save);
    // Replaced once: the next save asks nothing.
    to_menu_entry(editor, "save");
    EXPECT_EQ(editor.press(S).kind, Request::Kind::save);
}

TEST(EditorSaveAs, ATypedTakenNameAsksAndSaveAndQuitAsksToo) {
    auto editor = opened_ringtone();
    to_menu_entry(editor, "save as...");
    editor.scheme.set_taken({{"alarm", Shipped}, {"ringtone", Shipped}, {"ringtone-3", Stored}});
    press(editor, {S, U});  // ringtone-3, stored before
    press(editor, {S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::replace_menu);
    // A stored score is replaced for good, and the question says so.
    const auto view = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(view.title, "ringtone-3 exists");
    EXPECT_EQ(view.lines[1], "replace ringtone-3");
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u2191\u2193choose Sel:ok (old one is lost)");
    press(editor, {D});
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save_as, "ringtone-3"}));

    // Save and quit on a taken name asks as well, and quits once saved.
    auto quitting = opened_ringtone();
    press(quitting, {S, S, B, B});
    to_menu_entry(quitting, "quit");
    press(quitting, {S});
    EXPECT_EQ(quitting.scheme.mode(), ButtonScheme::Mode::quit_menu);
    press(quitting, {S});
    EXPECT_EQ(quitting.scheme.mode(), ButtonScheme::Mode::replace_menu);
    press(quitting, {S});
    EXPECT_EQ(quitting.press(S), (Request{Request::Kind::save_as, "ringtone-2", 0, true}));
}

// What replacing loses decides the words: a shipped score stays (shadowed), a stored score
// shadowing it and a file beside the one edited are gone.
TEST(EditorSaveAs, TheQuestionSaysWhetherTheTakenNameIsShippedStoredOrAFile) {
    const auto asked = [](editor::TakenName taken) {
        auto editor = fresh_editor();
        editor.scheme.set_taken({taken});
        editor.scheme.set_destination(taken.name, false);
        to_menu_entry(editor, "save");
        press(editor, {S});
        EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::replace_menu);
        const auto view = editor.scheme.menu_view(editor.model);
        return view.title + " | " + view.lines[1] + " | " + editor.scheme.hint(editor.model);
    };
    EXPECT_EQ(asked({"ringtone", Shipped}),
              "ringtone is shipped | store yours over it | \u2191\u2193choose Sel:ok (shipped file "
              "stays)");
    EXPECT_EQ(asked({"ringtone", editor::TakenName::What::stored_over_shipped}),
              "ringtone exists | replace ringtone | \u2191\u2193choose Sel:ok (old one is lost)");
    EXPECT_EQ(asked({"buzz", Stored}),
              "buzz exists | replace buzz | \u2191\u2193choose Sel:ok (old one is lost)");
    EXPECT_EQ(asked({"buzz", editor::TakenName::What::file}),
              "buzz exists | replace buzz | \u2191\u2193choose Sel:ok (old file is lost)");
}

TEST(EditorSaveAs, BackInTheUnsavedChangesQuestionReturnsToBrowsing) {
    auto editor = fresh_editor();
    press(editor, {S, S, B, B});  // a change
    to_menu_entry(editor, "quit");
    press(editor, {S});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::quit_menu);
    EXPECT_EQ(editor.scheme.menu_view(editor.model).title, "unsaved changes");
    EXPECT_EQ(editor.press(B).kind, Request::Kind::none);
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);  // not the menu
    EXPECT_TRUE(editor.scheme.menu_view(editor.model).lines.empty());
    EXPECT_TRUE(editor.model.modified());  // nothing saved, nothing lost
}

TEST(EditorSaveAs, ANewScoreSavesWithoutAsking) {
    auto editor = fresh_editor();
    editor.scheme.set_taken({{"alarm", Shipped}});
    editor.scheme.set_destination("tacton-1", true);
    to_menu_entry(editor, "save");
    EXPECT_EQ(editor.press(S).kind, Request::Kind::save);
    to_menu_entry(editor, "save as...");
    press(editor, {S});
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines[0], "tacton-[2]");
    press(editor, {B, B});  // cancelled
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

}  // namespace
}  // namespace vibscore
