// The bottom line of a 40x12 screen: what the buttons do is never cut.
#include <gtest/gtest.h>

#include <set>

#include "client/editor/score_edits.hpp"
#include "client/editor/status_line.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Button;
using editor::columns_of;
using editor::status_line;
using editor::status_of;
using editor::StatusParts;
using testing::fresh_editor;
using testing::press;

using namespace testing::buttons;

constexpr int kSmallWidth = 40;

TEST(StatusLine, TheSymbolBeingEnteredGivesWayToTheHint) {
    // A newcomer never saw "B:done": the symbol in front pushed it past column 40.
    StatusParts parts{
        true, "", "5 quarter_dot s3", "\u2191s4 S:s3 \u2193rest \u2190rest.. \u2192bar B:done",
        1,    2};
    const auto line = status_line(parts, kSmallWidth);
    EXPECT_NE(line.find("B:done"), std::string::npos) << line;
    EXPECT_EQ(line.find("quarter"), std::string::npos) << line;
    EXPECT_LE(columns_of(line), kSmallWidth);
}

TEST(StatusLine, TheBarAndItsCountStandAtTheRightWhereRoomIsLeft) {
    const auto editor = fresh_editor();
    const std::string browsing = editor.scheme.hint(editor.model);
    EXPECT_EQ(browsing, "S:new note B:play,go to,menu");
    const auto line = status_line({true, "", "", browsing, 2, 3}, kSmallWidth);
    EXPECT_EQ(columns_of(line), kSmallWidth);
    EXPECT_TRUE(line.starts_with("*" + browsing));
    EXPECT_TRUE(line.ends_with("bar 2/3"));
    EXPECT_EQ(status_line({false, "saved", "", "Sel:new note", 1, 1}, kSmallWidth), "saved");
}

// Every hint of every step and menu, on notes of every length, fits 40 columns whole, with the
// mark of unsaved changes in front.
TEST(StatusLine, EveryHintFitsFortyColumns) {
    const std::vector<std::vector<Button>> to_steps{
        {},  {S},          {S, B}, {S, S}, {S, S, B}, {S, S, S}, {S, S, S, B}, {S, S, S, B, D},
        {B}, {S, B, B, B}, {B, S},
    };
    for (int longer = 0; longer < 10; ++longer) {
        for (const auto& steps : to_steps) {
            auto editor = fresh_editor();
            editor.model.set_length(editor::stepped(Length::thirty_second, longer));
            for (const auto button : steps) {
                editor.press(button);
            }
            const std::string hint = editor.scheme.hint(editor.model);
            const auto line = status_line({true, "", "", hint, 12, 12}, kSmallWidth);
            EXPECT_NE(line.find(hint), std::string::npos) << "cut: " << line;
        }
    }
}

TEST(StatusLine, SaveAsHintsFitFortyColumnsAndHideTheLastAction) {
    auto editor = fresh_editor();
    editor.model.set_title("My Ringtone");  // proposed too: a list of names first
    editor.scheme.set_taken({{"ringtone", editor::TakenName::What::shipped}});
    editor.scheme.set_destination("ringtone", false);
    testing::to_menu_entry(editor, "save as...");
    press(editor, {S});  // the proposals, then every level of typing
    for (const auto& presses : std::vector<std::vector<Button>>{
             {}, {R}, {U}, {U}, {B}, {U}, {B}, {R}, {B}, {L}, {B}, {B}, {D}}) {
        for (const auto button : presses) {
            editor.press(button);
        }
        ASSERT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::name_entry);
        const auto parts = status_of(editor.model, editor.scheme, "undone");
        EXPECT_EQ(parts.message, "");
        const auto line = status_line(parts, kSmallWidth);
        EXPECT_NE(line.find(parts.hint), std::string::npos) << "cut: " << line;
    }
    press(editor, {B, B, B, B});  // back to letters, more, the proposals; cancelled
    ASSERT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::browse);
    testing::to_menu_entry(editor, "save");
    press(editor, {S});  // ringtone is shipped: another name, store yours over it, cancel
    const auto parts = status_of(editor.model, editor.scheme, "undone");
    EXPECT_EQ(parts.message, "");
    EXPECT_NE(status_line(parts, kSmallWidth).find("(shipped file stays)"), std::string::npos);
}

TEST(StatusLine, AListShowsItsHintNotWhatWasDoneBeforeIt) {
    auto editor = fresh_editor();
    editor.scheme.set_openable({"heartbeat", "ringtone"});
    press(editor, {S, S, B, B});  // a note
    ASSERT_TRUE(editor.model.undo());
    ASSERT_EQ(editor.model.message(), "undone");
    editor.scheme.command(editor::Command{editor::Action::open}, editor.model);
    ASSERT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::open_menu);
    const auto line =
        status_line(status_of(editor.model, editor.scheme, editor.model.message()), kSmallWidth);
    EXPECT_TRUE(line.starts_with(editor.scheme.hint(editor.model))) << line;
}

TEST(StatusLine, TheShortestLengthIsA32nd) {
    auto editor = fresh_editor();
    editor.model.set_length(Length::thirty_second);
    EXPECT_EQ(editor.model.message(), "length 32nd");
    press(editor, {S, U, B, S});  // a 32nd note on string 4, this number, at its length step
    ASSERT_EQ(editor.scheme.entry_step(), editor::EntrySteps::Step::length);
    EXPECT_EQ(editor::symbol_entered(editor.model), "5 32nd s4");
    const auto hint = editor.scheme.hint(editor.model);
    EXPECT_NE(hint.find("\u219332nd"), std::string::npos) << hint;  // Down: still a 32nd
}

TEST(StatusLine, AProposalUnlikeTheLastEnteredLengthOrStringIsInCapitals) {
    // A newcomer took an 8th proposed after quarters for another quarter: it looked the same.
    auto editor = fresh_editor();
    auto& model = editor.model;
    for (const int delta : {0, -1, +1}) {  // a quarter, an 8th, a quarter
        model.begin_entry();
        model.entry_length(delta);
        model.end_entry();
    }
    model.begin_entry();  // what followed a quarter before: an 8th
    ASSERT_EQ(editor::length_of(*editor::symbol_at(model.score(), model.cursor())), Length::eighth);
    EXPECT_EQ(editor::symbol_entered(model), "5 8TH s3");
    model.entry_length(+1);  // changed to the running length: plain again
    EXPECT_EQ(editor::symbol_entered(model), "5 quarter s3");
    model.entry_string(+1);  // the user's own string is the active one
    EXPECT_EQ(editor::symbol_entered(model), "5 quarter s4");
    model.end_entry();
}

TEST(StatusLine, AProposalOnAnotherStringThanTheLastNoteIsInCapitals) {
    auto editor = fresh_editor();
    auto& model = editor.model;
    for (const int delta : {0, +2, -2}) {  // strings 3, 5, 3
        model.begin_entry();
        model.entry_string(delta);
        model.end_entry();
    }
    model.begin_entry();  // what followed string 3 before: string 5
    EXPECT_EQ(editor::symbol_entered(model), "5 quarter S5");
    model.cancel_entry();
    model.begin_entry();
    model.entry_string(-2);  // the thumb's own choice
    EXPECT_EQ(editor::symbol_entered(model), "5 quarter s3");
}

TEST(StatusLine, AfterAMenuActionBackShowsTheChoicesNotTheOldNews) {
    // A newcomer saw "*crescendo" on the line through Back, Back, Back, pressed Up to change the
    // string, and the score played: the line never said the choices were open.
    auto editor = fresh_editor();
    press(editor, {S, S, B, B});  // a note
    testing::to_menu_entry(editor, "crescendo  <");
    press(editor, {S});
    ASSERT_EQ(editor.model.message(), "crescendo");
    press(editor, {B});
    ASSERT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::browse_choices);
    const auto line =
        status_line(status_of(editor.model, editor.scheme, editor.model.message()), kSmallWidth);
    EXPECT_TRUE(line.starts_with("*\u2191play all \u2193play bar")) << line;
    press(editor, {B});  // back to browsing: what Select and Back do, not the old news
    const auto browsing =
        status_line(status_of(editor.model, editor.scheme, editor.model.message()), kSmallWidth);
    EXPECT_TRUE(browsing.starts_with("*S:new note")) << browsing;
}

TEST(StatusLine, BrowsingNamesTheSymbolSelectWouldChangeInWords) {
    // A newcomer read "S:change 5 8th_dot s3": the score's XML tokens, not words.
    auto editor = fresh_editor();
    testing::type(editor, "5");
    testing::type(editor, "&0");  // an 8th rest
    press(editor, {L});
    EXPECT_EQ(editor.scheme.hint(editor.model), "S:change 8th rest B:play,go to,menu");
    press(editor, {L});
    EXPECT_EQ(editor.scheme.hint(editor.model), "S:change quarter, 5, string 3 B:more");
    editor.model.set_length(Length::eighth_dot);
    testing::type(editor, "5");
    press(editor, {L});
    EXPECT_EQ(editor.scheme.hint(editor.model), "S:change dotted 8th, 5, string 3 B:more");
    // The longest name (a dotted quarter) leaves out "change" rather than Back.
    editor.model.set_length(Length::quarter_dot);
    testing::type(editor, "9");
    press(editor, {L});
    const auto hint = editor.scheme.hint(editor.model);
    EXPECT_EQ(hint, "S:dotted quarter, 9, string 3 B:more");
    EXPECT_LE(columns_of(hint), kSmallWidth);
}

TEST(StatusLine, SymbolsAreNamedInWordsNeverInTheDocumentsTokens) {
    EXPECT_EQ(editor::symbol_words(Note{Length::eighth_dot, 5, 3}), "dotted 8th, 5, string 3");
    EXPECT_EQ(editor::symbol_words(Rest{Length::half_dot}), "dotted half rest");
    EXPECT_EQ(editor::symbol_words(Rest{Length::thirty_second}), "32nd rest");
    for (int longer = 0; longer < 10; ++longer) {
        const auto length = editor::stepped(Length::thirty_second, longer);
        EXPECT_EQ(editor::length_words(length).find('_'), std::string::npos);
        EXPECT_EQ(editor::length_words(editor::stepped(Length::sixteenth_dot, longer)).find('_'),
                  std::string::npos);
    }
    // While entering, the length in words too (the string stays "s3", as the hint's "↑s4").
    auto editor = fresh_editor();
    editor.model.set_length(Length::eighth_dot);
    press(editor, {S});
    const auto entered = editor::symbol_entered(editor.model);
    EXPECT_EQ(entered.find('_'), std::string::npos) << entered;
    EXPECT_NE(entered.find("dotted 8th"), std::string::npos) << entered;
}

TEST(StatusLine, TheNumberStepNamesEveryNumberOnTheScreen) {
    // Numbers more than two away were hidden behind "B:more": a wrong proposal cost 4-5 presses.
    for (int number = 1; number <= 9; ++number) {
        auto editor = fresh_editor();
        editor.model.insert_note(number);
        press(editor, {S, B, S});  // the same note again; this string: its number step
        ASSERT_EQ(editor.scheme.entry_step(), editor::EntrySteps::Step::number);
        const auto hint = editor.scheme.hint(editor.model);
        std::set<int> shown{number};
        for (const char c : hint) {
            if (c >= '1' && c <= '9') {
                shown.insert(c - '0');
            }
        }
        EXPECT_EQ(shown.size(), 9u) << hint;
        const auto line = status_line(status_of(editor.model, editor.scheme, ""), kSmallWidth);
        EXPECT_NE(line.find(hint), std::string::npos) << line;
    }
}

TEST(StatusLine, WhilePlayingTheLineNamesTheBarPlayingNow) {
    // "playing bar 1 on" read as "now in bar 1" while the playback cursor was in bar 4.
    auto editor = fresh_editor();
    press(editor, {S, S, S, S, S, S, S, S, S, S, B, B});  // two full bars and one note
    editor.scheme.set_playing(true);
    const auto parts = status_of(editor.model, editor.scheme, "", editor::Position{2, 0});
    EXPECT_EQ(status_line(parts, kSmallWidth), "*playing bar 3/3: any button stops");
}

TEST(StatusLine, ANewScoreShowsWhatTheButtonsDoBeforeTheFirstPress) {
    const auto editor = fresh_editor();
    const auto line = status_line(status_of(editor.model, editor.scheme, ""), kSmallWidth);
    EXPECT_TRUE(line.starts_with("S:new note B:play,go to,menu")) << line;
}

TEST(StatusLine, AFullKeyboardsScreenNamesTheDigitKeysInOneLine) {
    const std::string keys = editor::keyboard_hint();
    EXPECT_LE(columns_of(keys), 80);
    EXPECT_NE(keys.find("1-9 note"), std::string::npos);
    EXPECT_NE(keys.find("Shift+1..0 length"), std::string::npos);
}

}  // namespace
}  // namespace vibscore
