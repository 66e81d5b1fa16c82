// How many of the six buttons a person presses to enter tactons in `vibscore edit`, without and
// with proposals learned from a registry of other scores. For each target score the planner
// drives the real editor (model and six-button scheme) from a new score to the target, the
// result is checked to equal the target, and the presses are counted. With a registry the
// editor learns every registry score but the target itself (leave-one-out: not the same file
// name, not the same music), as `vibscore edit` learns the daemon's registry. Prints a table,
// the totals per note and per symbol, and one JSON line.
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

#include "bench/report.hpp"
#include "client/editor/editor.hpp"
#include "client/editor/phrase_book.hpp"
#include "client/editor/press_planner.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"

#ifndef VIBSCORE_BENCH_CLEFS
#define VIBSCORE_BENCH_CLEFS "clefs"
#endif

using namespace vibscore;
using namespace vibscore::editor;
namespace fs = std::filesystem;

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

struct Tacton {
    std::string name;  // the file name without .score.xml
    NamedScore file;   // by its file name: the leave-one-out compares it with the registry's
};

Tacton read_tacton(const fs::path& path) {
    std::string name = path.filename().string();
    const std::string_view suffix = ".score.xml";
    if (name.ends_with(suffix)) {
        name.resize(name.size() - suffix.size());
    }
    return {name,
            {path.filename().string(), read_score(read_document_file(path), path.string()).score}};
}

// The .score.xml files of a folder, by name; a file stands for itself.
std::vector<fs::path> score_files(const fs::path& path) {
    if (!fs::is_directory(path)) {
        return {path};
    }
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(path)) {
        if (entry.path().filename().string().ends_with(".score.xml")) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

// Every score the registry folder holds; one that does not read is left out, and said so.
std::vector<NamedScore> read_registry(const fs::path& folder) {
    std::vector<NamedScore> registry;
    for (const auto& file : score_files(folder)) {
        try {
            registry.push_back(read_tacton(file).file);
        } catch (const std::exception& error) {
            std::cerr << "editor_presses: registry: left out: " << error.what() << "\n";
        }
    }
    return registry;
}

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
        if (targets.empty()) {
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
    std::printf("%s],\"all_verified\":%s}\n", json.c_str(), all_verified ? "true" : "false");
    return all_verified ? 0 : 1;
}
