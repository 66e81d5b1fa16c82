// How many of the six buttons a person presses to enter tactons in `vibscore edit`, without and
// with proposals learned from a registry of other scores. For each target score the planner
// drives the real editor (model and six-button scheme) from a new score to the target, the
// result is checked to equal the target, and the presses are counted. With a registry the
// editor learns every registry score but the target itself (leave-one-out: not the same file
// name, not the same music), as `vibscore edit` learns the daemon's registry. Prints a table,
// the totals per note and per symbol, issue 26's newcomer tasks from opening the editor to the
// last press (bench/editor_tasks.hpp), and one JSON line.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/editor_tasks.hpp"
#include "bench/press_targets.hpp"
#include "bench/report.hpp"
#include "client/editor/editor.hpp"
#include "client/editor/phrase_book.hpp"
#include "client/editor/planner/press_planner.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"
#include "tests/support/editor_support.hpp"

#ifndef VIBSCORE_BENCH_CLEFS
#define VIBSCORE_BENCH_CLEFS "clefs"
#endif
#ifndef VIBSCORE_BENCH_THEME
#define VIBSCORE_BENCH_THEME "feedback/themes/default.json"
#endif

using namespace vibscore;
using namespace vibscore::editor;
namespace fs = std::filesystem;

namespace {

using bench::kFigure23;
using bench::kNotifications;
using bench::kThesisTactons;
using bench::read_registry;
using bench::read_tacton;
using bench::score_files;
using bench::Tacton;

struct Entered {
    std::size_t presses = 0;
    bool verified = false;
    std::string sequence;
    std::map<std::string, std::size_t> spent;  // presses by what they were pressed in
};

struct Result {
    std::string name;
    int notes = 0;
    int symbols = 0;  // notes and rests
    std::size_t learned_from = 0;
    Entered alone;
    std::optional<Entered> learning;
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

Entered enter(const Score& target, std::shared_ptr<const PhraseBook> phrases) {
    // A new score named after the target, on the target's first clef, with the target's clefs
    // to choose from: what `vibscore edit NAME` offers when those clefs are in the registry.
    const ClefDeclaration& first = *target.find_clef(target.bars.front().clef);
    Editor start{EditorModel(EditorModel::blank_score(target.title, first), target.clefs), {}};
    start.model.learn_from(std::move(phrases));
    const PressPlan plan = plan_presses(start, target);
    Entered entered;
    entered.presses = plan.presses.size();
    // Replay the presses on a fresh editor: the plan must stand on its own.
    Editor replay = start;
    for (const Button button : plan.presses) {
        ++entered.spent[spent_on(replay)];
        replay.press(button);
        entered.sequence += letter(button);
    }
    entered.verified = plan.reached && replay.model.score().bars == target.bars &&
                       replay.model.score().clefs == target.clefs;
    return entered;
}

Result measure(const Tacton& target, const std::vector<NamedScore>* registry) {
    Result result{target.name};
    for (const auto& bar : target.file.score.bars) {
        for (const auto& symbol : bar.symbols) {
            result.notes += std::holds_alternative<Note>(symbol) ? 1 : 0;
            result.symbols += std::holds_alternative<Blank>(symbol) ? 0 : 1;
        }
    }
    result.alone = enter(target.file.score, nullptr);
    if (registry != nullptr) {
        auto phrases = learned_from_others(*registry, target.file);
        result.learned_from = phrases->scores();
        result.learning = enter(target.file.score, std::move(phrases));
    }
    return result;
}

double per(std::size_t presses, int count) {
    return count == 0 ? 0.0 : static_cast<double>(presses) / count;
}

struct Set {
    std::string name;
    std::vector<Result> results;
};

struct Totals {
    int notes = 0, symbols = 0;
    std::size_t alone = 0, learning = 0;
    bool verified = true;
};

Totals totals_of(const Set& set) {
    Totals totals;
    for (const auto& r : set.results) {
        totals.notes += r.notes;
        totals.symbols += r.symbols;
        totals.alone += r.alone.presses;
        totals.verified = totals.verified && r.alone.verified;
        if (r.learning) {
            totals.learning += r.learning->presses;
            totals.verified = totals.verified && r.learning->verified;
        }
    }
    return totals;
}

void print_spent(const Set& set, bool learning) {
    std::map<std::string, std::size_t> spent;
    for (const auto& r : set.results) {
        const Entered* entered = learning ? (r.learning ? &*r.learning : nullptr) : &r.alone;
        if (entered != nullptr) {
            for (const auto& [what, count] : entered->spent) {
                spent[what] += count;
            }
        }
    }
    std::printf("  presses by what they were pressed in (%s):\n",
                learning ? "with registry proposals" : "without");
    for (const auto& [what, count] : spent) {
        std::printf("    %-50s %4zu\n", what.c_str(), count);
    }
}

// Prints a set's table and totals; returns its JSON object.
std::string report(const Set& set, bool with_registry, bool sequences) {
    std::printf("\n%s\n", set.name.c_str());
    std::printf("  %-24s %5s %7s | %7s %8s %10s | %7s %8s %10s | %s\n", "score", "notes", "symbols",
                "presses", "per note", "per symbol", "learned", "per note", "per symbol",
                "checked");
    for (const auto& r : set.results) {
        const bool verified = r.alone.verified && (!r.learning || r.learning->verified);
        std::printf("  %-24s %5d %7d | %7zu %8.2f %10.2f |", r.name.c_str(), r.notes, r.symbols,
                    r.alone.presses, per(r.alone.presses, r.notes),
                    per(r.alone.presses, r.symbols));
        if (r.learning) {
            std::printf(" %7zu %8.2f %10.2f |", r.learning->presses,
                        per(r.learning->presses, r.notes), per(r.learning->presses, r.symbols));
        } else {
            std::printf(" %7s %8s %10s |", "-", "-", "-");
        }
        std::printf(" %s\n", verified ? "equal" : "DIFFERS");
        if (sequences) {
            std::printf("      %s\n", r.alone.sequence.c_str());
            if (r.learning) {
                std::printf("      %s (learned from %zu scores)\n", r.learning->sequence.c_str(),
                            r.learned_from);
            }
        }
    }
    const Totals t = totals_of(set);
    std::printf(
        "  total: %d notes, %d symbols; without registry proposals %zu presses: %.2f per "
        "note, %.2f per symbol\n",
        t.notes, t.symbols, t.alone, per(t.alone, t.notes), per(t.alone, t.symbols));
    if (with_registry) {
        std::printf(
            "  with registry proposals (leave-one-out) %zu presses: %.2f per note, %.2f "
            "per symbol\n",
            t.learning, per(t.learning, t.notes), per(t.learning, t.symbols));
    }
    print_spent(set, false);
    if (with_registry) {
        print_spent(set, true);
    }
    char json[512];
    std::snprintf(json, sizeof json,
                  "{\"set\":\"%s\",\"scores\":%zu,\"notes\":%d,\"symbols\":%d,\"presses\":%zu,"
                  "\"per_note\":%.3f,\"per_symbol\":%.3f",
                  bench::json_escape(set.name).c_str(), set.results.size(), t.notes, t.symbols,
                  t.alone, per(t.alone, t.notes), per(t.alone, t.symbols));
    std::string object = json;
    if (with_registry) {
        std::snprintf(json, sizeof json,
                      ",\"registry_presses\":%zu,\"registry_per_note\":%.3f,"
                      "\"registry_per_symbol\":%.3f",
                      t.learning, per(t.learning, t.notes), per(t.learning, t.symbols));
        object += json;
    }
    return object + (t.verified ? ",\"verified\":true}" : ",\"verified\":false}");
}

// The names of issue 26's tasks, typed from what save-as proposes there: the fewest presses
// from the name entry opening to the Select that saves.
struct NameTask {
    std::string proposal;
    std::string name;
};
const std::vector<NameTask> kNameTasks{
    {"tacton-2", "exp2"}, {"tacton-2", "confirm"}, {"ringtone-2", "my-ring"}};

std::string report_names() {
    std::printf("\nnames typed from the proposal (save as)\n");
    std::printf("  %-10s %-12s %7s  %s\n", "name", "proposal", "presses", "sequence");
    std::string json = "[";
    std::size_t total = 0;
    for (const auto& task : kNameTasks) {
        NameEntry entry;
        entry.start({task.proposal});
        const PressPlan plan = plan_name(entry, task.name);
        std::string sequence;
        for (const Button button : plan.presses) {
            entry.press(button);
            sequence += letter(button);
        }
        const bool verified = plan.reached && entry.name() == task.name;
        total += plan.presses.size();
        std::printf("  %-10s %-12s %7zu  %s%s\n", task.name.c_str(), task.proposal.c_str(),
                    plan.presses.size(), sequence.c_str(), verified ? "" : "  DIFFERS");
        json += (json.size() > 1 ? "," : "") + std::string("{\"name\":\"") + task.name +
                "\",\"presses\":" + std::to_string(plan.presses.size()) +
                ",\"verified\":" + (verified ? "true" : "false") + "}";
    }
    std::printf(
        "  total %zu presses (one character at a time through a-z 0-9 - . _: 38, 56, 47 "
        "pressed by a newcomer, issue 26)\n",
        total);
    return json + "]";
}

// Experiment 2's score task (thesis Fig. 7.5, issue 26): three bars of four quarter notes,
// strengths 9, 3, 6, 3 in each, on one string; on a new score, entered note by note, and tapped
// (the rhythm tapped on Select, then the strengths changed).
Score experiment_2() {
    const std::string bars = testing::experiment_2_bars();
    return read_score(
               "<VibScore><Title>exp2</Title><Clef id=\"lra-phone\" "
               "href=\"lra-phone.clef.xml\"/>" +
                   bars + "</VibScore>",
               "experiment-2")
        .score;
}

std::string sequence_of(const std::vector<Button>& presses) {
    std::string text;
    for (const Button button : presses) {
        text += letter(button);
    }
    return text;
}

std::string report_experiment_2() {
    const Score target = experiment_2();
    const ClefDeclaration clef{"lra-phone", "lra-phone.clef.xml"};
    const Editor fresh{EditorModel(EditorModel::blank_score("tacton-1", clef), {clef}), {}};

    const PressPlan typed = plan_presses(fresh, target);
    Editor tapped = fresh;
    std::vector<Button> to_tap{Button::back, Button::select, Button::select};  // the menu's first
    for (const Button button : to_tap) {
        tapped.press(button);
    }
    for (int k = 0; k < 12; ++k) {
        tapped.press_at(Button::select, std::chrono::milliseconds(800 * k));
    }
    tapped.press_at(Button::back, std::chrono::milliseconds(9600));
    const std::size_t taps = to_tap.size() + 12 + 1;
    const PressPlan changed = plan_changes(tapped, target);
    Editor check = tapped;
    for (const Button button : changed.presses) {
        check.press(button);
    }
    const bool verified =
        typed.reached && changed.reached && check.model.score().bars == target.bars;
    if (!verified) {
        std::fprintf(stderr, "experiment 2: typed %s, tapped %s, tapped bars %zu\n",
                     typed.reached ? "reached" : "not reached",
                     changed.reached ? "reached" : "not reached", tapped.model.score().bars.size());
    }
    std::printf(
        "\nExperiment 2's score task (Fig. 7.5, strengths 9 3 6 3), from a new score to the "
        "score entered\n");
    std::printf("  entered note by note: %zu presses  %s\n", typed.presses.size(),
                sequence_of(typed.presses).c_str());
    std::printf(
        "  tapped: %zu presses to open tap entry, tap 12 and finish, then %zu to set the "
        "strengths (%zu in all)  %s%s\n",
        taps, changed.presses.size(), taps + changed.presses.size(),
        sequence_of(changed.presses).c_str(), verified ? "" : "  DIFFERS");
    return "{\"typed\":" + std::to_string(typed.presses.size()) +
           ",\"tapped\":" + std::to_string(taps + changed.presses.size()) +
           ",\"verified\":" + (verified ? "true" : "false") + "}";
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Six-button presses needed to enter tactons in vibscore edit, without and with proposals "
        "learned from a registry of other scores (leave-one-out)."};
    std::string clefs = VIBSCORE_BENCH_CLEFS;
    std::vector<std::string> targets;
    std::optional<std::string> registry_dir;
    bool no_registry = false;
    bool sequences = false;
    app.add_option("--clefs", clefs,
                   "folder of the shipped scores: the default targets, and the default registry");
    app.add_option("--targets", targets,
                   "score files or folders of .score.xml files to enter instead of Fig. 2.3, the "
                   "notification set and the thesis' tactons");
    app.add_option("--registry", registry_dir,
                   "folder of .score.xml files to learn proposals from (each target left out); "
                   "default: --clefs when no --targets are given");
    app.add_flag("--no-registry", no_registry, "measure without registry proposals only");
    app.add_flag("--sequences", sequences, "print each press sequence (U D L R S B)");
    std::string theme = VIBSCORE_BENCH_THEME;
    app.add_option("--theme", theme,
                   "vibscore-feedback theme whose events 'use for ...' offers in the tasks");
    bool tasks_only = false;
    app.add_flag("--tasks-only", tasks_only,
                 "count only issue 26's tasks (names, Experiment 2, the newcomer's tasks)");
    CLI11_PARSE(app, argc, argv);

    const auto began = std::chrono::steady_clock::now();
    std::vector<Set> sets;
    std::vector<NamedScore> registry;
    bool with_registry = false;
    try {
        if (!no_registry && (registry_dir || targets.empty())) {
            registry = read_registry(registry_dir.value_or(clefs));
            with_registry = true;
        }
        const auto* learning = with_registry ? &registry : nullptr;
        if (tasks_only) {
            // Issue 26's tasks only, below.
        } else if (targets.empty()) {
            Set notifications{"Fig. 2.3 + notification set"};
            notifications.results.push_back(measure(
                {"fig-2.3-measure-1", {"", read_score(kFigure23, "fig-2.3").score}}, learning));
            Set thesis{"the thesis' tactons (Figs. 5.1, 5.2)"};
            for (auto [set, names] : {std::pair{&notifications, &kNotifications},
                                      std::pair{&thesis, &kThesisTactons}}) {
                for (const auto& name : *names) {
                    set->results.push_back(
                        measure(read_tacton(fs::path(clefs) / (name + ".score.xml")), learning));
                }
            }
            sets.push_back(std::move(notifications));
            sets.push_back(std::move(thesis));
        } else {
            Set given{"targets"};
            for (const auto& target : targets) {
                for (const auto& file : score_files(target)) {
                    given.results.push_back(measure(read_tacton(file), learning));
                }
            }
            sets.push_back(std::move(given));
        }
    } catch (const std::exception& error) {
        std::cerr << "editor_presses: " << error.what() << "\n";
        return 1;
    }
    if (with_registry) {
        std::printf("registry: %zu scores from %s; each target is left out of it\n",
                    registry.size(), registry_dir.value_or(clefs).c_str());
    }
    std::string json = "{\"benchmark\":\"editor_presses\",\"sets\":[";
    bool all_verified = true;
    for (std::size_t i = 0; i < sets.size(); ++i) {
        json += (i > 0 ? "," : "") + report(sets[i], with_registry, sequences);
        all_verified = all_verified && totals_of(sets[i]).verified;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    std::printf("\nplanned and replayed in %.1f s (a count: the machine does not change it)\n",
                seconds);
    const std::string names = report_names();
    const std::string experiment = report_experiment_2();
    std::string tasks;
    try {
        // Issue 26's tasks: the shipped scores are the registry the editor learns from.
        const auto events = bench::theme_events(theme);
        const auto shipped = with_registry ? registry : read_registry(clefs);
        tasks =
            "{\"without_registry\":" + bench::report_tasks(nullptr, events, clefs) +
            (no_registry ? std::string()
                         : ",\"with_registry\":" + bench::report_tasks(&shipped, events, clefs)) +
            "}";
    } catch (const std::exception& error) {
        std::cerr << "editor_presses: " << error.what() << "\n";
        return 1;
    }
    all_verified = all_verified && names.find("false") == std::string::npos &&
                   experiment.find("false") == std::string::npos &&
                   tasks.find("false") == std::string::npos;
    std::printf("%s],\"names\":%s,\"experiment_2\":%s,\"tasks\":%s,\"all_verified\":%s}\n",
                json.c_str(), names.c_str(), experiment.c_str(), tasks.c_str(),
                all_verified ? "true" : "false");
    return all_verified ? 0 : 1;
}
