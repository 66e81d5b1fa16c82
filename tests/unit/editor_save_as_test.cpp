// Save-as with the six buttons: a name typed with them (NameEntry), a free name proposed, and a
// question before a taken name (a shipped score) is replaced.
#include <gtest/gtest.h>

#include "client/editor/name_entry.hpp"
#include "client/editor/planner/press_planner.hpp"
#include "score/score_xml.hpp"
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
    entry.start({"ringtone-2"});
    EXPECT_EQ(entry.lines(), std::vector<std::string>{"[ringtone-2]"});
    EXPECT_EQ(entry.hint(), "\u2191etaoi\u2193nshrd\u2192lcumw\u2190fgyp- S:save B:more");
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::done);
    EXPECT_EQ(entry.name(), "ringtone-2");
}

TEST(EditorNameEntry, TypingReplacesTheProposalTwoPressesACharacterThreeForTheRareOnes) {
    NameEntry entry;
    entry.start({"tacton-2"});
    press_all(entry, {U});  // the group e t a o i
    EXPECT_EQ(entry.hint(), "\u2191e \u2193t \u2192a \u2190o S:i B:back");
    press_all(entry, {U});  // e: the proposal goes
    EXPECT_EQ(entry.lines(), std::vector<std::string>{"e|"});
    press_all(entry, {B});  // the rest of the characters
    EXPECT_EQ(entry.hint(), "\u2191bvkjx\u2193qz._0\u219212345\u21906789 S:del B:cancel");
    press_all(entry, {U, S});     // x
    press_all(entry, {L, L});     // p
    press_all(entry, {B, R, D});  // 2
    EXPECT_EQ(entry.name(), "exp2");
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::done);
}

TEST(EditorNameEntry, BackDeletesTheLastCharacterAndBackBackCancels) {
    NameEntry entry;
    entry.start({"ringtone-2"});
    press_all(entry, {B, S});  // the proposal's last character goes: typing on from it
    EXPECT_FALSE(entry.untouched());
    EXPECT_EQ(entry.lines(), std::vector<std::string>{"ringtone-|"});
    press_all(entry, {B, R, R});  // 3
    EXPECT_EQ(entry.name(), "ringtone-3");
    press_all(entry, {U, B});  // a group opened and turned back from: nothing typed
    EXPECT_EQ(entry.name(), "ringtone-3");
    EXPECT_EQ(entry.level(), NameEntry::Level::letters);
    // The group of four has nothing on Select: still choosing.
    press_all(entry, {B, L, S});
    EXPECT_EQ(entry.level(), NameEntry::Level::more_group);
    press_all(entry, {B});
    EXPECT_EQ(press_all(entry, {B, B}), NameEntry::Outcome::cancelled);
}

TEST(EditorNameEntry, ANameThatIsNotARegistryNameIsNotSavedAndSaysWhy) {
    NameEntry entry;
    entry.start({"tacton-2"});
    press_all(entry, {L, S});  // '-' first
    EXPECT_EQ(entry.name(), "-");
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::typing);
    EXPECT_EQ(entry.problem(), "a name starts with a letter or digit");
    EXPECT_EQ(entry.lines(),
              (std::vector<std::string>{"-|", "a name starts with a letter or digit"}));
    press_all(entry, {B, S});  // deleted: nothing left
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::typing);
    EXPECT_EQ(entry.problem(), "a name needs a character");
    press_all(entry, {B, S});  // deleting nothing leaves nothing
    EXPECT_EQ(entry.name(), "");
}

TEST(EditorNameEntry, NamesStopAt64Characters) {
    NameEntry entry;
    entry.start({std::string(62, 'e')});
    press_all(entry, {B, S, U, U, U, U});  // 61, then 62 and 63
    ASSERT_EQ(entry.name().size(), 63u);
    press_all(entry, {U, U});  // the 64th: the last allowed
    EXPECT_EQ(entry.name().size(), 64u);
    EXPECT_TRUE(entry.problem().empty());
    press_all(entry, {U, U});  // the 65th: refused, and said so
    EXPECT_EQ(entry.name().size(), 64u);
    EXPECT_EQ(entry.problem(), "a name has at most 64 characters");
    EXPECT_EQ(entry.lines().back(), "a name has at most 64 characters");
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::done);  // what is there is a name
    EXPECT_FALSE(editor::is_registry_name(std::string(65, 'a')));
    EXPECT_FALSE(editor::is_registry_name("A"));
    EXPECT_FALSE(editor::is_registry_name("-a"));
}

TEST(EditorNameEntry, ProposalsFirstTheEventTheTitleAndAFreeName) {
    EXPECT_EQ(editor::name_proposals("tacton-1", "Experiment 2", "phone-incoming-call",
                                     {"tacton-1", "phone-incoming-call"}),
              (std::vector<std::string>{"phone-incoming-call-2", "experiment-2", "tacton-2"}));
    // A title that is the name (or taken) is not proposed twice.
    EXPECT_EQ(editor::name_proposals("ringtone", "ringtone", "", {"ringtone"}),
              (std::vector<std::string>{"ringtone-2"}));
    EXPECT_EQ(editor::name_from_title("  Ode to Joy (Beethoven)!"), "ode-to-joy-beethoven");
    EXPECT_EQ(editor::name_from_title("--"), "");
    EXPECT_EQ(editor::name_from_title(std::string(70, 'x')).size(), 64u);

    NameEntry entry;
    entry.start({"phone-incoming-call-2", "experiment-2", "tacton-2"});
    EXPECT_EQ(entry.level(), NameEntry::Level::proposals);
    EXPECT_EQ(entry.hint(), "\u2191\u2193choose S:save \u2192new \u2190edit B:cancel");
    EXPECT_EQ(entry.name(), "phone-incoming-call-2");
    press_all(entry, {D});
    EXPECT_EQ(entry.highlighted(), 1);
    EXPECT_EQ(entry.press(S), NameEntry::Outcome::done);
    EXPECT_EQ(entry.name(), "experiment-2");
    entry.start({"a-2", "b-2"});
    press_all(entry, {U, L, U, U});  // b-2 typed on: b-2e
    EXPECT_EQ(entry.name(), "b-2e");
    press_all(entry, {B, B});  // back to the proposals
    EXPECT_EQ(entry.level(), NameEntry::Level::proposals);
    press_all(entry, {R, D, D});  // a new name: s
    EXPECT_EQ(entry.name(), "s");
}

// The names of issue 26's tasks, from what save-as proposes there, within 15 presses each
// (38, 56 and 47 with the old one-character-at-a-time entry).
TEST(EditorNameEntry, TheTasksNamesTakeAtMost15Presses) {
    for (const auto& [proposal, name] : std::vector<std::pair<std::string, std::string>>{
             {"tacton-2", "exp2"}, {"tacton-2", "confirm"}, {"ringtone-2", "my-ring"}}) {
        NameEntry entry;
        entry.start({proposal});
        const auto plan = editor::plan_name(entry, name);
        ASSERT_TRUE(plan.reached) << name;
        EXPECT_LE(plan.presses.size(), 15u) << name;
        for (const auto button : plan.presses) {
            entry.press(button);
        }
        EXPECT_EQ(entry.name(), name);
    }
}

constexpr auto Shipped = editor::TakenName::What::shipped;
constexpr auto Stored = editor::TakenName::What::stored;

// An editor on the shipped "ringtone", as `vibscore edit ringtone` opens it.
editor::Editor opened_ringtone() {
    auto editor = fresh_editor();
    editor.model.set_title("ringtone");
    editor.model.mark_saved();
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
    EXPECT_EQ(view.lines, std::vector<std::string>{"[ringtone-2]"});
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save_as, "ringtone-2"}));
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorSaveAs, ATypedNameIsSavedUnder) {
    auto editor = opened_ringtone();
    to_menu_entry(editor, "save as...");
    press(editor, {S, B, S, B, R});  // ringtone-, the digits 1 to 5
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u21911 \u21932 \u21923 \u21904 S:5 B:back");
    press(editor, {L});  // ringtone-4
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines, std::vector<std::string>{"ringtone-4|"});
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save_as, "ringtone-4"}));
}

TEST(EditorSaveAs, AKeyboardTypesTheNameInsteadOfRunningTheLettersActions) {
    auto editor = opened_ringtone();
    to_menu_entry(editor, "save as...");
    press(editor, {S});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::name_entry);
    const std::string before = write_score(editor.model.score());
    for (const char c : std::string("My-Ring.2")) {
        EXPECT_EQ(editor.key(c), Request{});
        ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::name_entry) << c;
    }
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines, std::vector<std::string>{"my-ring.2|"});
    // The last character a name takes and the first it does not: neither runs an action.
    EXPECT_EQ(editor.key(' '), Request{});
    EXPECT_EQ(editor.key('!'), Request{});
    EXPECT_EQ(editor.model.message(), "names take a-z 0-9 . _ -; Enter saves");
    EXPECT_EQ(editor.key('_'), Request{});
    EXPECT_EQ(write_score(editor.model.score()), before);
    EXPECT_EQ(editor.key('\n'), (Request{Request::Kind::save_as, "my-ring.2_"}));
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorSaveAs, OutsideANameTheSameKeyRunsItsAction) {
    auto editor = opened_ringtone();
    editor.key('t');
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::tapping);
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
    press(editor, {S, B, S, B, R, R});  // ringtone-3, stored before
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
    editor.model.set_title("tacton-1");  // as `vibscore edit` titles a new score
    editor.scheme.set_taken({{"alarm", Shipped}});
    editor.scheme.set_destination("tacton-1", true);
    to_menu_entry(editor, "save");
    EXPECT_EQ(editor.press(S).kind, Request::Kind::save);
    to_menu_entry(editor, "save as...");
    press(editor, {S});
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines[0], "[tacton-2]");
    press(editor, {B, B});  // cancelled
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

}  // namespace
}  // namespace vibscore
