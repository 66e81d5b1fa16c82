// The six-button scheme: button presses in, score out.
#include <gtest/gtest.h>

#include "client/editor/planner/press_planner.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Button;
using editor::ButtonScheme;
using editor::Position;
using editor::Request;
using testing::bars;
using testing::fresh_editor;
using testing::highlighted;
using testing::press;
using testing::to_menu_entry;

using namespace testing::buttons;

const Symbol& symbol(const editor::Editor& editor, std::size_t index, std::size_t bar = 0) {
    return editor.model.score().bars.at(bar).symbols.at(index);
}

// The notes and rests of every bar in order: entering runs on into a new bar as a bar fills.
std::vector<Symbol> entered(const editor::Editor& editor) {
    std::vector<Symbol> symbols;
    for (const auto& bar : editor.model.score().bars) {
        symbols.insert(symbols.end(), bar.symbols.begin(), bar.symbols.end());
    }
    return symbols;
}

Note nth_note(const editor::Editor& editor, std::size_t index) {
    return std::get<Note>(entered(editor).at(index));
}

using Step = editor::EntrySteps::Step;

TEST(EditorButtons, EachPressChoosesAndEnteringGoesOnToTheNextProposal) {
    auto editor = fresh_editor();  // string 3, number 5, quarter
    press(editor, {S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::entry);
    EXPECT_EQ(editor.model.score().bars, bars("<Bar clef=\"lra\"><Note length=\"quarter\" "
                                              "number=\"5\" string=\"3\"/></Bar>"));
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u2191s4 \u2193s2 \u2192s5 \u2190s1 S:ok B:more");
    press(editor, {U});  // string 4, on to its number
    EXPECT_EQ(editor.scheme.hint(editor.model),
              "\u2191"
              "6 \u2193"
              "4 \u2192"
              "7 \u2190"
              "3 S:ok B:1,2,8,9");  // Back's numbers named too: every number is on the screen
    press(editor, {U, D});          // number 6; one length shorter, and done
    EXPECT_EQ(symbol(editor, 0), (Symbol{Note{Length::eighth, 6, 4}}));
    // The next position's proposal is open at once: the same note again.
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::entry);
    EXPECT_EQ(editor.model.cursor(), (Position{0, 1}));
    EXPECT_EQ(symbol(editor, 1), (Symbol{Note{Length::eighth, 6, 4}}));
    press(editor, {S});     // kept as proposed
    press(editor, {B, B});  // leave: the open proposal goes
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note length=\"8th\" number=\"6\" string=\"4\"/>"
                   "<Note length=\"8th\" number=\"6\" string=\"4\"/></Bar>"));
    EXPECT_EQ(editor.model.cursor(), (Position{0, 2}));
}

TEST(EditorButtons, RightAndLeftChangeByTwoAndBackOffersTheRest) {
    auto editor = fresh_editor();
    press(editor, {S, R, L, R});  // string 5, number 3, two lengths longer: a whole note
    EXPECT_EQ(symbol(editor, 0), (Symbol{Note{Length::whole, 3, 5}}));
    press(editor, {B, U});  // the opposite string: 2
    press(editor, {B, R});  // number + 4: 7
    press(editor, {B, L});  // three lengths shorter: whole -> half -> quarter -> 8th
    EXPECT_EQ(entered(editor).at(1), (Symbol{Note{Length::eighth, 7, 2}}));
    // 3 then 7: the proposal steps on to 9 (the most there is). This string; number - 3.
    press(editor, {B, S, B, D});
    EXPECT_EQ(editor.scheme.hint(editor.model),
              "\u2191quarter \u2193"
              "16th \u2192half \u2190"
              "32nd S:ok B:more");
    press(editor, {S});
    EXPECT_EQ(entered(editor).at(2), (Symbol{Note{Length::eighth, 6, 2}}));
}

TEST(EditorButtons, StringsAndNumbersWrapAround) {
    auto editor = fresh_editor();
    press(editor, {S, R, R});  // string 3 + 2 = 5, number 5 + 2 = 7
    press(editor, {S});
    press(editor, {R, R, S});  // string 5 + 2 = 1, number 7 + 2 = 9
    EXPECT_EQ(symbol(editor, 1), (Symbol{Note{Length::quarter, 9, 1}}));
    press(editor, {D, U, S});  // string 6, number 9 + 1 = 1
    EXPECT_EQ(symbol(editor, 2), (Symbol{Note{Length::quarter, 1, 6}}));
}

TEST(EditorButtons, RestsComeFromTheStringStepsOtherChoicesAndKeepTheirOwnLength) {
    auto editor = fresh_editor();
    press(editor, {S, S});           // a quarter note
    press(editor, {B, D});           // a rest as long, done
    press(editor, {B, L, D});        // a rest, one length shorter: an 8th
    press(editor, {B, S, S});        // a note: its length is still the quarter
    press(editor, {B, D});           // a rest: the 8th, the last rest's length
    press(editor, {B, L, B, U, U});  // a rest, dotted, one longer: a dotted quarter
    EXPECT_EQ(entered(editor),
              (std::vector<Symbol>{Note{Length::quarter, 5, 3}, Rest{Length::quarter},
                                   Rest{Length::eighth}, Note{Length::quarter, 5, 3},
                                   Rest{Length::eighth}, Rest{Length::quarter_dot},
                                   Note{Length::quarter, 5, 3}}));
}

TEST(EditorButtons, TheProposalContinuesTheHairpinTiesAndTheStepInNumber) {
    auto editor = fresh_editor();
    press(editor, {S, B, S, B, S, B, D, L, S});  // this string, this number; marks: decrescendo
    EXPECT_EQ(nth_note(editor, 0).dynamics, Dynamics::decrescendo);
    press(editor, {B, S, D, S});  // the same string, number 4
    EXPECT_EQ(nth_note(editor, 1).dynamics, Dynamics::decrescendo);
    // 5 then 4: the fade goes on, 3 is proposed.
    EXPECT_EQ(nth_note(editor, 2).number, 3);
    press(editor, {S, B, D});  // a rest parts the fade; each note's own hairpin carries over
    EXPECT_EQ(nth_note(editor, 4).dynamics, Dynamics::decrescendo);
    EXPECT_EQ(nth_note(editor, 4).number, 3);
    press(editor, {S, U, B, S, B, D, U, S});  // string 4, legato with the note before
    EXPECT_NE(nth_note(editor, 5).legato, 0);
    EXPECT_EQ(nth_note(editor, 4).legato, nth_note(editor, 5).legato);
    EXPECT_EQ(nth_note(editor, 6).legato, nth_note(editor, 5).legato);
    press(editor, {U, B, S, B, D, U, S});  // legato again takes it off
    EXPECT_EQ(nth_note(editor, 6).legato, 0);
}

TEST(EditorButtons, TheProposalRepeatsWhatFollowedBeforeAndTiesAsBefore) {
    auto editor = fresh_editor();       // string 3, number 5, quarter
    press(editor, {S, D, B, S, D});     // string 2, number 5, an 8th
    press(editor, {U, U, B, D, U, S});  // string 3, number 6, legato with the note before
    press(editor, {B, D});              // a rest as long
    press(editor, {D, D, S});           // string 2, number 5: the first note again
    // After the first note came the second, tied to it: so it comes again, tied.
    const auto proposed = std::get<Note>(entered(editor).at(4));
    EXPECT_EQ(proposed.string, 3);
    EXPECT_EQ(proposed.number, 6);
    EXPECT_EQ(proposed.length, Length::eighth);
    press(editor, {S});  // kept as proposed
    EXPECT_NE(nth_note(editor, 3).legato, 0);
    EXPECT_EQ(nth_note(editor, 3).legato, nth_note(editor, 4).legato);
    EXPECT_NE(nth_note(editor, 3).legato, nth_note(editor, 0).legato);  // a tie of its own
    // And after it came the 8th rest: one press.
    EXPECT_EQ(entered(editor).at(5), (Symbol{Rest{Length::eighth}}));
    press(editor, {S, B, B});
    EXPECT_EQ(entered(editor).size(), 6u);
}

TEST(EditorButtons, SelectOnANoteChangesItAndGoesOnThroughTheNotesAfterIt) {
    auto editor = fresh_editor();
    press(editor, {S, S, B, S, U, S, B, B});  // two notes: 5 and 6
    press(editor, {L, L, S});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::entry);
    press(editor, {U, S});  // the first moves to string 4, entered as shown
    EXPECT_EQ(editor.model.cursor(), (Position{0, 1}));
    press(editor, {S, B, B});  // the second is kept; leaving drops only the proposal after it
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"5\" string=\"4\"/>"
                   "<Note length=\"quarter\" number=\"6\" string=\"3\"/></Bar>"));
}

TEST(EditorButtons, SelectEntersTheSymbolAsShownInEveryStep) {
    // S:ok entered the whole note in the string step but only kept the number in the number
    // step: one rule now, and Back, Select keeps a step's part and goes on.
    auto editor = fresh_editor();  // string 3, number 5, quarter
    press(editor, {S, U, S});      // string 4; Select in the number step: entered
    EXPECT_EQ(entered(editor).at(0), (Symbol{Note{Length::quarter, 5, 4}}));
    EXPECT_EQ(editor.model.cursor(), (Position{0, 1}));
    EXPECT_EQ(editor.scheme.entry_step(), Step::string);
    press(editor, {B, S, B});  // this string, then the number's other choices
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u21918 \u21932 \u21929 \u21901 S:len B:back");
    press(editor, {S});  // this number: on to the length
    EXPECT_EQ(editor.scheme.entry_step(), Step::length);
    press(editor, {S});  // and Select enters it there too
    EXPECT_EQ(entered(editor).at(1), (Symbol{Note{Length::quarter, 5, 4}}));
}

TEST(EditorButtons, ChangingSaysSoAndRunsOnOnlyThroughTheScoresOwnSymbols) {
    // A newcomer changed a note and did not see that the next symbol was open for changing.
    auto editor = fresh_editor();
    testing::type(editor, "56");
    press(editor, {L, L, S});
    EXPECT_TRUE(editor.model.changing());
    press(editor, {U, S});  // changed, entered: the 6 is open now, for changing too
    EXPECT_EQ(editor.model.cursor(), (Position{0, 1}));
    EXPECT_TRUE(editor.model.changing());
    press(editor, {S});  // kept: the end of the bar, a proposal
    EXPECT_FALSE(editor.model.changing());
    press(editor, {B});
    EXPECT_EQ(editor.scheme.hint(editor.model),
              "\u2191s6 S:s3 \u2193rest \u2190rest.. \u2192bar B:leave");
    press(editor, {B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    EXPECT_FALSE(editor.model.changing());
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 2u);
}

TEST(EditorButtons, EachEnteredSymbolIsOneUndoStep) {
    auto editor = fresh_editor();
    press(editor, {S, U, U, D, B, L, D, B, B});
    ASSERT_EQ(editor.model.score().bars[0].symbols.size(), 2u);
    editor.model.undo();
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 1u);
    editor.model.undo();
    EXPECT_TRUE(editor.model.score().bars[0].symbols.empty());
    editor.model.redo();
    editor.model.redo();
    EXPECT_EQ(symbol(editor, 1), (Symbol{Rest{Length::sixteenth}}));
}

TEST(EditorButtons, ANewBarWhileEnteringAsksForItsClef) {
    auto editor = fresh_editor();  // two clefs to choose from
    press(editor, {S, S, B, R});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_menu);
    EXPECT_EQ(highlighted(editor), "lra  lra-phone.clef.xml");
    press(editor, {D, S});  // the ERM clef; entering goes on in the new bar
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::entry);
    EXPECT_EQ(editor.model.cursor(), (Position{1, 0}));
    press(editor, {S, B, R, B});  // another bar: Back keeps the clef it has
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::entry);
    press(editor, {B, B});
    const auto& score = editor.model.score();
    ASSERT_EQ(score.bars.size(), 3u);
    EXPECT_EQ(score.bars[0].clef, "lra");
    EXPECT_EQ(score.bars[1].clef, "erm");
    EXPECT_EQ(score.bars[2].clef, "erm");
    EXPECT_EQ(score.bars[1].symbols.size(), 1u);
    EXPECT_TRUE(score.bars[2].symbols.empty());
}

TEST(EditorButtons, EnteringRunsOnIntoANewBarWhenTheBarIsFull) {
    auto editor = fresh_editor();    // quarters
    press(editor, {S, S, S, S, S});  // four beats: the bar is full
    EXPECT_EQ(editor.model.cursor(), (Position{1, 0}));
    EXPECT_EQ(editor.model.score().bars.at(1).clef, "lra");
    press(editor, {S, B, B});  // one note in the new bar, then leave
    ASSERT_EQ(editor.model.score().bars.size(), 2u);
    EXPECT_EQ(editor.model.score().bars[1].symbols.size(), 1u);
}

TEST(EditorButtons, ChangingNotesRunsOnFromAFullBarIntoTheNextBarsNotes) {
    auto editor = fresh_editor();
    press(editor, {S, S, S, S, S, S, B, B});  // a full bar and one note in the next
    ASSERT_EQ(editor.model.score().bars.size(), 2u);
    press(editor, {L, L, L, L, L, L});  // back to the first note
    EXPECT_EQ(editor.model.cursor(), (Position{0, 0}));
    press(editor, {S, U, S, S, S, S});  // change the first note; keep the other three
    // On from the end of the full bar: the note of the second bar, not a fifth beat.
    EXPECT_EQ(editor.model.cursor(), (Position{1, 0}));
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 4u);
    press(editor, {B, B});
    EXPECT_EQ(nth_note(editor, 0).string, 4);
    EXPECT_EQ(entered(editor).size(), 5u);
}

TEST(EditorButtons, LeavingAtTheStartOfARunOnBarTakesTheBarBack) {
    auto editor = fresh_editor();
    press(editor, {S, S, S, S, S, B, B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    ASSERT_EQ(editor.model.score().bars.size(), 1u);
    EXPECT_EQ(editor.model.cursor(), (Position{0, 4}));
    // Select there goes on in the full bar: a fifth beat is the user's to choose.
    press(editor, {S, S, B, B});
    ASSERT_EQ(editor.model.score().bars.size(), 1u);
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 5u);
}

TEST(EditorButtons, ANewBarAtTheStartOfARunOnBarStillAsksForItsClef) {
    auto editor = fresh_editor();
    press(editor, {S, S, S, S, S, B, R});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_menu);
    press(editor, {D, S});
    ASSERT_EQ(editor.model.score().bars.size(), 2u);
    EXPECT_EQ(editor.model.score().bars[1].clef, "erm");
    EXPECT_EQ(editor.model.cursor(), (Position{1, 0}));
}

TEST(EditorButtons, AKeyboardCommandDropsTheOpenProposal) {
    auto editor = fresh_editor();
    press(editor, {S, S});
    editor.scheme.command({editor::Action::split_bar}, editor.model);
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 1u);
    EXPECT_EQ(editor.model.score().bars.size(), 2u);
}

TEST(EditorButtons, TheMenuActsOnTheSymbolJustEnteredAndRemembersTheChoice) {
    auto editor = fresh_editor();
    press(editor, {S, S, B, B, B, S});  // a note, leave; the other choices, the menu
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::menu);
    EXPECT_EQ(highlighted(editor), "tap a rhythm");  // the first line, a newcomer's first look
    press(editor, {D});
    EXPECT_EQ(highlighted(editor), "decrescendo  >");
    press(editor, {D, S});
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[0]).dynamics,
              Dynamics::crescendo);
    press(editor, {B, S});
    EXPECT_EQ(highlighted(editor), "crescendo  <");  // the last choice
    press(editor, {B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorButtons, LeftAndRightJumpBetweenMenuGroupsAndTheListWraps) {
    auto editor = fresh_editor();
    press(editor, {B, S, R, R});
    EXPECT_EQ(highlighted(editor), "legato with previous");
    press(editor, {R});
    EXPECT_EQ(highlighted(editor), "dotted / not dotted");
    press(editor, {L});
    EXPECT_EQ(highlighted(editor), "legato with previous");
    press(editor, {L, L, U});
    EXPECT_EQ(highlighted(editor), "quit");
}

TEST(EditorButtons, TiesFromTheMenu) {
    auto editor = fresh_editor();
    press(editor, {S, S, B, S, U, S, B, B});  // two notes
    press(editor, {B, S, R, R, S});           // legato with previous
    press(editor, {S, S, B, B});              // the proposal continues the tie
    press(editor, {B, S, D, S});              // the menu reopens on legato: portamento is next
    const auto& symbols = editor.model.score().bars[0].symbols;
    EXPECT_EQ(std::get<Note>(symbols[0]).legato, 1);
    EXPECT_EQ(std::get<Note>(symbols[1]).legato, 1);
    EXPECT_EQ(std::get<Note>(symbols[2]).legato, 1);
    EXPECT_EQ(std::get<Note>(symbols[2]).portamento, 1);
    EXPECT_EQ(std::get<Note>(symbols[1]).portamento, 1);
}

TEST(EditorButtons, LeftFromInsideAGroupGoesToThePreviousGroupAndTheTitleNamesIt) {
    // A newcomer pressed Left three times from "bar clef..." and landed on a hairpin.
    auto editor = fresh_editor();
    to_menu_entry(editor, "bar clef...");
    EXPECT_EQ(editor.scheme.menu_view(editor.model).title, "menu: symbol, bar 4/8");
    press(editor, {L});
    EXPECT_EQ(highlighted(editor), "legato with previous");
    EXPECT_EQ(editor.scheme.menu_view(editor.model).title, "menu: ties 3/8");
    press(editor, {L, L, L});
    EXPECT_EQ(highlighted(editor), "save");
    press(editor, {R});
    EXPECT_EQ(highlighted(editor), "tap a rhythm");
    EXPECT_EQ(editor.scheme.menu_view(editor.model).title, "menu: enter 1/8");
}

TEST(EditorButtons, ABlockMarkedWithButtonsIsCopiedPastedAndRaised) {
    auto editor = fresh_editor();
    press(editor, {S, S, B, S, U, S, B, B});  // two notes: 5 and 6
    press(editor, {L, L});
    to_menu_entry(editor, "mark block");
    press(editor, {S, R, R});
    ASSERT_TRUE(editor.model.block());
    to_menu_entry(editor, "copy");
    press(editor, {S});
    EXPECT_FALSE(editor.model.block());  // copied: the block is let go
    press(editor, {R});                  // past the end: a new bar
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

TEST(EditorButtons, ABarMarkedFromItsFirstToItsLastSymbolIsCopiedWhole) {
    // A newcomer marked a bar from its first note to its last rest: the rest was lost.
    auto editor = fresh_editor();
    testing::type(editor, "10");  // a note, then a rest
    ASSERT_EQ(editor.model.score().bars[0].symbols.size(), 2u);
    press(editor, {L, L});
    to_menu_entry(editor, "mark block");
    press(editor, {S, R});  // on the rest
    ASSERT_TRUE(std::holds_alternative<Rest>(symbol(editor, 1)));
    to_menu_entry(editor, "copy");
    press(editor, {S, R, R});  // the block let go, Right moves on and past the end: a new bar
    ASSERT_EQ(editor.model.score().bars.size(), 2u);
    to_menu_entry(editor, "paste");
    press(editor, {S});
    EXPECT_EQ(editor.model.score().bars[1].symbols, editor.model.score().bars[0].symbols);
}

TEST(EditorButtons, TheClipboardStaysWhenAnotherScoreIsOpened) {
    auto first = fresh_editor();
    testing::type(first, "10");  // a note, then a rest
    first.model.apply(editor::Command{editor::Action::mark_block});
    press(first, {L, L});
    first.model.copy();
    auto second = fresh_editor();  // what opening another score or a new one starts
    second.model.carry_over(first.model);
    ASSERT_TRUE(second.model.paste());
    EXPECT_EQ(second.model.score().bars[0].symbols, first.model.score().bars[0].symbols);
}

TEST(EditorButtons, TheBarClefFromTheMenu) {
    auto editor = fresh_editor();
    press(editor, {S, S, B, B, R});  // bar 2
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
    press(editor, {S, S, S, B, B, L});
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
    press(editor, {S, S, B, B, R});
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

TEST(EditorButtons, TheMenuGoesToTheFirstAndLastBarAndPlaysFromTheStart) {
    // A newcomer pressed Left 15 times to play from the start.
    auto editor = fresh_editor();
    press(editor, {S, S, S, S, S, S, S, S, S, S, B, B});  // nine quarters: three bars
    ASSERT_EQ(editor.model.score().bars.size(), 3u);
    to_menu_entry(editor, "to the first bar");
    EXPECT_EQ(editor.scheme.menu_view(editor.model).title, "menu: play, go to, undo 7/8");
    EXPECT_EQ(editor.press(S).kind, Request::Kind::none);
    EXPECT_EQ(editor.model.cursor(), (Position{0, 0}));
    to_menu_entry(editor, "to the last bar");
    press(editor, {S});
    EXPECT_EQ(editor.model.cursor(), (Position{2, 1}));
    // The menu reopens on the last choice: the same place again is Back, Select, Select.
    press(editor, {L, L});
    press(editor, {B, S, S});
    EXPECT_EQ(editor.model.cursor(), (Position{2, 1}));
    to_menu_entry(editor, "play from the start");
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::play, {}, 0}));
}

TEST(EditorButtons, BackFromBrowsingPlaysAndGoesToTheFirstOrLastBarInTwoPresses) {
    // A newcomer pressed Left 15 times to play from the start; each of these is Back and one
    // press from anywhere while browsing.
    auto editor = fresh_editor();
    press(editor, {S, S, S, S, S, S, S, S, S, S, B, B});  // nine quarters: three bars
    press(editor, {L, L, L, L, L});
    const Position middle = editor.model.cursor();
    ASSERT_EQ(middle.bar, 1u);
    EXPECT_EQ(editor.press(B).kind, Request::Kind::none);
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse_choices);
    EXPECT_EQ(editor.scheme.hint(editor.model),
              "\u2191play all \u2193play bar \u2190first \u2192last S:menu");
    EXPECT_EQ(editor.press(U), (Request{Request::Kind::play, {}, 0}));  // play from the start
    editor.scheme.set_playing(true);
    editor.scheme.set_playing(false);
    EXPECT_EQ(editor.model.cursor(), middle);
    press(editor, {B});
    EXPECT_EQ(editor.press(D), (Request{Request::Kind::play, {}, 1}));  // from the cursor's bar
    editor.scheme.set_playing(false);
    press(editor, {B, L});  // to the first bar
    EXPECT_EQ(editor.model.cursor(), (Position{0, 0}));
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    press(editor, {B, R});  // to the end of the last bar, where entering goes on
    EXPECT_EQ(editor.model.cursor(), (Position{2, 1}));
    press(editor, {B, B});  // Back turns back, changing nothing
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    EXPECT_EQ(editor.model.cursor(), (Position{2, 1}));
    press(editor, {B, S});  // Select: the menu
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::menu);
    EXPECT_EQ(editor.model.score().bars.size(), 3u);
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
    EXPECT_LE(plan.presses.size(), 20u);
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
