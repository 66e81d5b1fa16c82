// Editors compare by value (EditorModel, ButtonScheme and their parts: operator== = default),
// and the press planner tells states apart by it: two equal editors must answer every press
// alike, or the planner would take one state for another and count presses that do not work.
// Every state a search of the buttons reaches twice, by two ways, is pressed on again, and both
// answers must be the same for every sequence of up to three presses.
#include <gtest/gtest.h>

#include <deque>
#include <random>
#include <unordered_set>

#include "client/editor/phrase_book.hpp"
#include "client/editor/planner/editor_hash.hpp"
#include "client/editor/status_line.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Button;
using editor::Editor;
using editor::EditorHash;
using testing::fresh_editor;

using namespace testing::buttons;

// Everything a press shows or asks for: the score, the cursor and block, what the screen says,
// the open menu, and the request to the session.
std::string answer(Editor& editor, Button button) {
    const auto request = editor.press(button);
    const auto& model = editor.model;
    std::string text = editor::score_text(model.score());
    text += "|request " + std::to_string(static_cast<int>(request.kind)) + ' ' + request.name +
            ' ' + std::to_string(request.bar) + ' ' + std::to_string(request.then_quit);
    text += "|cursor " + std::to_string(model.cursor().bar) + '.' +
            std::to_string(model.cursor().symbol) + " s" + std::to_string(model.string());
    if (const auto block = model.block()) {
        text += "|block " + std::to_string(block->first.bar) + '.' +
                std::to_string(block->first.symbol) + '-' + std::to_string(block->end.bar) + '.' +
                std::to_string(block->end.symbol);
    }
    text += "|status " +
            editor::status_line(editor::status_of(model, editor.scheme, model.message()), 40);
    text += "|hint " + editor.scheme.hint(model);
    const auto menu = editor.scheme.menu_view(model);
    text += "|menu " + menu.title + ':' + std::to_string(menu.highlighted);
    for (const auto& line : menu.lines) {
        text += ';' + line;
    }
    text += "|modified " + std::to_string(model.modified());
    return text;
}

// The answers to every sequence of up to `depth` presses, in order.
std::vector<std::string> answers(const Editor& editor, int depth) {
    std::vector<std::string> found;
    if (depth == 0) {
        return found;
    }
    for (const Button button : editor::all_buttons) {
        Editor pressed = editor;
        found.push_back(answer(pressed, button));
        const auto further = answers(pressed, depth - 1);
        found.insert(found.end(), further.begin(), further.end());
    }
    return found;
}

struct Search {
    std::size_t states = 0;
    std::size_t met_again = 0;
};

// Random walks of the buttons (and now and then a key) from `start`, every state kept by its
// key; a state met again, by another walk or another way, is checked against the one met first.
Search walk_from(const Editor& start, int walks, int presses, unsigned seed) {
    Search search;
    std::unordered_set<Editor, EditorHash> first_met;
    std::mt19937 random(seed);
    const int keys[] = {'1',
                        '5',
                        '9',
                        '0',
                        '.',
                        '&',
                        '%',
                        'c',
                        'l',
                        'p',
                        'b',
                        3 /* Ctrl+C */,
                        22 /* Ctrl+V */,
                        26 /* Ctrl+Z */,
                        '`',
                        KEY_DC};
    for (int walk = 0; walk < walks; ++walk) {
        Editor editor = start;
        for (int press = 0; press < presses; ++press) {
            const auto pick = random() % 20;
            if (pick < 6) {
                editor.press(editor::all_buttons[pick]);
            } else if (pick < 18) {
                editor.press(editor::all_buttons[random() % 6]);
            } else {
                editor.key(keys[random() % std::size(keys)]);
            }
            if (editor.scheme.mode() == editor::ButtonScheme::Mode::playing) {
                editor.scheme.set_playing(false);
            }
            const auto [met, added] = first_met.insert(editor);
            if (!added) {
                ++search.met_again;
                EXPECT_EQ(answers(*met, 3), answers(editor, 3));
                if (::testing::Test::HasFailure()) {
                    return search;
                }
            }
        }
    }
    search.states = first_met.size();
    return search;
}

// Breadth-first over the buttons from `start`, up to `limit` states; every state met again by
// another path is checked against the one met first.
Search search_from(const Editor& start, std::size_t limit) {
    Search search;
    std::unordered_set<Editor, EditorHash> first_met{start};
    std::deque<Editor> queue{start};
    while (!queue.empty() && first_met.size() < limit) {
        const Editor from = std::move(queue.front());
        queue.pop_front();
        for (const Button button : editor::all_buttons) {
            Editor next = from;
            next.press(button);
            const auto [met, added] = first_met.insert(next);
            if (added) {
                queue.push_back(std::move(next));
                continue;
            }
            ++search.met_again;
            EXPECT_EQ(answers(*met, 3), answers(next, 3));
            if (::testing::Test::HasFailure()) {
                return search;  // one stale key is enough to say so
            }
        }
    }
    search.states = first_met.size();
    return search;
}

TEST(EditorEquality, EqualEditorsAnswerEveryPressAlikeOnANewScore) {
    const auto search = search_from(fresh_editor(), 5'000);
    EXPECT_GE(search.states, 5'000u);
    EXPECT_GT(search.met_again, 500u);  // the search met states again, so it compared some
}

TEST(EditorEquality, EqualEditorsAnswerEveryPressAlikeInAScoreWithBarsBlocksAndNames) {
    auto editor = fresh_editor();
    testing::type(editor, "1203");  // notes and a rest to change, mark, copy and undo
    testing::type(editor, {KEY_LEFT, KEY_SLEFT, KEY_SLEFT});
    editor.model.copy();
    editor.model.split_bar();
    testing::type(editor, "45");
    editor.model.mark_saved();
    testing::type(editor, "6");
    editor.scheme.set_openable({"alarm", "ringtone"});
    editor.scheme.set_taken(
        {{"alarm", editor::TakenName::What::shipped}, {"t", editor::TakenName::What::stored}});
    editor.scheme.set_destination("t", false, true);
    editor.scheme.set_events({{"phone-incoming-call", "ringtone", "ringtone", false},
                              {"message-new-sms", "confirm", "message-new-sms", true}});
    const auto search = search_from(editor, 5'000);
    EXPECT_GE(search.states, 5'000u);
    EXPECT_GT(search.met_again, 500u);
}

TEST(EditorEquality, EqualEditorsAnswerEveryPressAlikeWithRegistryProposals) {
    auto editor = fresh_editor();
    const auto learned = read_score(
        "<VibScore><Clef id=\"lra\" href=\"lra-phone.clef.xml\"/><Bar clef=\"lra\">"
        "<Note length=\"quarter\" number=\"5\" string=\"3\"/><Note length=\"8th\" number=\"9\" "
        "string=\"6\"/><Rest length=\"8th\"/></Bar></VibScore>",
        "learned.xml");
    editor.model.learn_from(editor::learned_from_others({{"learned", learned.score}}, {"t", {}}));
    const auto search = search_from(editor, 3'000);
    EXPECT_GE(search.states, 3'000u);
    EXPECT_GT(search.met_again, 250u);
}

TEST(EditorEquality, EqualEditorsAnswerEveryPressAlikeAlongRandomWalks) {
    const auto search = walk_from(fresh_editor(), 40, 150, 26);
    EXPECT_GT(search.met_again, 500u);
}

}  // namespace
}  // namespace vibscore
