// "use for ...": saving offers the feedback theme's events before any name, a name proposed from
// the event chosen, and "keep as it was" after.
#include <gtest/gtest.h>

#include "client/editor/events.hpp"
#include "client/editor/menu.hpp"
#include "client/editor/status_line.hpp"
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

// A score opened from the registry and saved before: heartbeat.
editor::Editor opened_heartbeat() {
    auto editor = fresh_editor();
    editor.model.set_title("heartbeat");
    editor.model.mark_saved();
    editor.scheme.set_taken({{"heartbeat", editor::TakenName::What::shipped}});
    editor.scheme.set_destination("heartbeat", false, false);
    editor.scheme.set_events(theme_events());
    return editor;
}

TEST(EditorUseForEvent, TheFileGroupAssignsTheOpenScoreItselfNeverACopy) {
    // Assigning worked only through save as, which made heartbeat-2.
    auto editor = opened_heartbeat();
    const auto presses = to_menu_entry(editor, "use for event...");
    EXPECT_EQ(editor.scheme.menu_view(editor.model).title.rfind("menu: file", 0), 0u);
    press(editor, {S});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::use_for);
    const auto view = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(view.title, "use heartbeat for");
    EXPECT_EQ(view.lines.back(), "no event");
    EXPECT_EQ(editor.scheme.hint(editor.model), "\u2191\u2193choose Sel:use for it Back:close");
    press(editor, {D, D, D});  // alarm
    EXPECT_EQ(highlighted(editor), "alarm: alarm");
    // Nothing changed since it was saved: nothing is saved, the event gets heartbeat itself.
    EXPECT_EQ(editor.press(S),
              (Request{Request::Kind::assign_event, "", 0, false, "alarm-clock-elapsed"}));
    // The session assigns it and asks ok / keep as it was; ok confirms on the line.
    editor.scheme.show_assigned("alarm-clock-elapsed", "heartbeat");
    EXPECT_EQ(editor.press(S), Request{});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    EXPECT_EQ(editor.model.message(), "alarm-clock-elapsed plays heartbeat");
    // The key 'u' opens the same list.
    testing::type(editor, "u");
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::use_for);
    press(editor, {B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorUseForEvent, UnsavedChangesAreSavedToTheScoresOwnNameFirst) {
    auto editor = opened_heartbeat();
    press(editor, {S, S, B, B});  // a note: unsaved
    ASSERT_TRUE(editor.model.modified());
    to_menu_entry(editor, "use for event...");
    press(editor, {S});
    // heartbeat is shipped: saving over it asks, as save does (the stored one shadows it).
    EXPECT_EQ(editor.press(S), Request{});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::replace_menu);
    press(editor, {D});  // store yours over it
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save, "", 0, false, "phone-incoming-call"}));
    // Once stored over, the next time saves quietly, still under its own name.
    press(editor, {S, B, B});
    to_menu_entry(editor, "use for event...");
    press(editor, {S, D});
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save, "", 0, false, "message-new-instant"}));
}

TEST(EditorUseForEvent, WithoutTheFeedbackServiceItSaysSoAndHowToStartIt) {
    auto editor = opened_heartbeat();
    editor.scheme.set_events({},
                             "The feedback service is not running.\nFrom a checkout: ./dev daemon");
    to_menu_entry(editor, "use for event...");
    press(editor, {S});
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::no_events);
    const auto view = editor.scheme.menu_view(editor.model);
    EXPECT_EQ(view.lines, (std::vector<std::string>{"The feedback service is not running.",
                                                    "From a checkout: ./dev daemon"}));
    EXPECT_EQ(editor.scheme.hint(editor.model), "Sel/Back:close");
    press(editor, {B});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorUseForEvent, EverySaveThatDidNotAskOffersTheEventsAfterwards) {
    auto editor = opened_heartbeat();
    editor.scheme.set_destination("heartbeat", true, false);
    to_menu_entry(editor, "save");
    EXPECT_EQ(editor.press(S), (Request{Request::Kind::save}));
    editor.scheme.after_save("");
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::use_for);
    EXPECT_EQ(highlighted(editor), "no event");  // one Select goes on
    EXPECT_EQ(editor.press(S), Request{});
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    // Again at the next save: every save, not only the first.
    to_menu_entry(editor, "save");
    editor.press(S);
    editor.scheme.after_save("");
    ASSERT_EQ(editor.scheme.mode(), ButtonScheme::Mode::use_for);
    press(editor, {U});  // the line before "no event": the last event
    EXPECT_EQ(editor.press(S),
              (Request{Request::Kind::assign_event, "", 0, false, "button-pressed"}));
    // A save that was for an event, or that asked already, offers nothing more.
    editor.scheme.after_save("phone-incoming-call");
    EXPECT_EQ(editor.scheme.mode(), ButtonScheme::Mode::browse);
    auto fresh = new_score();
    to_menu_entry(fresh, "save");
    press(fresh, {S, U});  // asked first: no event, just save
    EXPECT_EQ(fresh.press(S), (Request{Request::Kind::save}));
    fresh.scheme.after_save("");
    EXPECT_EQ(fresh.scheme.mode(), ButtonScheme::Mode::browse);
    // No events: nothing to offer.
    auto without = opened_heartbeat();
    without.scheme.set_events({}, "not running");
    without.scheme.after_save("");
    EXPECT_EQ(without.scheme.mode(), ButtonScheme::Mode::browse);
}

TEST(EditorUseForEvent, LongLinesWrapAtTheScreensWidthAndShowWhole) {
    // "window-attention-requested: notification-message" was cut at 40 columns.
    const std::vector<std::string> lines{"window attention requested: notification-message",
                                         "alarm: alarm",
                                         "abcdefghijklmnopqrstuvwxyz0123456789abcdef"};
    const auto rows = editor::menu_rows(lines, 37);
    std::vector<std::string> again(lines.size());
    for (const auto& row : rows) {
        EXPECT_LE(editor::columns_of(row.text), 37) << row.text;
        auto& line = again[static_cast<std::size_t>(row.line)];
        const bool continued = !line.empty();
        const std::string text = continued ? row.text.substr(1) : row.text;  // indented
        line += (continued && row.line == 0 ? " " : "") + text;
    }
    EXPECT_EQ(again, lines);
    EXPECT_EQ(rows.size(), 5u);
    EXPECT_EQ(rows[0], (editor::MenuRow{"window attention requested:", 0}));
    EXPECT_EQ(rows[1], (editor::MenuRow{" notification-message", 0}));
    // A line exactly as wide as the menu is one row; one column more wraps.
    EXPECT_EQ(editor::menu_rows({std::string(37, 'x')}, 37).size(), 1u);
    EXPECT_EQ(editor::menu_rows({std::string(38, 'x')}, 37).size(), 2u);
}

}  // namespace
}  // namespace vibscore
