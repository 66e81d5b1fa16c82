#include "bench/editor_tasks.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <variant>

#include "client/editor/documents.hpp"
#include "client/editor/editor.hpp"
#include "client/editor/planner/press_planner.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/profile.hpp"
#include "feedback/theme.hpp"
#include "score/score_xml.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore::bench {

namespace {

using editor::Button;
using editor::Editor;
using editor::EditorModel;
using editor::Request;

const ClefDeclaration kLraPhone{"lra-phone", "lra-phone.clef.xml"};

// Where a task's presses went.
struct Count {
    std::string task;
    std::size_t entering = 0;  // notes, rests, changes (and tapping)
    std::size_t saving = 0;    // the menu to save, "use for", the event's name, ok
    std::size_t naming = 0;    // typing a name from the proposal
    std::size_t playing = 0;
    bool verified = false;
    std::size_t total() const { return entering + saving + naming + playing; }
};

Score one_string_score(const std::string& bars) {
    return read_score(
               "<VibScore><Title>t</Title><Clef id=\"lra-phone\" "
               "href=\"lra-phone.clef.xml\"/>" +
                   bars + "</VibScore>",
               "task")
        .score;
}

// Thesis Fig. 7.5: three bars of four quarter notes, strengths 9, 3, 6, 3, on string 3.
Score experiment_2() {
    return one_string_score(testing::experiment_2_bars());
}

// A double tap: two strong 16ths a 16th apart.
Score double_tap() {
    return one_string_score(
        "<Bar clef=\"lra-phone\"><Note length=\"16th\" number=\"9\" string=\"3\"/>"
        "<Rest length=\"16th\"/><Note length=\"16th\" number=\"9\" string=\"3\"/></Bar>");
}

std::string stripped(std::string name) {
    const std::string suffix = ".score.xml";
    if (name.ends_with(suffix)) {
        name.resize(name.size() - suffix.size());
    }
    return name;
}

// What `vibscore edit [NAME]` opens: a new tacton-1 on lra-phone, or a registry score; the
// registry's names taken, proposals learned from the others, the theme's events.
Editor opened(const std::string& name, const Score* score,
              const std::vector<editor::NamedScore>* registry,
              const std::vector<editor::EventScore>& events) {
    const bool fresh = score == nullptr;
    Editor editor{
        EditorModel(fresh ? EditorModel::blank_score(name, kLraPhone) : *score, {kLraPhone}), {}};
    std::vector<editor::TakenName> taken;
    if (registry != nullptr) {
        editor.model.learn_from(
            editor::learned_from_others(*registry, {name, editor.model.score()}));
        for (const auto& known : *registry) {
            taken.push_back({stripped(known.name), editor::TakenName::What::shipped});
        }
    }
    editor.scheme.set_taken(taken);
    editor.scheme.set_destination(name, fresh, fresh);
    editor.scheme.set_events(events);
    return editor;
}

std::size_t press_all(Editor& editor, const std::vector<Button>& presses) {
    for (const Button button : presses) {
        editor.press(button);
    }
    return presses.size();
}

// Entered note by note; false when the planner did not reach the score.
bool enter(Editor& editor, const Score& target, Count& count) {
    const auto plan = editor::plan_presses(editor, target);
    count.entering += press_all(editor, plan.presses);
    return plan.reached && editor.model.score().bars == target.bars;
}

// The rhythm tapped on Select at 0.8 s a beat (tap a rhythm: the menu's first line), then the
// strengths set as notation.
bool tap(Editor& editor, const Score& target, Count& count) {
    count.entering += press_all(editor, {Button::back, Button::select, Button::select});
    int notes = 0;
    for (const auto& bar : target.bars) {
        for (const auto& symbol : bar.symbols) {
            notes += std::holds_alternative<Note>(symbol) ? 1 : 0;
        }
    }
    for (int k = 0; k < notes; ++k) {
        editor.press_at(Button::select, std::chrono::milliseconds(800 * k));
    }
    editor.press_at(Button::back, std::chrono::milliseconds(800 * notes));
    count.entering += static_cast<std::size_t>(notes) + 1;
    const auto plan = editor::plan_changes(editor, target);
    count.entering += press_all(editor, plan.presses);
    return plan.reached && editor.model.score().bars == target.bars;
}

// Save for the first event offered (incoming call): save, the event, its proposed name, ok.
bool use_for_first_event(Editor& editor, Count& count) {
    count.saving += testing::menu_presses(editor, "save").size();
    if (editor.scheme.mode() != editor::ButtonScheme::Mode::use_for) {
        return false;
    }
    ++count.saving;
    editor.press(Button::select);  // the first event
    ++count.saving;
    const Request saved = editor.press(Button::select);  // the name proposed from it
    if (saved.kind != Request::Kind::save_as || saved.event.empty()) {
        return false;
    }
    editor.scheme.show_assigned(saved.event, saved.name);  // as the session does once stored
    ++count.saving;
    editor.press(Button::select);  // ok
    return saved.event == "phone-incoming-call" &&
           editor.scheme.mode() == editor::ButtonScheme::Mode::browse;
}

// Save as: no event (the list's last line, Up from its first), then `name` typed from the
// proposals.
bool save_as(Editor& editor, const std::string& name, Count& count) {
    count.saving += testing::menu_presses(editor, "save as...").size();
    if (editor.scheme.mode() == editor::ButtonScheme::Mode::use_for) {
        count.saving += press_all(editor, {Button::up});
        if (testing::highlighted(editor) != "no event: a name...") {
            return false;
        }
        count.saving += press_all(editor, {Button::select});
    }
    const auto plan = editor::plan_name(editor.scheme.name_entry(), name);
    Request saved;
    for (const Button button : plan.presses) {
        saved = editor.press(button);
        ++count.naming;
    }
    return plan.reached && saved.kind == Request::Kind::save_as && saved.name == name;
}

// Playing it all: other choices, Up.
bool play(Editor& editor, Count& count) {
    editor.press(Button::back);
    const Request request = editor.press(Button::up);
    count.playing += 2;
    return request.kind == Request::Kind::play && request.bar == 0;
}

}  // namespace

std::vector<editor::EventScore> theme_events(const std::string& theme_file) {
    const auto theme = feedback::load_theme(theme_file, feedback::ThemeSearch{});
    std::vector<editor::EventScore> events;
    for (const auto& [event, levels] : theme.events()) {
        const auto* entry = theme.lookup(event, feedback::Profile::full);
        const std::string score = entry != nullptr ? entry->score : "";
        events.push_back({event, score, score, false});
    }
    return events;
}

std::string report_tasks(const std::vector<editor::NamedScore>* registry,
                         const std::vector<editor::EventScore>& events,
                         const std::string& clefs_dir) {
    std::vector<Count> counts;
    {
        Count count{"exp2"};
        Editor editor = opened("tacton-1", nullptr, registry, events);
        count.verified = enter(editor, experiment_2(), count) && save_as(editor, "exp2", count);
        counts.push_back(count);
    }
    {
        Count count{"exp2-call"};
        Editor editor = opened("tacton-1", nullptr, registry, events);
        count.verified = enter(editor, experiment_2(), count) && use_for_first_event(editor, count);
        counts.push_back(count);
    }
    {
        Count count{"exp2-tap"};
        Editor editor = opened("tacton-1", nullptr, registry, events);
        count.verified = tap(editor, experiment_2(), count) && use_for_first_event(editor, count);
        counts.push_back(count);
    }
    {
        Count count{"confirm"};
        Editor editor = opened("tacton-1", nullptr, registry, events);
        count.verified = enter(editor, double_tap(), count) && save_as(editor, "confirm", count);
        counts.push_back(count);
    }
    {
        Count count{"my-ring"};
        const Score ringtone =
            editor::read_score_file(std::filesystem::path(clefs_dir) / "ringtone.score.xml");
        Score changed = ringtone;
        for (auto bar = changed.bars.rbegin(); bar != changed.bars.rend(); ++bar) {
            const auto last =
                std::find_if(bar->symbols.rbegin(), bar->symbols.rend(),
                             [](const auto& s) { return std::holds_alternative<Note>(s); });
            if (last != bar->symbols.rend()) {
                auto& note = std::get<Note>(*last);
                note.number = std::min(note.number + 1, 9);
                break;
            }
        }
        Editor editor = opened("ringtone", &ringtone, registry, events);
        const auto plan = editor::plan_changes(editor, changed);
        count.entering += press_all(editor, plan.presses);
        count.verified = plan.reached && editor.model.score().bars == changed.bars &&
                         save_as(editor, "my-ring", count) && play(editor, count);
        counts.push_back(count);
    }

    std::printf("\nissue 26's tasks, from opening the editor (%s)\n",
                registry != nullptr ? "with registry proposals, leave-one-out"
                                    : "without registry proposals");
    std::printf("  %-10s %7s %9s %7s %7s %8s  %s\n", "task", "presses", "entering", "saving",
                "naming", "playing", "checked");
    std::string json = "[";
    for (const auto& count : counts) {
        std::printf("  %-10s %7zu %9zu %7zu %7zu %8zu  %s\n", count.task.c_str(), count.total(),
                    count.entering, count.saving, count.naming, count.playing,
                    count.verified ? "reached" : "NOT REACHED");
        json += (json.size() > 1 ? "," : "") + std::string("{\"task\":\"") + count.task +
                "\",\"presses\":" + std::to_string(count.total()) +
                ",\"entering\":" + std::to_string(count.entering) +
                ",\"saving\":" + std::to_string(count.saving) +
                ",\"naming\":" + std::to_string(count.naming) +
                ",\"playing\":" + std::to_string(count.playing) +
                ",\"verified\":" + (count.verified ? "true" : "false") + "}";
    }
    std::printf(
        "  (a newcomer pressed 83 + 38 naming for exp2, 81 for confirm, 87 for my-ring; "
        "issue 26's target for exp2-call: <= 55)\n");
    return json + "]";
}

}  // namespace vibscore::bench
