// What the score itself says comes next: the recurrence behind the six-button proposal.
#include <gtest/gtest.h>

#include "client/editor/recurrence.hpp"
#include "client/editor/score_edits.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Position;
using editor::recurrence_at;
using testing::bars;
using testing::end_of;
using testing::score_of;

TEST(Recurrence, NoneBeforeTwoSymbolsOrWhenNothingIsAlike) {
    const auto one = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\"/>"
        "</Bar>");
    EXPECT_FALSE(recurrence_at(one, end_of(one)));
    const auto unlike = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\"/>"
        "<Rest length=\"quarter\"/><Note length=\"half\" number=\"7\" string=\"5\"/></Bar>");
    EXPECT_FALSE(recurrence_at(unlike, end_of(unlike)));
}

TEST(Recurrence, ANoteAndAPauseTakenInTurnsGoOnInTurns) {
    const auto score = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\"/><Rest length=\"8th\"/>"
        "<Note length=\"8th\" number=\"7\" string=\"5\"/></Bar>");
    const auto next = recurrence_at(score, end_of(score));
    ASSERT_TRUE(next);
    EXPECT_EQ(next->next, (Symbol{Rest{Length::eighth}}));
}

TEST(Recurrence, TheSameBeatOfAnEarlierBarGivesTheRhythmOfABarPlayedAgainElsewhere) {
    // Bar 2 is bar 1 on other strings: after its third 8th note comes what came at that beat.
    const auto score = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\"/><Rest length=\"8th\"/>"
        "<Note length=\"8th\" number=\"7\" string=\"5\"/><Rest length=\"8th\"/>"
        "<Note length=\"8th\" number=\"7\" string=\"5\"/><Rest length=\"quarter_dot\"/></Bar>"
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"9\" string=\"6\"/><Rest length=\"8th\"/>"
        "<Note length=\"8th\" number=\"9\" string=\"6\"/><Rest length=\"8th\"/>"
        "<Note length=\"8th\" number=\"9\" string=\"6\"/></Bar>");
    const auto at_third = recurrence_at(score, end_of(score));
    ASSERT_TRUE(at_third);
    EXPECT_EQ(at_third->next, (Symbol{Rest{Length::quarter_dot}}));
    // Earlier in bar 2, the same 8th note is followed by the 8th rest, as at that beat of bar 1.
    const auto at_second = recurrence_at(score, Position{1, 3});
    ASSERT_TRUE(at_second);
    EXPECT_EQ(at_second->next, (Symbol{Rest{Length::eighth}}));
}

TEST(Recurrence, AfterTheSameNoteTheNoteThatFollowedItComesTiedAsItWas) {
    const auto score = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"6\" string=\"2\" legato=\"1\"/>"
        "<Note length=\"quarter\" number=\"7\" string=\"4\" legato=\"1\" dynamics=\"crescendo\"/>"
        "<Rest length=\"8th\"/><Note length=\"8th\" number=\"6\" string=\"2\"/></Bar>");
    const auto next = recurrence_at(score, end_of(score));
    ASSERT_TRUE(next);
    ASSERT_TRUE(next->pitch_known);
    const auto& note = std::get<Note>(next->next);
    EXPECT_EQ(note.length, Length::quarter);
    EXPECT_EQ(note.number, 7);
    EXPECT_EQ(note.string, 4);
    EXPECT_EQ(note.dynamics, Dynamics::crescendo);
    // The note before is not tied yet: a serial no note uses, for the two of them.
    EXPECT_EQ(note.legato, 2);
    EXPECT_EQ(note.portamento, 0);
}

TEST(Recurrence, AfterARestOrANoteAlikeOnlyInLengthANoteIsOnlyARhythm) {
    const auto after_rest = score_of(
        "<Bar clef=\"lra\"><Rest length=\"8th\"/><Note length=\"half\" number=\"8\" string=\"3\"/>"
        "<Rest length=\"8th\"/></Bar>");
    const auto note_after_rest = recurrence_at(after_rest, end_of(after_rest));
    ASSERT_TRUE(note_after_rest);
    EXPECT_FALSE(note_after_rest->pitch_known);
    EXPECT_EQ(editor::length_of(note_after_rest->next), Length::half);

    const auto same_length = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"4\" string=\"1\"/>"
        "<Note length=\"quarter\" number=\"6\" string=\"3\"/>"
        "<Note length=\"8th\" number=\"9\" string=\"6\"/></Bar>");
    const auto rhythm = recurrence_at(same_length, end_of(same_length));
    ASSERT_TRUE(rhythm);
    EXPECT_FALSE(rhythm->pitch_known);
    EXPECT_EQ(editor::length_of(rhythm->next), Length::quarter);
}

TEST(Recurrence, BlanksAreNotSymbolsAndTheLatestOccurrenceWins) {
    const auto score = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"5\" string=\"3\"/><Rest length=\"8th\"/>"
        "<Note length=\"8th\" number=\"5\" string=\"3\"/><Rest length=\"16th\"/>"
        "<Note length=\"8th\" number=\"5\" string=\"3\"/></Bar>");
    auto with_blank = score;
    with_blank.bars[0].symbols.insert(with_blank.bars[0].symbols.begin() + 1, Blank{});
    for (const Score* s : {&score, static_cast<const Score*>(&with_blank)}) {
        const auto next = recurrence_at(*s, end_of(*s));
        ASSERT_TRUE(next);
        // Neither earlier 8th note is at this beat: the latest one's rest follows.
        EXPECT_EQ(next->next, (Symbol{Rest{Length::sixteenth}}));
    }
}

}  // namespace
}  // namespace vibscore
