// How many of the six buttons a person presses to enter real tactons in `vibscore edit`.
// For each target score the planner drives the real editor (model and six-button scheme) from a
// new score to the target, the result is checked to equal the target, and the presses are
// counted. Prints a table, the averages (target: at most 4 presses per note) and one JSON line.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "client/editor/editor.hpp"
#include "client/editor/press_planner.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"

#ifndef VIBSCORE_BENCH_CLEFS
#define VIBSCORE_BENCH_CLEFS "clefs"
#endif

using namespace vibscore;
using namespace vibscore::editor;

namespace {

// Thesis Fig. 2.3a, first measure: an 8th (string 2, number 1) tied by legato to a quarter
// (string 3, number 2), an 8th rest and a half note (string 1, number 2); as the repository's
// golden tests write it.
constexpr const char* kFigure23 =
    "<VibScore><Title>Fig. 2.3 first measure</Title>"
    "<Clef id=\"c\" href=\"fig23-sine.clef.xml\"/><Bar clef=\"c\">"
    "<Note length=\"8th\" number=\"1\" string=\"2\" legato=\"1\"/>"
    "<Note length=\"quarter\" number=\"2\" string=\"3\" legato=\"1\"/>"
    "<Rest length=\"8th\"/><Note length=\"half\" number=\"2\" string=\"1\"/>"
    "</Bar></VibScore>";

// The shipped notification set (phone LRA) and the thesis' tactons (Figs. 5.1 and 5.2).
const std::vector<std::string> kNotifications{
    "alarm",    "failure", "notification-calendar", "notification-mail", "notification-message",
    "ringtone", "success", "touch-click",           "touch-tick"};
const std::vector<std::string> kThesisTactons{"create",      "delete",
                                              "file",        "folder",
                                              "create-file", "create-folder",
                                              "delete-file", "delete-folder",
                                              "call",        "call-high-priority",
                                              "message",     "message-high-priority"};

struct Result {
    std::string name;
    std::string group;
    int notes = 0;
    int symbols = 0;  // notes and rests
    std::size_t presses = 0;
    bool verified = false;
    double seconds = 0.0;
    std::string sequence;
    std::map<std::string, std::size_t> spent;  // presses by what they were pressed in
};

// What a press is spent on: the editor's state when it is pressed.
std::string spent_on(const Editor& editor) {
    using Mode = ButtonScheme::Mode;
    using Step = EntrySteps::Step;
    switch (editor.scheme.mode()) {
        case Mode::browse:
            return "browsing (string, cursor, start)";
        case Mode::entry:
            switch (editor.scheme.entry_step()) {
                case Step::string:
                    return "string step";
                case Step::string_more:
                    return "string step, other choices (rests, bars, leave)";
                case Step::number:
                case Step::number_more:
                    return "number step (and its other choices)";
                case Step::length:
                    return "length step";
                case Step::length_more:
                case Step::marks:
                    return "length step, other choices (dots, marks)";
            }
            break;
        default:
            break;
    }
    return "menus and lists (bar clefs)";
}

char letter(Button button) {
    switch (button) {
        case Button::up:
            return 'U';
        case Button::down:
            return 'D';
        case Button::left:
            return 'L';
        case Button::right:
            return 'R';
        case Button::select:
            return 'S';
        case Button::back:
            return 'B';
    }
    return '?';
}

Result measure(const std::string& name, const std::string& group, const Score& target) {
    Result result{name, group};
    for (const auto& bar : target.bars) {
        for (const auto& symbol : bar.symbols) {
            result.notes += std::holds_alternative<Note>(symbol) ? 1 : 0;
            result.symbols += std::holds_alternative<Blank>(symbol) ? 0 : 1;
        }
    }
    // A new score named after the target, on the target's first clef, with the target's clefs
    // to choose from: what `vibscore edit NAME` offers when those clefs are in the registry.
    const ClefDeclaration& first = *target.find_clef(target.bars.front().clef);
    Editor start{EditorModel(EditorModel::blank_score(target.title, first), target.clefs), {}};
    const auto began = std::chrono::steady_clock::now();
    const PressPlan plan = plan_presses(start, target);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    result.presses = plan.presses.size();
    // Replay the presses on a fresh editor: the plan must stand on its own.
    Editor replay = start;
    for (const Button button : plan.presses) {
        ++result.spent[spent_on(replay)];
        replay.press(button);
        result.sequence += letter(button);
    }
    result.verified = plan.reached && replay.model.score().bars == target.bars &&
                      replay.model.score().clefs == target.clefs;
    return result;
}

double per(std::size_t presses, int count) {
    return count == 0 ? 0.0 : static_cast<double>(presses) / count;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Six-button presses needed to enter tactons in vibscore edit."};
    std::string clefs = VIBSCORE_BENCH_CLEFS;
    bool sequences = false;
    app.add_option("--clefs", clefs, "directory of the shipped scores");
    app.add_flag("--sequences", sequences, "print each press sequence (U D L R S B)");
    CLI11_PARSE(app, argc, argv);

    std::vector<Result> results;
    try {
        results.push_back(
            measure("fig-2.3-measure-1", "thesis", read_score(kFigure23, "fig-2.3").score));
        for (const auto* group : {&kNotifications, &kThesisTactons}) {
            for (const auto& name : *group) {
                const auto path = std::filesystem::path(clefs) / (name + ".score.xml");
                const auto target = read_score(read_document_file(path), path.string()).score;
                results.push_back(
                    measure(name, group == &kNotifications ? "notification" : "thesis", target));
            }
        }
    } catch (const std::exception& error) {
        std::cerr << "editor_presses: " << error.what() << "\n";
        return 1;
    }

    std::printf("%-24s %-12s %5s %7s %7s %11s %13s %8s\n", "score", "group", "notes", "symbols",
                "presses", "per note", "per symbol", "checked");
    struct Sum {
        std::size_t presses = 0;
        int notes = 0, symbols = 0, scores = 0;
        double ratio_sum = 0.0;
    };
    Sum notification, all;
    bool all_verified = true;
    for (const auto& r : results) {
        std::printf("%-24s %-12s %5d %7d %7zu %11.2f %13.2f %8s\n", r.name.c_str(), r.group.c_str(),
                    r.notes, r.symbols, r.presses, per(r.presses, r.notes),
                    per(r.presses, r.symbols), r.verified ? "equal" : "DIFFERS");
        if (sequences) {
            std::printf("    %s\n", r.sequence.c_str());
        }
        all_verified = all_verified && r.verified;
        for (Sum* sum :
             {&all, r.group == "notification" || r.name == "fig-2.3-measure-1" ? &notification
                                                                               : nullptr}) {
            if (sum != nullptr) {
                sum->presses += r.presses;
                sum->notes += r.notes;
                sum->symbols += r.symbols;
                sum->scores += 1;
                sum->ratio_sum += per(r.presses, r.notes);
            }
        }
    }
    std::map<std::string, std::size_t> spent;
    for (const auto& r : results) {
        if (r.group == "notification" || r.name == "fig-2.3-measure-1") {
            for (const auto& [what, count] : r.spent) {
                spent[what] += count;
            }
        }
    }
    std::printf("\nFig. 2.3 + notification set, presses by what they were pressed in:\n");
    for (const auto& [what, count] : spent) {
        std::printf("  %-50s %4zu\n", what.c_str(), count);
    }
    std::printf(
        "\nFig. 2.3 + notification set: %zu presses for %d notes (%d symbols): "
        "%.2f per note, %.2f per symbol; mean of per-score ratios %.2f (target <= 4)\n",
        notification.presses, notification.notes, notification.symbols,
        per(notification.presses, notification.notes),
        per(notification.presses, notification.symbols),
        notification.ratio_sum / notification.scores);
    std::printf(
        "every score above: %zu presses for %d notes (%d symbols): %.2f per note, "
        "%.2f per symbol\n",
        all.presses, all.notes, all.symbols, per(all.presses, all.notes),
        per(all.presses, all.symbols));
    std::printf(
        "{\"benchmark\":\"editor_presses\",\"fig_2_3_presses\":%zu,\"fig_2_3_per_note\":%.3f,"
        "\"notification_presses\":%zu,\"notification_notes\":%d,\"notification_per_note\":%.3f,"
        "\"notification_per_symbol\":%.3f,\"all_per_note\":%.3f,\"all_verified\":%s}\n",
        results.front().presses, per(results.front().presses, results.front().notes),
        notification.presses, notification.notes, per(notification.presses, notification.notes),
        per(notification.presses, notification.symbols), per(all.presses, all.notes),
        all_verified ? "true" : "false");
    return all_verified ? 0 : 1;
}
