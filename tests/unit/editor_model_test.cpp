// The editor model driven by the keyboard of thesis Fig. 4.3: keys in, score out.
#include <gtest/gtest.h>

#include "client/editor/score_edits.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Position;
using testing::bars;
using testing::ctrl;
using testing::fresh_editor;
using testing::type;

TEST(EditorKeys, Figure23FirstMeasureFromTheKeyboard) {
    auto editor = fresh_editor();
    // String 2, Shift+7 (8th), note 1; Shift+5 (quarter), string 3, note 2, legato with the
    // note before; Shift+7, rest; strings down to 1, Shift+3 (half), note 2.
    type(editor, {KEY_DOWN});
    type(editor, "&1%");
    type(editor, {KEY_UP});
    type(editor, "2l&0");
    type(editor, {KEY_DOWN, KEY_DOWN});
    type(editor, "#2");
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note length=\"8th\" number=\"1\" string=\"2\" legato=\"1\"/>"
                   "<Note length=\"quarter\" number=\"2\" string=\"3\" legato=\"1\"/>"
                   "<Rest length=\"8th\"/><Note length=\"half\" number=\"2\" string=\"1\"/>"
                   "</Bar>"));
}

TEST(EditorKeys, NumbersInsertNotesOnTheActiveStringWithTheCurrentLength) {
    auto editor = fresh_editor();  // string 3, quarter
    type(editor, "5");
    type(editor, {KEY_UP, KEY_UP});
    type(editor, "(9");  // Shift+9 = 16th
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"5\" string=\"3\"/>"
                   "<Note length=\"16th\" number=\"9\" string=\"5\"/></Bar>"));
    EXPECT_EQ(editor.model.cursor(), (Position{0, 2}));
}

TEST(EditorKeys, ShiftedDigitsAreTheTenLengthsInTableOrder) {
    auto editor = fresh_editor();
    type(editor, "!0@0#0$0%0^0&0*0(0)0");
    std::vector<Length> lengths;
    for (const auto& symbol : editor.model.score().bars[0].symbols) {
        lengths.push_back(std::get<Rest>(symbol).length);
    }
    EXPECT_EQ(lengths, (std::vector<Length>{
                           Length::whole, Length::half_dot, Length::half, Length::quarter_dot,
                           Length::quarter, Length::eighth_dot, Length::eighth,
                           Length::sixteenth_dot, Length::sixteenth, Length::thirty_second}));
}

TEST(EditorKeys, InsertingBeforeASymbolKeepsTheCursorOnIt) {
    auto editor = fresh_editor();
    type(editor, "13");
    type(editor, {KEY_LEFT});
    type(editor, "2");
    const auto& symbols = editor.model.score().bars[0].symbols;
    ASSERT_EQ(symbols.size(), 3u);
    EXPECT_EQ(std::get<Note>(symbols[1]).number, 2);
    EXPECT_EQ(editor.model.cursor(), (Position{0, 2}));  // still on the 3
}

TEST(EditorKeys, GraveSplitsTheBarAndDeleteJoinsItAgain) {
    auto editor = fresh_editor();
    type(editor, "12");
    type(editor, {KEY_LEFT});
    type(editor, "`");
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note number=\"1\" string=\"3\" length=\"quarter\"/></Bar>"
                   "<Bar clef=\"lra\"><Note number=\"2\" string=\"3\" length=\"quarter\"/>"
                   "</Bar>"));
    EXPECT_EQ(editor.model.cursor(), (Position{1, 0}));
    type(editor, {KEY_LEFT, KEY_DC});  // on the end of bar 1: removes the bar line
    EXPECT_EQ(editor.model.score().bars.size(), 1u);
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 2u);
}

TEST(EditorKeys, RightPastTheEndStartsANewBar) {
    auto editor = fresh_editor();
    type(editor, {KEY_RIGHT});  // an empty bar gets no second bar
    EXPECT_EQ(editor.model.score().bars.size(), 1u);
    type(editor, "1");
    type(editor, {KEY_RIGHT});
    EXPECT_EQ(editor.model.score().bars.size(), 2u);
    EXPECT_EQ(editor.model.cursor(), (Position{1, 0}));
    type(editor, {KEY_DC});  // Delete on an empty last bar removes it
    EXPECT_EQ(editor.model.score().bars.size(), 1u);
    EXPECT_EQ(editor.model.cursor(), (Position{0, 1}));
}

TEST(EditorKeys, DeleteRemovesTheSymbolUnderTheCursor) {
    auto editor = fresh_editor();
    type(editor, "1230");
    type(editor, {KEY_LEFT, KEY_LEFT, KEY_LEFT, KEY_DC});
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note number=\"1\" string=\"3\" length=\"quarter\"/>"
                   "<Note number=\"3\" string=\"3\" length=\"quarter\"/><Rest length=\"quarter\"/>"
                   "</Bar>"));
}

TEST(EditorKeys, DynamicsActOnTheNoteJustEntered) {
    auto editor = fresh_editor();
    type(editor, "5c6d7d");
    const auto& symbols = editor.model.score().bars[0].symbols;
    EXPECT_EQ(std::get<Note>(symbols[0]).dynamics, Dynamics::crescendo);
    EXPECT_EQ(std::get<Note>(symbols[1]).dynamics, Dynamics::decrescendo);
    EXPECT_EQ(std::get<Note>(symbols[2]).dynamics, Dynamics::decrescendo);
    type(editor, "e");
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[2]).dynamics, Dynamics::none);
    type(editor, "0c");  // a rest has no dynamics
    EXPECT_EQ(editor.model.message(), "no note here");
}

TEST(EditorKeys, LegatoTiesToThePreviousNoteAndJoinsItsRun) {
    auto editor = fresh_editor();
    type(editor, "12l3l4");
    const auto serials = [&] {
        std::vector<std::int64_t> found;
        for (const auto& symbol : editor.model.score().bars[0].symbols) {
            found.push_back(std::get<Note>(symbol).legato);
        }
        return found;
    };
    EXPECT_EQ(serials(), (std::vector<std::int64_t>{1, 1, 1, 0}));
    type(editor, "5l");  // 4 and 5: a new run, a new serial
    EXPECT_EQ(serials(), (std::vector<std::int64_t>{1, 1, 1, 2, 2}));
    type(editor, {KEY_LEFT, KEY_LEFT});
    type(editor, "l");  // now 4 ties back to 3, and 5 comes along: one run of five
    EXPECT_EQ(serials(), (std::vector<std::int64_t>{1, 1, 1, 1, 1}));
}

TEST(EditorKeys, RemovingLegatoLeavesNoNoteTiedToNothing) {
    auto editor = fresh_editor();
    type(editor, "12l3l");
    type(editor, {KEY_LEFT, KEY_LEFT});  // on the 2: the middle of the run
    type(editor, "g");
    for (const auto& symbol : editor.model.score().bars[0].symbols) {
        EXPECT_EQ(std::get<Note>(symbol).legato, 0);
    }
    type(editor, "g");
    EXPECT_EQ(editor.model.message(), "no legato here");
}

TEST(EditorKeys, PortamentoAndItsRemoval) {
    auto editor = fresh_editor();
    type(editor, "19p");
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[1]).portamento, 1);
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[0]).portamento, 1);
    type(editor, "m");
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[0]).portamento, 0);
    type(editor, "0p");
    EXPECT_EQ(editor.model.message(), "no note here");
}

TEST(EditorKeys, LegatoNeedsANoteDirectlyBefore) {
    auto editor = fresh_editor();
    type(editor, "10");
    type(editor, "2l");
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[2]).legato, 0);
    EXPECT_NE(editor.model.message().find("no note just before"), std::string::npos);
}

TEST(EditorKeys, ShiftArrowsMarkABlockThatTheFunctionsActOn) {
    auto editor = fresh_editor();
    type(editor, "1234");
    type(editor, {KEY_LEFT, KEY_LEFT, KEY_LEFT, KEY_LEFT, KEY_SRIGHT, KEY_SRIGHT, KEY_SRIGHT});
    ASSERT_TRUE(editor.model.block());
    type(editor, "d+l");
    type(editor, {KEY_SR, KEY_SR});  // Shift+Up twice: strings up
    const auto& symbols = editor.model.score().bars[0].symbols;
    for (int i = 0; i < 3; ++i) {
        const auto& note = std::get<Note>(symbols[static_cast<std::size_t>(i)]);
        EXPECT_EQ(note.dynamics, Dynamics::decrescendo) << i;
        EXPECT_EQ(note.number, i + 2) << i;
        EXPECT_EQ(note.string, 5) << i;
        EXPECT_EQ(note.legato, 1) << i;
    }
    EXPECT_EQ(std::get<Note>(symbols[3]), (Note{Length::quarter, 4, 3}));
    type(editor, {KEY_RIGHT});  // a plain move ends the block
    EXPECT_FALSE(editor.model.block());
}

TEST(EditorKeys, BlockShiftsStopAtTheStaffsEdges) {
    auto editor = fresh_editor();
    type(editor, "19");
    type(editor, {KEY_SLEFT, KEY_SLEFT});
    const auto before = editor.model.score();
    type(editor, "+");
    EXPECT_EQ(editor.model.score(), before);
    EXPECT_EQ(editor.model.message(), "a number is already 9");
    type(editor, {KEY_SF, KEY_SF, KEY_SF});  // strings 3 -> 0 is refused at the third
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[0]).string, 1);
    EXPECT_EQ(editor.model.message(), "a note is already on the lowest string");
}

TEST(EditorKeys, ShiftDigitWithABlockSetsItsLengths) {
    auto editor = fresh_editor();
    type(editor, "120");
    type(editor, {KEY_SLEFT, KEY_SLEFT, KEY_SLEFT});
    type(editor, "&");
    for (const auto& symbol : editor.model.score().bars[0].symbols) {
        const Length length = std::holds_alternative<Note>(symbol) ? std::get<Note>(symbol).length
                                                                   : std::get<Rest>(symbol).length;
        EXPECT_EQ(length, Length::eighth);
    }
}

TEST(EditorKeys, CopyPasteGivesThePastedTiesFreshSerials) {
    auto editor = fresh_editor();
    type(editor, "12l");
    type(editor, {KEY_SLEFT, KEY_SLEFT, ctrl('C'), KEY_RIGHT, KEY_RIGHT});
    type(editor, "`");
    type(editor, {ctrl('V')});
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note number=\"1\" string=\"3\" length=\"quarter\" "
                   "legato=\"1\"/><Note number=\"2\" string=\"3\" length=\"quarter\" "
                   "legato=\"1\"/></Bar><Bar clef=\"lra\"><Note number=\"1\" string=\"3\" "
                   "length=\"quarter\" legato=\"2\"/><Note number=\"2\" string=\"3\" "
                   "length=\"quarter\" legato=\"2\"/></Bar>"));
    EXPECT_EQ(editor.model.cursor(), (Position{1, 2}));
}

TEST(EditorKeys, ABlockAcrossBarsPastesAsBars) {
    auto editor = fresh_editor();
    type(editor, "1`23");
    // From the end of bar 1 to the end of bar 2: its bar line and bar 2's notes.
    type(editor, {KEY_SLEFT, KEY_SLEFT, KEY_SLEFT, ctrl('C')});
    ASSERT_EQ(editor.model.cursor(), (Position{0, 1}));
    type(editor, {KEY_RIGHT, KEY_RIGHT, ctrl('V')});  // inside bar 2, before its 3
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note number=\"1\" string=\"3\" length=\"quarter\"/></Bar>"
                   "<Bar clef=\"lra\"><Note number=\"2\" string=\"3\" length=\"quarter\"/></Bar>"
                   "<Bar clef=\"lra\"><Note number=\"2\" string=\"3\" length=\"quarter\"/>"
                   "<Note number=\"3\" string=\"3\" length=\"quarter\"/>"
                   "<Note number=\"3\" string=\"3\" length=\"quarter\"/></Bar>"));
}

TEST(EditorKeys, WholeBarsPastedAtTheEndOfTheScoreAreNewBars) {
    // A newcomer copied bar 1 to the end: it went into the last bar, which then had 8 beats.
    auto editor = fresh_editor();
    type(editor, "1234`5678");
    type(editor, {KEY_HOME});
    for (int i = 0; i < 4; ++i) {
        type(editor, {KEY_SRIGHT});  // bar 1, its first to its last symbol
    }
    type(editor, {ctrl('C'), KEY_END, ctrl('V')});
    const auto& score = editor.model.score();
    ASSERT_EQ(score.bars.size(), 3u);
    EXPECT_EQ(score.bars[2], score.bars[0]);
    EXPECT_EQ(editor.model.cursor(), (Position{2, 4}));  // the end of the pasted bar
    EXPECT_EQ(editor.model.message(), "bar pasted");
    // At the start of a bar the bars go in before it; inside a bar, into it.
    type(editor, {KEY_HOME, ctrl('V')});
    ASSERT_EQ(editor.model.score().bars.size(), 4u);
    EXPECT_EQ(editor.model.score().bars[0], editor.model.score().bars[1]);
    type(editor, {KEY_RIGHT, KEY_RIGHT, ctrl('V')});  // between 3 and 4 of bar 2
    ASSERT_EQ(editor.model.score().bars.size(), 4u);
    EXPECT_EQ(editor.model.score().bars[1].symbols.size(), 8u);
    // One note copied is a note, even where it fills its bar.
    auto single = fresh_editor();
    type(single, "1`2");
    type(single, {KEY_HOME, ctrl('C'), KEY_END, ctrl('V')});
    EXPECT_EQ(single.model.score().bars.size(), 2u);
    EXPECT_EQ(single.model.score().bars[1].symbols.size(), 2u);
}

TEST(EditorKeys, CutRemovesTheBlockAndItsBarLines) {
    auto editor = fresh_editor();
    type(editor, "1`2`3");
    const auto before = editor.model.score();
    // From the end of bar 1 to the start of bar 3: the 2 and both its bar lines.
    type(editor, {KEY_LEFT, KEY_SLEFT, KEY_SLEFT, KEY_SLEFT, ctrl('X')});
    EXPECT_EQ(editor.model.score().bars,
              bars("<Bar clef=\"lra\"><Note number=\"1\" string=\"3\" length=\"quarter\"/>"
                   "<Note number=\"3\" string=\"3\" length=\"quarter\"/></Bar>"));
    type(editor, {ctrl('V')});  // puts the 2 and its bar lines back
    EXPECT_EQ(editor.model.score(), before);
}

TEST(EditorKeys, UndoAndRedoStepThroughEveryEdit) {
    auto editor = fresh_editor();
    const auto empty = editor.model.score();
    type(editor, "12d");
    const auto full = editor.model.score();
    type(editor, {ctrl('Z')});
    EXPECT_EQ(std::get<Note>(editor.model.score().bars[0].symbols[1]).dynamics, Dynamics::none);
    type(editor, {ctrl('Z'), ctrl('Z')});
    EXPECT_EQ(editor.model.score(), empty);
    EXPECT_EQ(editor.model.cursor(), (Position{0, 0}));
    type(editor, {ctrl('Z')});
    EXPECT_EQ(editor.model.message(), "nothing to undo");
    type(editor, {ctrl('Y'), ctrl('Y'), ctrl('Y')});
    EXPECT_EQ(editor.model.score(), full);
    type(editor, {ctrl('Y')});
    EXPECT_EQ(editor.model.message(), "nothing to redo");
    type(editor, {ctrl('Z')});
    type(editor, "5");  // a new edit forgets the redo
    type(editor, {ctrl('Y')});
    EXPECT_EQ(editor.model.message(), "nothing to redo");
}

TEST(EditorKeys, TheClefMenuSetsTheBarsClefAndDeclaresIt) {
    auto editor = fresh_editor();
    type(editor, "1`2");
    type(editor, "k");
    ASSERT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::clef_menu);
    const auto menu = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(menu.lines[static_cast<std::size_t>(menu.highlighted)], "lra  lra-phone.clef.xml");
    type(editor, {KEY_DOWN, '\n'});
    EXPECT_EQ(editor.model.score().bars[1].clef, "erm");
    EXPECT_EQ(editor.model.score().clefs,
              (std::vector<ClefDeclaration>{testing::kLra, testing::kErm}));
    type(editor, {KEY_LEFT, KEY_LEFT, KEY_LEFT});  // into bar 1
    type(editor, "k");
    type(editor, {KEY_DOWN, '\n'});
    // "lra" is used by no bar now: its declaration goes.
    EXPECT_EQ(editor.model.score().clefs, (std::vector<ClefDeclaration>{testing::kErm}));
}

TEST(EditorKeys, HomeAndEndGoToTheFirstAndTheLastBar) {
    auto editor = fresh_editor();
    type(editor, "5555`55");  // two bars
    type(editor, {KEY_HOME});
    EXPECT_EQ(editor.model.cursor(), (editor::Position{0, 0}));
    type(editor, {KEY_END});
    EXPECT_EQ(editor.model.cursor(), (editor::Position{1, 2}));
}

TEST(EditorKeys, FileAndPlaybackKeysAreRequests) {
    auto editor = fresh_editor();
    EXPECT_EQ(editor.key(ctrl('S')).kind, editor::Request::Kind::save);
    EXPECT_EQ(editor.key(ctrl('N')).kind, editor::Request::Kind::new_score);
    type(editor, "1`2");
    const auto play = editor.key(' ');
    EXPECT_EQ(play.kind, editor::Request::Kind::play);
    EXPECT_EQ(play.bar, 1u);
    // Unsaved changes: quitting asks first.
    EXPECT_EQ(editor.key('q').kind, editor::Request::Kind::none);
    EXPECT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::quit_menu);
    EXPECT_EQ(editor.key(KEY_DOWN).kind, editor::Request::Kind::none);
    EXPECT_EQ(editor.key('\n').kind, editor::Request::Kind::quit);
    editor.model.mark_saved();
    EXPECT_EQ(editor.key(ctrl('Q')).kind, editor::Request::Kind::quit);
}

TEST(EditorKeys, WhilePlayingEveryKeyStops) {
    auto editor = fresh_editor();
    type(editor, "1");
    editor.scheme.set_playing(true);
    const auto before = editor.model.score();
    for (const int key : {int{'5'}, KEY_LEFT, int{'\n'}, 27, KEY_DC}) {
        EXPECT_EQ(editor.key(key).kind, editor::Request::Kind::stop) << key;
    }
    EXPECT_EQ(editor.model.score(), before);
    editor.scheme.set_playing(false);
    EXPECT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::browse);
}

TEST(EditorKeys, UnknownKeysDoNothing) {
    auto editor = fresh_editor();
    const auto before = editor.model.score();
    type(editor, "xyz");
    EXPECT_EQ(editor.model.score(), before);
}

TEST(ScoreEdits, LengthStepsKeepDottedLengthsDotted) {
    using editor::longer;
    using editor::shorter;
    EXPECT_EQ(shorter(Length::quarter), Length::eighth);
    EXPECT_EQ(longer(Length::quarter), Length::half);
    EXPECT_EQ(shorter(Length::thirty_second), Length::thirty_second);
    EXPECT_EQ(longer(Length::whole), Length::whole);
    EXPECT_EQ(shorter(Length::quarter_dot), Length::eighth_dot);
    EXPECT_EQ(longer(Length::half_dot), Length::whole);
    EXPECT_EQ(shorter(Length::sixteenth_dot), Length::thirty_second);
    EXPECT_FALSE(editor::toggled_dot(Length::whole));
    EXPECT_EQ(editor::toggled_dot(Length::eighth), Length::eighth_dot);
}

}  // namespace
}  // namespace vibscore
