// What the registry's scores say comes next: the proposals learned from other scores.
#include <gtest/gtest.h>

#include "client/editor/phrase_book.hpp"
#include "client/editor/score_edits.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::EditorModel;
using editor::PhraseBook;
using editor::Position;
using testing::bars;
using testing::end_of;
using testing::kLra;
using testing::score_of;

const std::string kLearned =
    "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\"/>"
    "<Note length=\"quarter\" number=\"3\" string=\"2\"/>"
    "<Note length=\"half\" number=\"9\" string=\"6\"/></Bar>";

// A score being entered that begins as kLearned does.
const char* const kEnteringItsStart =
    "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\"/>"
    "<Note length=\"quarter\" number=\"3\" string=\"2\"/></Bar>";

TEST(PhraseBook, WhatFollowedTheSamePhraseInALearnedScoreComesNext) {
    PhraseBook book;
    book.learn(score_of(kLearned));
    const auto entering = score_of(kEnteringItsStart);
    const auto next = book.next_after(entering, end_of(entering));
    ASSERT_TRUE(next);
    EXPECT_EQ(next->next, (Symbol{Note{Length::half, 9, 6}}));
    EXPECT_EQ(next->context, 3);  // two symbols and the start of both scores
}

TEST(PhraseBook, AScoreStartsAsTheLearnedScoresStart) {
    PhraseBook book;
    book.learn(score_of(kLearned));
    const auto empty = score_of("<Bar clef=\"lra\"></Bar>");
    const auto first = book.next_after(empty, Position{0, 0});
    ASSERT_TRUE(first);
    EXPECT_EQ(first->next, (Symbol{Note{Length::eighth, 7, 5}}));
    EXPECT_EQ(first->context, 1);
}

TEST(PhraseBook, TheLongestPhraseWinsOverTheMoreFrequentOne) {
    PhraseBook book;
    // After the 8th note on string 5: twice a rest in the second score, once a half note after
    // the same two notes as in the score being entered.
    book.learn(score_of(kLearned));
    book.learn(score_of(
        "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"3\" string=\"2\"/><Rest "
        "length=\"8th\"/>"
        "<Note length=\"quarter\" number=\"3\" string=\"2\"/><Rest length=\"8th\"/></Bar>"));
    const auto entering = score_of(kEnteringItsStart);
    const auto next = book.next_after(entering, end_of(entering));
    ASSERT_TRUE(next);
    EXPECT_EQ(next->next, (Symbol{Note{Length::half, 9, 6}}));
    // One symbol of context only: the more frequent rest.
    const auto lone = score_of(
        "<Bar clef=\"lra\"><Rest length=\"half\"/><Note length=\"quarter\" number=\"3\" "
        "string=\"2\"/></Bar>");
    const auto after_lone = book.next_after(lone, end_of(lone));
    ASSERT_TRUE(after_lone);
    EXPECT_EQ(after_lone->next, (Symbol{Rest{Length::eighth}}));
    EXPECT_EQ(after_lone->occurrences, 2);
}

TEST(PhraseBook, AHairpinGoesOnAsItWentOnWhereItWasLearned) {
    // Pulses learned with a fade each, pulses learned plain after a swell.
    PhraseBook book;
    book.learn(score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\" "
        "dynamics=\"decrescendo\"/><Rest length=\"8th\"/><Note length=\"8th\" number=\"7\" "
        "string=\"5\" dynamics=\"decrescendo\"/></Bar>"));
    book.learn(
        score_of("<Bar clef=\"lra\"><Note length=\"half\" number=\"9\" string=\"6\" "
                 "dynamics=\"crescendo\"/><Rest length=\"quarter\"/><Note length=\"quarter\" "
                 "number=\"7\" string=\"5\"/></Bar>"));
    // Plain pulses: the learned pulse kept the hairpin of the one before, so it comes plain.
    const auto plain = score_of(
        "<Bar clef=\"lra\"><Note length=\"8th\" number=\"7\" string=\"5\"/><Rest "
        "length=\"8th\"/></Bar>");
    const auto pulse = book.next_after(plain, end_of(plain));
    ASSERT_TRUE(pulse);
    EXPECT_EQ(pulse->next, (Symbol{Note{Length::eighth, 7, 5}}));
    // A hairpin that changed where it was learned comes as learned: plain after a fade here.
    const auto faded = score_of(
        "<Bar clef=\"lra\"><Note length=\"half\" number=\"9\" string=\"6\" "
        "dynamics=\"decrescendo\"/><Rest length=\"quarter\"/></Bar>");
    const auto after_fade = book.next_after(faded, end_of(faded));
    ASSERT_TRUE(after_fade);
    EXPECT_EQ(after_fade->next, (Symbol{Note{Length::quarter, 7, 5}}));
}

TEST(PhraseBook, NothingIsPredictedAfterASymbolNoLearnedScorePlays) {
    PhraseBook book;
    book.learn(score_of(kLearned));
    const auto entering =
        score_of("<Bar clef=\"lra\"><Note length=\"whole\" number=\"1\" string=\"1\"/></Bar>");
    EXPECT_FALSE(book.next_after(entering, end_of(entering)));
}

TEST(PhraseBook, TheEditorProposesTheLearnedNoteWhereTheScoreSaysNothing) {
    auto book = std::make_shared<PhraseBook>();
    book->learn(score_of(kLearned));
    EditorModel alone(EditorModel::blank_score("t", kLra), {kLra});
    EditorModel learning(EditorModel::blank_score("t", kLra), {kLra});
    learning.learn_from(book);
    for (auto* model : {&alone, &learning}) {
        model->insert_note(7);  // on the active string 3, a quarter: unlike the learned start
    }
    // After a note no learned score plays, the rules propose.
    EXPECT_EQ(learning.proposed_symbol(), alone.proposed_symbol());
    EditorModel started(EditorModel::blank_score("t", kLra), {kLra});
    started.learn_from(book);
    started.set_length(Length::eighth);
    started.move_up();
    started.move_up();
    started.insert_note(7);  // 8th, number 7, string 5: the learned start, so the phrase is two
    ASSERT_EQ(started.score().bars[0].symbols.front(), (Symbol{Note{Length::eighth, 7, 5}}));
    EXPECT_EQ(started.proposed_symbol(), (Symbol{Note{Length::quarter, 3, 2}}));
    EditorModel unlearned(EditorModel::blank_score("t", kLra), {kLra});
    unlearned.set_length(Length::eighth);
    unlearned.move_up();
    unlearned.move_up();
    unlearned.insert_note(7);
    EXPECT_NE(unlearned.proposed_symbol(), (Symbol{Note{Length::quarter, 3, 2}}));
}

TEST(PhraseBook, AScoreIsNeverLearnedFromItselfByNameOrByMusic) {
    const Score learned = score_of(kLearned);
    const Score other = score_of("<Bar clef=\"lra\"><Rest length=\"half\"/></Bar>");
    const std::vector<editor::NamedScore> registry{
        {"ringtone", learned}, {"copy-of-ringtone", learned}, {"pause", other}};
    EXPECT_EQ(editor::learned_from_others(registry, {"ringtone", learned})->scores(), 1u);
    EXPECT_EQ(editor::learned_from_others(registry, {"pause", learned})->scores(), 0u);
    EXPECT_EQ(editor::learned_from_others(registry, {"", Score{}})->scores(), 3u);
}

}  // namespace
}  // namespace vibscore
