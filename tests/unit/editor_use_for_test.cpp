// "use for ...": saving offers the feedback theme's events before any name, a name proposed from
// the event chosen, and "keep as it was" after.
#include <gtest/gtest.h>

#include "client/editor/events.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::ButtonScheme;
using editor::EventScore;
using editor::Request;
using testing::fresh_editor;
using testing::highlighted;
using testing::press;
using testing::to_menu_entry;

using namespace testing::buttons;

// vibscore-feedback's shipped theme, as EventScores lists it (sorted by event), the user having
// chosen "confirm" for new SMS.
std::vector<EventScore> theme_events() {
    return {{"alarm-clock-elapsed", "alarm", "alarm", false},
            {"button-pressed", "touch-click", "touch-click", false},
            {"message-new-instant", "notification-message", "notification-message", false},
            {"message-new-sms", "confirm", "message-new-sms", true},
            {"phone-incoming-call", "ringtone", "ringtone", false}};
}

// `vibscore edit` on a new score, tacton-1, with vibscore-feedback's events.
editor::Editor new_score() {
    auto editor = fresh_editor();
    editor.model.set_title("tacton-1");
    editor.model.mark_saved();
    editor.scheme.set_taken({{"alarm", editor::TakenName::What::shipped},
                             {"ringtone", editor::TakenName::What::shipped}});
    editor.scheme.set_destination("tacton-1", true, true);
    editor.scheme.set_events(theme_events());
    return editor;
}

TEST(EditorEvents, TheEventsPeopleComposeForComeFirstInTheirOwnWords) {
    const auto ordered = editor::in_offer_order(theme_events());
    std::vector<std::string> labels;
    for (const auto& event : ordered) {
        labels.push_back(editor::event_label(event.event));
    }
    EXPECT_EQ(labels, (std::vector<std::string>{"incoming call", "new message", "new SMS", "alarm",
                                                "button pressed"}));
    EXPECT_EQ(editor::score_before(ordered[2]), "confirm");  // the user's own before
    EXPECT_EQ(editor::score_before(ordered[0]), "");         // the theme's
}

TEST(EditorUseFor, SaveAsOffersTheEventsWithWhatEachPlaysThenANameFromTheEvent) {
    auto editor = new_score();
    press(editor, {S, S, B, B});  // a note
    to_menu_entry(editor, "save as...");
    press(editor, {S});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::use_for);
    const auto view = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(view.title, "use for ...");
    EXPECT_EQ(view.lines, (std::vector<std::string>{
                              "incoming call: ringtone", "new message: notification-message",
                              "new SMS: confirm", "alarm: alarm", "button pressed: touch-click",
                              "no event: a name..."}));
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u2191\u2193choose Sel:save for it Back:close");
    press(editor, {S});  // incoming call: the names, the event's first
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::name_entry);
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines,
              (std::vector<std::string>{"phone-incoming-call-2", "tacton-2"}));
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save_as, "phone-incoming-call-2", 0, false,
                                        "phone-incoming-call"}));
}

TEST(EditorUseFor, ANewScoresFirstSaveAsksTooAndNoEventJustSaves) {
    auto editor = new_score();
    to_menu_entry(editor, "save");
    press(editor, {S});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::use_for);
    press(editor, {U});  // wraps to the last line
    EXPECT_EQ(highlighted(editor), "no event: just save");
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save}));
    // For an event, its own name is a choice too, after the event's.
    to_menu_entry(editor, "save");
    press(editor, {S, D, S});  // new message
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines,
              (std::vector<std::string>{"message-new-instant-2", "tacton-1", "tacton-2"}));
    EXPECT_EQ(editor.press(D), Request{});
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save, "", 0, false, "message-new-instant"}));
    // Back closes the question, saving nothing.
    to_menu_entry(editor, "save");
    press(editor, {S, B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorUseFor, AScoreOpenedFromTheRegistrySavesWithoutAskingAndNoEventsNoQuestion) {
    auto opened = new_score();
    opened.scheme.set_destination("tacton-1", true, false);  // saved before
    to_menu_entry(opened, "save");
    EXPECT_EQ(opened.press(S), (Request{Request::Kind::save}));

    auto without = new_score();
    without.scheme.set_events({});  // vibscore-feedback out of reach, or a file
    to_menu_entry(without, "save as...");
    press(without, {S});
    EXPECT_EQ(without.scheme.mode(), ButtonScheme::Mode::name_entry);
    press(without, {B, B});  // cancelled
    to_menu_entry(without, "save");
    EXPECT_EQ(without.press(S), (Request{Request::Kind::save}));
}

TEST(EditorUseFor, SavedForAnEventOkOrKeepAsItWas) {
    auto editor = new_score();
    editor.scheme.show_assigned("phone-incoming-call", "my-ring");
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::assigned);
    auto view = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(view.title, "incoming call plays:");
    EXPECT_EQ(view.lines, (std::vector<std::string>{"my-ring (ok)", "keep as it was (ringtone)"}));
    EXPECT_EQ(editor.press(S), Request{});  // ok
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);

    // Keep as it was: an event that played the theme's gets the theme's back ("").
    editor.scheme.show_assigned("phone-incoming-call", "my-ring");
    press(editor, {D});
    EXPECT_EQ(editor.press(S),
              (Request{Request::Kind::keep_event, "", 0, false, "phone-incoming-call"}));
    // One the user had chosen before gets that one back.
    editor.scheme.show_assigned("message-new-sms", "my-sms");
    EXPECT_EQ(editor.scheme.menu_view(editor.model).lines[1], "keep as it was (confirm)");
    press(editor, {U});
    EXPECT_EQ(editor.press(S),
              (Request{Request::Kind::keep_event, "confirm", 0, false, "message-new-sms"}));
}

}  // namespace
}  // namespace vibscore
