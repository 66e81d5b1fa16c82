// The six-button scheme: button presses in, score out.
#include <gtest/gtest.h>

#include "client/editor/press_planner.hpp"
#include "tests/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Button;
using editor::ButtonScheme;
using editor::Position;
using editor::Request;
using testing::bars;
using testing::fresh_editor;
using testing::press;

constexpr auto U = Button::up;
constexpr auto D = Button::down;
constexpr auto L = Button::left;
constexpr auto R = Button::right;
constexpr auto S = Button::select;
constexpr auto B = Button::back;

std::string highlighted(const editor::Editor& editor) {
    const auto menu = editor.scheme.menu_view(editor.model);
    return menu.lines.empty() ? "" : menu.lines[static_cast<std::size_t>(menu.highlighted)];
}

TEST(EditorButtons, SelectOnAnEmptyPositionEntersTheProposedNote) {
    auto editor = fresh_editor();  // string 3, number 5, quarter
    press(editor, {S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::entry);
    EXPECT_EQ(editor.model.score().bars, bars("<Bar clef=\"lra\"><Note length=\"quarter\" "
                                              "number=\"5\" string=\"3\"/></Bar>"));
    press(editor, {U, U, L, S});  // number 7, an 8th; done
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    EXPECT_EQ(editor.model.cursor(), (Position{0, 1}));
    press(editor, {D, S, S});  // the next note: the same number and length, a string lower
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"3\"/>"
                   "<Note length=\"8th\" number=\"7\" string=\"2\"/></Bar>"));
}

TEST(EditorButtons, StringsAndNumbersWrapAround) {
    auto editor = fresh_editor();
    press(editor, {U, U, U, U});  // 3 -> 6 -> 1
    EXPECT_EQ(editor.model.string(), 1);
    press(editor, {D});
    EXPECT_EQ(editor.model.string(), 6);
    press(editor, {S, U, U, U, U, U});  // 5 -> 9 -> 1
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[0]).number, 1);
}

TEST(EditorButtons, BackChangesTheShapeNoteRestDottedRestDottedNote) {
    auto editor = fresh_editor();
    press(editor, {S, B});
    EXPECT_EQ(editor.model.score().bars[0].symbols[0], (Symbol{Rest{Length::quarter}}));
    press(editor, {B});
    EXPECT_EQ(editor.model.score().bars[0].symbols[0], (Symbol{Rest{Length::quarter_dot}}));
    press(editor, {B});
    EXPECT_EQ(editor.model.score().bars[0].symbols[0], (Symbol{Note{Length::quarter_dot, 5, 3}}));
    press(editor, {B});
    EXPECT_EQ(editor.model.score().bars[0].symbols[0], (Symbol{Note{Length::quarter, 5, 3}}));
    // A whole note has no dotted form: note <-> rest only.
    press(editor, {R, R, B, B});
    EXPECT_EQ(editor.model.score().bars[0].symbols[0], (Symbol{Note{Length::whole, 5, 3}}));
}

TEST(EditorButtons, TheNewNoteContinuesTheHairpinAndTieBeforeIt) {
    auto editor = fresh_editor();
    press(editor, {S, S, B, S});  // a note, then "decrescendo" from the menu
    press(editor, {S, S});
    auto second = std::get<Note>(editor.model.score().bars[0].symbols[1]);
    EXPECT_EQ(second.dynamics, Dynamics::decrescendo);
    press(editor, {S, B, S});  // a rest breaks the hairpin
    press(editor, {S, S});
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[3]).dynamics, Dynamics::none);
}

TEST(EditorButtons, SelectOnANoteChangesItAndMovesItToTheActiveString) {
    auto editor = fresh_editor();
    press(editor, {S, S, L, U, U, S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::entry);
    press(editor, {D, S});
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"4\" string=\"5\"/>"
                   "</Bar>"));
    EXPECT_EQ(editor.model.cursor(), (Position{0, 1}));
}

TEST(EditorButtons, AnEntryIsOneUndoStep) {
    auto editor = fresh_editor();
    press(editor, {S, U, U, L, B, S});
    ASSERT_EQ(editor.model.score().bars[0].symbols.size(), 1u);
    editor.model.undo();
    EXPECT_TRUE(editor.model.score().bars[0].symbols.empty());
    editor.model.redo();
    EXPECT_EQ(editor.model.score().bars[0].symbols[0], (Symbol{Rest{Length::eighth}}));
}

TEST(EditorButtons, TheMenuActsOnTheSymbolJustEnteredAndRemembersTheChoice) {
    auto editor = fresh_editor();
    press(editor, {S, S, B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::menu);
    EXPECT_EQ(highlighted(editor), "decrescendo  >");
    press(editor, {D, S});
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[0]).dynamics,
              Dynamics::crescendo);
    press(editor, {B});
    EXPECT_EQ(highlighted(editor), "crescendo  <");  // the last choice
    press(editor, {B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorButtons, LeftAndRightJumpBetweenMenuGroupsAndTheListWraps) {
    auto editor = fresh_editor();
    press(editor, {B, R});
    EXPECT_EQ(highlighted(editor), "legato with previous");
    press(editor, {R});
    EXPECT_EQ(highlighted(editor), "dotted / not dotted");
    press(editor, {L});
    EXPECT_EQ(highlighted(editor), "legato with previous");
    press(editor, {L, U});
    EXPECT_EQ(highlighted(editor), "quit");
}

TEST(EditorButtons, TiesFromTheMenu) {
    auto editor = fresh_editor();
    press(editor, {S, S, U, S, S, B, R, S});  // legato with previous
    press(editor, {S, S});                    // continues the tie
    press(editor, {B, D, S});                 // the menu reopens on legato: portamento is next
    const auto& symbols = editor.model.score().bars[0].symbols;
    EXPECT_EQ(std::get<Note>(symbols[0]).legato, 1);
    EXPECT_EQ(std::get<Note>(symbols[1]).legato, 1);
    EXPECT_EQ(std::get<Note>(symbols[2]).legato, 1);
    EXPECT_EQ(std::get<Note>(symbols[2]).portamento, 1);
    EXPECT_EQ(std::get<Note>(symbols[1]).portamento, 1);
}

std::vector<Button> to_menu_entry(editor::Editor& editor, const std::string& label) {
    std::vector<Button> presses{B};
    editor.press(B);
    for (int i = 0; i < 40 && highlighted(editor) != label; ++i) {
        editor.press(D);
        presses.push_back(D);
    }
    return presses;
}

TEST(EditorButtons, ABlockMarkedWithButtonsIsCopiedPastedAndRaised) {
    auto editor = fresh_editor();
    press(editor, {S, S, S, U, S});  // two notes: 5 and 6
    press(editor, {L, L});
    to_menu_entry(editor, "mark block");
    press(editor, {S, R, R});
    ASSERT_TRUE(editor.model.block());
    to_menu_entry(editor, "copy");
    press(editor, {S});
    to_menu_entry(editor, "unmark block");
    press(editor, {S, R});  // past the end: a new bar
    to_menu_entry(editor, "paste");
    press(editor, {S});
    press(editor, {L, L});
    to_menu_entry(editor, "mark block");
    press(editor, {S, R, R});
    to_menu_entry(editor, "numbers +1");
    press(editor, {S});
    to_menu_entry(editor, "strings up");
    press(editor, {S});
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"5\" string=\"3\"/>"
                   "<Note length=\"quarter\" number=\"6\" string=\"3\"/></Bar>"
                   "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"6\" string=\"4\"/>"
                   "<Note length=\"quarter\" number=\"7\" string=\"4\"/></Bar>"));
}

TEST(EditorButtons, TheBarClefFromTheMenu) {
    auto editor = fresh_editor();
    press(editor, {S, S, R});  // bar 2
    to_menu_entry(editor, "bar clef...");
    press(editor, {S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_menu);
    EXPECT_EQ(highlighted(editor), "lra  lra-phone.clef.xml");
    press(editor, {D});
    EXPECT_EQ(highlighted(editor), "erm  erm-phone.clef.xml");
    press(editor, {B});  // back to the menu: nothing chosen
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::menu);
    EXPECT_EQ(editor.model.score().bars[1].clef, "lra");
    press(editor, {S, D, S});
    EXPECT_EQ(editor.model.score().bars[1].clef, "erm");
    EXPECT_EQ(editor.model.score().bars[0].clef, "lra");
}

TEST(EditorButtons, UndoRedoDeleteAndSplitFromTheMenu) {
    auto editor = fresh_editor();
    press(editor, {S, S, S, S, L});
    to_menu_entry(editor, "delete");
    press(editor, {S});
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 1u);
    to_menu_entry(editor, "undo");
    press(editor, {S});
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 2u);
    to_menu_entry(editor, "redo");
    press(editor, {S});
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 1u);
    to_menu_entry(editor, "undo");
    press(editor, {S});
    to_menu_entry(editor, "new bar here");
    press(editor, {S});
    EXPECT_EQ(editor.model.score().bars.size(), 2u);
}

TEST(EditorButtons, SessionEntriesAreRequests) {
    auto editor = fresh_editor();
    press(editor, {S, S, R});
    to_menu_entry(editor, "play from this bar");
    const auto play = editor.press(S);
    EXPECT_EQ(play.kind, Request::Kind::play);
    EXPECT_EQ(play.bar, 1u);
    editor.scheme.set_playing(true);
    EXPECT_EQ(editor.press(U).kind, Request::Kind::stop);
    editor.scheme.set_playing(false);
    to_menu_entry(editor, "save");
    EXPECT_EQ(editor.press(S).kind, Request::Kind::save);
    editor.scheme.set_openable({"alarm", "ringtone"});
    to_menu_entry(editor, "open...");
    press(editor, {S, D});
    const auto open = editor.press(S);
    EXPECT_EQ(open, (Request{Request::Kind::open, "ringtone"}));
    to_menu_entry(editor, "quit");
    press(editor, {S});  // unsaved changes: save and quit / quit without saving / cancel
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::quit_menu);
    EXPECT_EQ(editor.press(S).kind, Request::Kind::save_and_quit);
}

TEST(PressPlanner, FindsAndVerifiesTheButtonsForFigure23) {
    const auto target =
        read_score(
            "<VibScore><Title>t</Title><Clef id=\"lra\" href=\"lra-phone.clef.xml\"/>"
            "<Bar clef=\"lra\"><Note length=\"8th\" number=\"1\" string=\"2\" "
            "legato=\"1\"/><Note length=\"quarter\" number=\"2\" string=\"3\" "
            "legato=\"1\"/><Rest length=\"8th\"/><Note length=\"half\" "
            "number=\"2\" string=\"1\"/></Bar></VibScore>",
            "fig23.xml")
            .score;
    const auto start = fresh_editor();
    const auto plan = editor::plan_presses(start, target);
    ASSERT_TRUE(plan.reached);
    auto replay = start;
    for (const auto button : plan.presses) {
        replay.press(button);
    }
    EXPECT_EQ(replay.model.score().bars, target.bars);
    EXPECT_LE(plan.presses.size(), 30u);
}

TEST(PressPlanner, EnteredPrefixComparesTiesAsTheNeighboursTheyJoin) {
    const auto target =
        read_score(
            "<VibScore><Clef id=\"lra\" href=\"x\"/><Bar clef=\"lra\"><Note length=\"8th\" "
            "number=\"1\" string=\"2\" legato=\"7\"/><Note length=\"8th\" number=\"1\" "
            "string=\"2\" legato=\"7\"/></Bar></VibScore>",
            "t.xml")
            .score;
    auto score = target;
    EXPECT_EQ(editor::entered_prefix(score, target), 3);
    std::get<Note>(score.bars[0].symbols[0]).legato = 1;
    std::get<Note>(score.bars[0].symbols[1]).legato = 1;
    EXPECT_EQ(editor::entered_prefix(score, target), 3);
    std::get<Note>(score.bars[0].symbols[1]).legato = 0;
    EXPECT_EQ(editor::entered_prefix(score, target), -1);
    score.bars[0].symbols.pop_back();
    EXPECT_EQ(editor::entered_prefix(score, target), 2);
}

}  // namespace
}  // namespace vibscore
