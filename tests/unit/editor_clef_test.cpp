// Clefs on the device (client/editor/clef_editor.*): a sine clef's frequencies, amplitudes and
// tempo, a curve clef's points, each change heard, saved under a new name for the bar.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "client/editor/actuator_feel.hpp"
#include "client/editor/clef_editor.hpp"
#include "client/editor/status_line.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::ButtonScheme;
using editor::ClefEditor;
using editor::Request;
using Outcome = ClefEditor::Outcome;

using namespace testing::buttons;

// lra-phone as shipped: tempo 0.2 s, numbers 0.2 .. 1.0, strings 155 .. 235 Hz.
Clef lra_phone() {
    Clef clef;
    clef.tempo = 0.2;
    clef.numbers = {0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    for (const double hz : {155.0, 170.0, 185.0, 200.0, 215.0, 235.0}) {
        clef.strings.push_back({hz, {}});
    }
    return clef;
}

Clef curve() {
    Clef clef = lra_phone();
    clef.type = ClefType::curve;
    for (auto& string : clef.strings) {
        string.frequency = 0.0;
        string.points = {{0.0, 0.0}, {0.5, 1.0}, {1.0, 0.0}};
    }
    return clef;
}

Outcome press_all(ClefEditor& editor, std::initializer_list<editor::Button> buttons) {
    Outcome outcome = Outcome::editing;
    for (const auto button : buttons) {
        outcome = editor.press(button);
    }
    return outcome;
}

TEST(ClefEditor, ASineClefShowsTempoStringsAndNumbersInFortyColumns) {
    const ClefEditor editor("lra-phone", lra_phone());
    const auto lines = editor.lines(40, 11);
    EXPECT_EQ(lines,
              (std::vector<std::string>{"clef lra-phone (sine)", ">tempo 0.200 s", " s6 235 Hz",
                                        " s5 215 Hz", " s4 200 Hz", " s3 185 Hz", " s2 170 Hz",
                                        " s1 155 Hz", " n1 0.20  n2 0.30  n3 0.40  n4 0.50 ",
                                        " n5 0.60  n6 0.70  n7 0.80  n8 0.90 ", " n9 1.00 "}));
    for (const auto& line : lines) {
        EXPECT_LE(editor::columns_of(line), 40) << line;
    }
    EXPECT_EQ(editor.hint(), "\u2191\u2193field \u2190\u2192value S:hear B:more");
}

TEST(ClefEditor, AtEightyColumnsTheNumbersTakeTwoRowsAndAShortWindowKeepsTheCursorInSight) {
    ClefEditor editor("lra-phone", lra_phone());
    const auto wide = editor.lines(80, 20);
    ASSERT_EQ(wide.size(), 10u);
    EXPECT_EQ(wide[8].substr(0, 9), " n1 0.20 ");
    EXPECT_NE(wide[8].find("n8 0.90"), std::string::npos);
    EXPECT_EQ(wide[9], " n9 1.00 ");
    // Five rows: the field under the cursor (n9, Up from the tempo) stays on screen.
    editor.press(editor::Button::up);
    const auto shortened = editor.lines(40, 5);
    ASSERT_EQ(shortened.size(), 5u);
    EXPECT_EQ(shortened.back(), ">n9 1.00 ");
}

TEST(ClefEditor, AStringsFrequencyStepsBy5HzThen1HzFineAndEachStepIsHeard) {
    ClefEditor editor("lra-phone", lra_phone());
    press_all(editor, {D, D, D, D});  // tempo, s6, s5, s4, s3
    EXPECT_EQ(editor.string(), 3);
    EXPECT_EQ(editor.press(R), Outcome::hear);
    EXPECT_DOUBLE_EQ(editor.clef().strings[2].frequency, 190.0);
    EXPECT_TRUE(editor.modified());
    EXPECT_EQ(editor.lines(40, 11)[5], ">s3 190 Hz");
    press_all(editor, {B});
    EXPECT_EQ(editor.hint(), "\u2191fine \u2193hear S:save as B:close");
    press_all(editor, {U, L, L});  // fine: 1 Hz down, twice
    EXPECT_DOUBLE_EQ(editor.clef().strings[2].frequency, 188.0);
    EXPECT_EQ(editor.number(), 5);  // heard at the number under the cursor (5 by default)
}

TEST(ClefEditor, ANumberChangedIsHeardOnTheStringJustEditedNotTheLastOneTheCursorPassed) {
    // n5 0.60 -> 0.70 played on s1, the last string passed on the way down to the numbers.
    ClefEditor editor("lra-phone", lra_phone());
    press_all(editor, {D, D, D});  // tempo, s6, s5, s4
    EXPECT_EQ(editor.press(R), Outcome::hear);
    EXPECT_EQ(editor.string(), 4);
    press_all(editor, {D, D, D, D, D, D, D, D});  // s3, s2, s1, n1 .. n5
    EXPECT_EQ(editor.string(), 4);
    EXPECT_EQ(editor.press(R), Outcome::hear);
    EXPECT_EQ(editor.string(), 4);
    EXPECT_EQ(editor.number(), 5);
    EXPECT_DOUBLE_EQ(editor.clef().numbers[4], 0.7);
    // Select on a string is hearing that string: the numbers are heard on it from then on.
    press_all(editor, {U, U, U, U, U, U, S});  // n4 .. n1, s1, s2: heard
    EXPECT_EQ(editor.string(), 2);
}

TEST(ClefEditor, ANumberSetAboveTheNextNumbersAmplitudeIsAllowedButSaid) {
    ClefEditor editor("lra-phone", lra_phone());
    press_all(editor, {U, U, U, U, U});  // from the tempo up: n9 .. n5
    ASSERT_EQ(editor.number(), 5);
    press_all(editor, {R});  // 0.70: as strong as n6, the last value said nothing of
    EXPECT_EQ(editor.notice(), "");
    press_all(editor, {R});  // 0.80: above n6's 0.70, the first value said
    EXPECT_DOUBLE_EQ(editor.clef().numbers[4], 0.8);
    EXPECT_EQ(editor.notice(), "n5 0.80 is above n6 0.70");
    const auto lines = editor.lines(40, 11);
    ASSERT_EQ(lines.size(), 11u);
    EXPECT_EQ(lines.back(), "!n5 0.80 is above n6 0.70");
    EXPECT_NE(std::find(lines.begin(), lines.end(), ">n5 0.80  n6 0.70  n7 0.80  n8 0.90 "),
              lines.end())
        << "the field under the cursor in sight";
    press_all(editor, {L, L});  // back to 0.60: in order again, nothing said
    EXPECT_EQ(editor.notice(), "");
    EXPECT_EQ(editor.lines(40, 11).back(), " n9 1.00 ");
    // Lowered below the number before: said too.
    press_all(editor, {U, L, L, L});  // n4 0.50 -> 0.20, below n3's 0.40
    EXPECT_EQ(editor.notice(), "n4 0.20 is below n3 0.40");
}

TEST(ClefEditor, ValuesStopAtTheirLimitsOnBothSides) {
    Clef clef = lra_phone();
    clef.strings[0].frequency = 2.0;
    clef.strings[5].frequency = 19'998.0;
    clef.numbers[0] = 0.1;
    clef.tempo = 0.003;
    ClefEditor editor("x", clef);
    press_all(editor, {B, U});     // fine steps
    press_all(editor, {L, L, L});  // tempo 0.003: 0.002, 0.001 (the least), 0.001
    EXPECT_DOUBLE_EQ(editor.clef().tempo, 0.001);
    press_all(editor, {U});  // from the tempo up: wraps to n9
    EXPECT_EQ(editor.number(), 9);
    press_all(editor, {D});        // and down again: the tempo
    press_all(editor, {D});        // s6
    press_all(editor, {R, R, R});  // 19998: 19999, 20000 (the most), 20000
    EXPECT_DOUBLE_EQ(editor.clef().strings[5].frequency, 20'000.0);
    press_all(editor, {D, D, D, D, D});  // s1
    press_all(editor, {L, L});           // 2: 1 (the least), 1
    EXPECT_DOUBLE_EQ(editor.clef().strings[0].frequency, 1.0);
    press_all(editor, {D});  // n1
    EXPECT_EQ(editor.number(), 1);
    press_all(editor, {B, U, L, L});  // coarse: 0.1 - 0.1 = 0 (the least), 0
    EXPECT_DOUBLE_EQ(editor.clef().numbers[0], 0.0);
}

TEST(ClefEditor, ACurveStringsPointsMoveInTimeAndLevelAndAreAddedAndDeleted) {
    ClefEditor editor("soft", curve());
    press_all(editor, {D});  // s6: a waveform
    EXPECT_EQ(editor.hint(), "\u2191\u2193field S:points B:more");
    EXPECT_EQ(editor.press(R), Outcome::editing);  // no value to step
    EXPECT_EQ(editor.press(S), Outcome::hear);     // its points
    ASSERT_EQ(editor.level(), ClefEditor::Level::points);
    EXPECT_EQ(editor.hint(), "\u2191\u2193level \u2190\u2192time S:next B:more");
    press_all(editor, {S});  // the middle point
    EXPECT_EQ(editor.press(D), Outcome::hear);
    EXPECT_DOUBLE_EQ(editor.clef().strings[5].points[1].level, 0.9);
    press_all(editor, {R, R});
    EXPECT_DOUBLE_EQ(editor.clef().strings[5].points[1].time, 0.6);
    // In time, a point stays between its neighbours.
    for (int i = 0; i < 20; ++i) {
        editor.press(R);
    }
    EXPECT_DOUBLE_EQ(editor.clef().strings[5].points[1].time, 1.0);
    press_all(editor, {B, U});  // a point after it, halfway to the next
    ASSERT_EQ(editor.clef().strings[5].points.size(), 4u);
    EXPECT_EQ(editor.point(), 2);
    press_all(editor, {B, D, B, D});  // two deleted: two points are the fewest
    EXPECT_EQ(editor.clef().strings[5].points.size(), 2u);
    press_all(editor, {B, D});
    EXPECT_EQ(editor.clef().strings[5].points.size(), 2u);
    const auto lines = editor.lines(40, 11);
    EXPECT_EQ(lines[0], "clef soft s6 (curve) *");
    EXPECT_NE(lines[2].find('^'), std::string::npos);  // the point under the cursor
    press_all(editor, {B, B});                         // back to the fields
    EXPECT_EQ(editor.level(), ClefEditor::Level::fields);
    EXPECT_EQ(press_all(editor, {B, S}), Outcome::save_as);
    EXPECT_EQ(press_all(editor, {B, B}), Outcome::close);
}

TEST(ClefEditor, EveryHintFitsFortyColumns) {
    ClefEditor sine("lra-phone", lra_phone());
    ClefEditor waves("soft", curve());
    for (auto* editor : {&sine, &waves}) {
        for (const auto& presses : std::vector<std::vector<editor::Button>>{
                 {}, {B}, {U}, {D}, {D, S}, {B}, {B, B, U}, {B}}) {
            for (const auto button : presses) {
                editor->press(button);
            }
            EXPECT_LE(editor::columns_of(editor->hint()), 40) << editor->hint();
        }
    }
}

// In the editor: "edit clefs..." lists the clefs read, a change is heard, and saving stores
// the clef under a new name for the bar.
class ClefWindow : public ::testing::Test {
  protected:
    ClefWindow() {
        editor.scheme.set_clef_book(
            editor::ClefBook({{testing::kLra, lra_phone(), true}, {testing::kErm, curve(), true}}));
        testing::to_menu_entry(editor, "edit clefs...");
        editor.press(S);
    }
    editor::Editor editor = testing::fresh_editor();
};

TEST_F(ClefWindow, TheListOpensOnTheBarsClefAndSelectOpensItsWindow) {
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_list);
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines,
              (std::vector<std::string>{"lra  sine 0.20 s", "erm  curve 0.20 s"}));
    EXPECT_EQ(testing::highlighted(editor), "lra  sine 0.20 s");
    editor.press(S);
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_edit);
    ASSERT_NE(editor.scheme.clef_editor(), nullptr);
    EXPECT_EQ(editor.scheme.clef_editor()->id(), "lra");
}

TEST_F(ClefWindow, EachChangeIsHeardAndSavingUsesANewName) {
    editor.press(S);
    testing::press(editor, {D, D, D, D});
    const auto heard = editor.press(R);
    EXPECT_EQ(heard.kind, Request::Kind::hear_clef);
    EXPECT_EQ(heard.string, 3);
    EXPECT_EQ(heard.number, 5);
    EXPECT_DOUBLE_EQ(read_clef(heard.document, "heard").strings[2].frequency, 190.0);
    testing::press(editor, {B, S});  // save as
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_name);
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines, std::vector<std::string>{"[lra-2]"});
    const auto saved = editor.press(S);
    EXPECT_EQ(saved.kind, Request::Kind::save_clef);
    EXPECT_EQ(saved.name, "lra-2");
    EXPECT_DOUBLE_EQ(read_clef(saved.document, "saved").strings[2].frequency, 190.0);
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST_F(ClefWindow, ANameThatExistsIsRefusedSoAShippedClefIsNeverSavedOver) {
    editor.press(S);
    testing::press(editor, {D, R, B, S});  // a change; save as
    // Typed "erm": e, r, m.
    testing::press(editor, {U, U, D, L, R, L});
    ASSERT_EQ(editor.scheme.menu_view(editor.model).lines[0], "erm|");
    EXPECT_EQ(editor.press(S), Request{});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_name);
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines[1], "erm exists: another name");
}

TEST_F(ClefWindow, ClosingAChangedClefAsksFirst) {
    editor.press(S);
    testing::press(editor, {D, R, B, B});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_close);
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines,
              (std::vector<std::string>{"save as...", "drop the changes", "cancel"}));
    testing::press(editor, {D, D, S});  // cancel: back in the window, the change kept
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_edit);
    EXPECT_TRUE(editor.scheme.clef_editor()->modified());
    testing::press(editor, {B, B, D, S});  // drop the changes
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST_F(ClefWindow, AKeyboardCommandWhileAClefIsOpenIsRefusedAndTheClefKept) {
    editor.press(S);
    testing::press(editor, {D, R});  // s6 changed
    const std::string before = write_score(editor.model.score());
    EXPECT_EQ(editor.scheme.command(editor::Command{editor::Action::crescendo}, editor.model),
              Request{});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::clef_edit);
    EXPECT_TRUE(editor.scheme.clef_editor()->modified());
    EXPECT_EQ(write_score(editor.model.score()), before);
    EXPECT_EQ(editor.model.message(), "a clef is open: Back, Back closes it");
    testing::press(editor, {B, B, D, S});  // drop the changes: commands work again
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    editor.scheme.command(editor::Command{editor::Action::tap_rhythm}, editor.model);
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::tapping);
}

TEST(ClefOfBars, ASavedClefIsDeclaredOnceAndGivenToTheBarsAsked) {
    editor::Editor editor = testing::fresh_editor();
    const ClefDeclaration mine{"lra-2", "lra-2.clef.xml"};
    editor.model.add_available_clef(mine);
    editor.model.add_available_clef(mine);  // once only
    EXPECT_EQ(std::count(editor.model.available_clefs().begin(),
                         editor.model.available_clefs().end(), mine),
              1);
    ASSERT_TRUE(editor.model.set_clef_of_bars(0, 0, mine));  // the last bar there is
    EXPECT_EQ(editor.model.score().bars[0].clef, "lra-2");
    ASSERT_NE(editor.model.score().find_clef("lra-2"), nullptr);
    EXPECT_FALSE(editor.model.set_clef_of_bars(0, 1, mine));  // the first bar there is not
    EXPECT_FALSE(editor.model.set_clef_of_bars(1, 0, mine));
    EXPECT_TRUE(editor.model.undo());
    EXPECT_EQ(editor.model.score().bars[0].clef, "lra");
}

TEST(ActuatorFeel, AnLraGivesItsStrengthAtEachStringsFrequencyBesideIt) {
    const std::map<std::string, std::string> lra{
        {"kind", "lra"}, {"resonance-hz", "185"}, {"q", "10"}, {"rated-drive", "1"}};
    const auto feel = editor::actuator_feel(lra_phone(), lra);
    ASSERT_EQ(feel.size(), 6u);
    EXPECT_EQ(feel[2], "gives 100%");  // s3: 185 Hz, the resonance
    // G(f) = (1/Q) / sqrt((1 - r^2)^2 + (r/Q)^2): s1 155 Hz 32 %, s6 235 Hz 16 %.
    EXPECT_EQ(feel[0], "gives 32%");
    EXPECT_EQ(feel[5], "gives 16%");
    // A curve clef's strings play at the resonance.
    EXPECT_EQ(editor::actuator_feel(curve(), lra)[0], "gives 100%");
    // Written beside each string in the window.
    const ClefEditor editor("lra-phone", lra_phone());
    EXPECT_EQ(editor.lines(40, 11, feel)[5], " s3 185 Hz  gives 100%");
}

TEST(ActuatorFeel, NothingIsShownForAnErmOrWithoutAUsableDeclaration) {
    EXPECT_TRUE(editor::actuator_feel(lra_phone(), {}).empty());
    EXPECT_TRUE(
        editor::actuator_feel(lra_phone(), {{"kind", "erm"}, {"spin-up-ms", "30"}}).empty());
    for (const std::string resonance : {"0", "-5", "abc", "175x", "inf"}) {
        EXPECT_TRUE(editor::actuator_feel(
                        lra_phone(), {{"kind", "lra"}, {"resonance-hz", resonance}, {"q", "10"}})
                        .empty())
            << resonance;
    }
    EXPECT_TRUE(
        editor::actuator_feel(lra_phone(), {{"kind", "lra"}, {"q", "10"}, {"brake", "x"}}).empty());
}

// The property is read by actuator::from_settings, as the client's verbs read it (issue 30): what
// the declaration allows is shown, what it refuses is not. (The editor's own parse once took any
// positive resonance and wanted q given; the declaration's limit is 10 Hz and q defaults to 15.)
TEST(ActuatorFeel, TheDeclarationsOwnLimitsAndDefaultsDecideWhatIsShown) {
    EXPECT_EQ(
        editor::actuator_feel(lra_phone(), {{"kind", "lra"}, {"resonance-hz", "10"}, {"q", "1"}})
            .size(),
        6u);  // the last resonance allowed
    EXPECT_TRUE(
        editor::actuator_feel(lra_phone(), {{"kind", "lra"}, {"resonance-hz", "9.99"}, {"q", "1"}})
            .empty());  // the first refused
    EXPECT_EQ(editor::actuator_feel(lra_phone(), {{"kind", "lra"}, {"resonance-hz", "185"}}),
              editor::actuator_feel(lra_phone(),
                                    {{"kind", "lra"}, {"resonance-hz", "185"}, {"q", "15"}}));
}

}  // namespace
}  // namespace vibscore
