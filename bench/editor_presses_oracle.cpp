// An oracle bound for registry proposals (analysis, not part of the product): for each symbol of
// each target, is the symbol to enter among the phrase book's candidates (top 1, 2, 3, all, as
// PhraseBook::candidates ranks them), or anywhere in the leave-one-out registry? And what would
// the bench's per-note figure be if every such predicted symbol cost one press (Select on the
// proposal), the others what they cost now (the cheaper of the planner's plans without and with
// the registry)? Per-symbol costs come from replaying the planner's presses on the real editor.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/press_targets.hpp"
#include "bench/report.hpp"
#include "client/editor/editor.hpp"
#include "client/editor/phrase_book.hpp"
#include "client/editor/planner/press_planner.hpp"
#include "client/editor/recurrence.hpp"
#include "client/editor/score_edits.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"

#ifndef VIBSCORE_BENCH_CLEFS
#define VIBSCORE_BENCH_CLEFS "clefs"
#endif

using namespace vibscore;
using namespace vibscore::editor;
namespace fs = std::filesystem;

namespace {

using bench::kFigure23;
using bench::kNotifications;
using bench::kThesisTactons;
using bench::read_registry;

NamedScore read_named(const fs::path& path) {
    return bench::read_tacton(path).file;
}

// A target's symbols (notes and rests) in order, with their positions and token indices.
struct Slot {
    Position at;
    int token = 0;  // index in entered_prefix's tokens (bars count one each)
    bool note = false;
};

std::vector<Slot> slots_of(const Score& target) {
    std::vector<Slot> slots;
    int token = 0;
    for (std::size_t b = 0; b < target.bars.size(); ++b) {
        ++token;  // the bar line
        for (std::size_t s = 0; s < target.bars[b].symbols.size(); ++s) {
            const auto& symbol = target.bars[b].symbols[s];
            if (!std::holds_alternative<Blank>(symbol)) {
                slots.push_back({{b, s}, token, std::holds_alternative<Note>(symbol)});
            }
            ++token;
        }
    }
    return slots;
}

struct Costs {
    std::size_t total = 0;
    std::vector<int> per_slot;  // presses spent reaching each symbol
    int overhead = 0;           // the rest: bar lines, leaving
    bool verified = false;
};

Costs costs_of(const Score& target, std::shared_ptr<const PhraseBook> phrases) {
    const ClefDeclaration& first = *target.find_clef(target.bars.front().clef);
    Editor start{EditorModel(EditorModel::blank_score(target.title, first), target.clefs), {}};
    start.model.learn_from(std::move(phrases));
    const PressPlan plan = plan_presses(start, target);
    const auto slots = slots_of(target);
    Costs costs;
    costs.total = plan.presses.size();
    costs.per_slot.assign(slots.size(), 0);
    Editor replay = start;
    int pending = 0;
    int reached = progress(replay, target);
    for (const Button button : plan.presses) {
        replay.press(button);
        ++pending;
        const int now = progress(replay, target);
        if (now > reached) {
            // Presses so far go to the last symbol token reached (a bar line alone: overhead).
            int charged = -1;
            for (std::size_t i = 0; i < slots.size(); ++i) {
                if (slots[i].token < now && slots[i].token >= reached) {
                    charged = static_cast<int>(i);
                }
            }
            if (charged >= 0) {
                costs.per_slot[static_cast<std::size_t>(charged)] += pending;
            } else {
                costs.overhead += pending;
            }
            pending = 0;
            reached = now;
        }
    }
    costs.overhead += pending;
    costs.verified = plan.reached && replay.model.score().bars == target.bars;
    return costs;
}

// The leave-one-out registry's symbols in order, for what no context decides: how often each
// occurs, and whether it occurs at all.
struct Learned {
    Symbol symbol;
    double beat = 0.0;
};

std::vector<std::vector<Learned>> phrases_of(const std::vector<NamedScore>& registry,
                                             const NamedScore& entering) {
    std::vector<std::vector<Learned>> phrases;
    for (const auto& other : registry) {
        if (other.name == entering.name || other.score.bars == entering.score.bars) {
            continue;
        }
        std::vector<Learned> phrase;
        for (const auto& bar : other.score.bars) {
            double beat = 0.0;
            for (const auto& symbol : bar.symbols) {
                if (std::holds_alternative<Blank>(symbol)) {
                    continue;
                }
                phrase.push_back({symbol, beat});
                beat += beats(length_of(symbol));
            }
        }
        if (!phrase.empty()) {
            phrases.push_back(std::move(phrase));
        }
    }
    return phrases;
}

Score prefix_of(const Score& target, Position at) {
    Score prefix = target;
    prefix.bars.resize(at.bar + 1);
    prefix.bars[at.bar].symbols.resize(at.symbol);
    return prefix;
}

// The candidate entered as proposed gives the target's symbol (ties as the neighbours they join).
bool exact(const Score& target, Position at, const Symbol& candidate) {
    Score entered = prefix_of(target, at);
    entered.bars[at.bar].symbols.push_back(candidate);
    return entered_prefix(entered, target) >= 0;
}

struct Row {
    std::string name;
    int notes = 0, symbols = 0;
    Costs alone, learning;
    // Per slot: rank (1-based) of the first exact candidate, 0 when none; likewise alike.
    std::vector<int> exact_rank, alike_rank;
    std::vector<int> frequency_rank;  // of its alike symbol among the registry's, by count
    std::vector<bool> in_registry;    // an alike symbol is anywhere in the registry
    std::vector<bool> note;
    int start_presses = 1;
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Oracle bound for registry proposals (see the source)."};
    std::string clefs = VIBSCORE_BENCH_CLEFS;
    std::string registry_dir;
    bool thesis = false;
    bool verbose = false;
    app.add_option("--clefs", clefs, "folder of the shipped scores");
    app.add_option("--registry", registry_dir, "registry folder (default: --clefs)");
    app.add_flag("--thesis", thesis, "also the thesis' 12 tactons");
    app.add_flag("--verbose", verbose, "a line per symbol");
    CLI11_PARSE(app, argc, argv);
    const auto registry = read_registry(registry_dir.empty() ? clefs : registry_dir);
    std::printf("registry: %zu scores\n", registry.size());

    std::vector<std::pair<std::string, std::vector<NamedScore>>> sets;
    sets.push_back({"Fig. 2.3 + notification set", {}});
    sets.back().second.push_back({"", read_score(kFigure23, "fig-2.3").score});
    for (const auto& name : kNotifications) {
        sets.back().second.push_back(read_named(fs::path(clefs) / (name + ".score.xml")));
    }
    if (thesis) {
        sets.push_back({"the thesis' tactons", {}});
        for (const auto& name : kThesisTactons) {
            sets.back().second.push_back(read_named(fs::path(clefs) / (name + ".score.xml")));
        }
    }
    std::string json;  // one object per set, its bounds in order
    for (const auto& [set_name, targets] : sets) {
        std::printf("\n%s\n", set_name.c_str());
        json += std::string(json.empty() ? "" : ",") + "{\"set\":\"" +
                bench::json_escape(set_name) + "\",\"bounds\":[";
        bool first_bound = true;
        std::vector<Row> rows;
        for (const auto& target : targets) {
            Row row;
            row.name = target.name.empty() ? "fig-2.3-measure-1" : target.name;
            const Score& score = target.score;
            auto book = learned_from_others(registry, target);
            row.alone = costs_of(score, nullptr);
            row.learning = costs_of(score, book);
            const auto phrases = phrases_of(registry, target);
            const auto slots = slots_of(score);
            for (const auto& slot : slots) {
                const Symbol& want = *symbol_at(score, slot.at);
                const Score prefix = prefix_of(score, slot.at);
                const auto found = book->candidates(prefix, slot.at);
                int exact_rank = 0, alike_rank = 0;
                for (std::size_t k = 0; k < found.size(); ++k) {
                    if (exact_rank == 0 && exact(score, slot.at, found[k].next)) {
                        exact_rank = static_cast<int>(k) + 1;
                    }
                    if (alike_rank == 0 && alike(found[k].next, want)) {
                        alike_rank = static_cast<int>(k) + 1;
                    }
                }
                // Context-free: the registry's symbols (alike) by how often they occur.
                std::vector<std::pair<int, const Symbol*>> counted;
                for (const auto& phrase : phrases) {
                    for (const auto& learned : phrase) {
                        auto it = std::find_if(counted.begin(), counted.end(), [&](const auto& c) {
                            return alike(*c.second, learned.symbol);
                        });
                        if (it == counted.end()) {
                            counted.push_back({1, &learned.symbol});
                        } else {
                            ++it->first;
                        }
                    }
                }
                std::stable_sort(counted.begin(), counted.end(),
                                 [](const auto& a, const auto& b) { return a.first > b.first; });
                int frequency_rank = 0;
                for (std::size_t k = 0; k < counted.size() && frequency_rank == 0; ++k) {
                    if (alike(*counted[k].second, want)) {
                        frequency_rank = static_cast<int>(k) + 1;
                    }
                }
                row.frequency_rank.push_back(frequency_rank);
                bool anywhere = false;
                for (const auto& phrase : phrases) {
                    for (const auto& learned : phrase) {
                        anywhere = anywhere || alike(learned.symbol, want);
                    }
                }
                row.exact_rank.push_back(exact_rank);
                row.alike_rank.push_back(alike_rank);
                row.in_registry.push_back(anywhere);
                row.note.push_back(slot.note);
                row.notes += slot.note ? 1 : 0;
                ++row.symbols;
                if (verbose) {
                    std::printf(
                        "  %-22s %zu:%-2zu %-4s cost %d/%d  candidates %2zu  exact rank %d  alike "
                        "rank %d  %s  best context %d\n",
                        row.name.c_str(), slot.at.bar, slot.at.symbol, slot.note ? "note" : "rest",
                        row.alone.per_slot[row.symbols - 1], row.learning.per_slot[row.symbols - 1],
                        found.size(), exact_rank, alike_rank,
                        anywhere ? "in registry" : "NOT in registry",
                        found.empty() ? 0 : found.front().context);
                }
            }
            std::printf("  %-22s presses %zu/%zu (without/with), overhead %d/%d, %s\n",
                        row.name.c_str(), row.alone.total, row.learning.total, row.alone.overhead,
                        row.learning.overhead,
                        row.alone.verified && row.learning.verified ? "equal" : "DIFFERS");
            rows.push_back(std::move(row));
        }
        int notes = 0, symbols = 0;
        std::size_t alone = 0, learning = 0;
        for (const auto& r : rows) {
            notes += r.notes;
            symbols += r.symbols;
            alone += r.alone.total;
            learning += r.learning.total;
        }
        std::printf(
            "  %d notes, %d symbols; presses without %zu (%.2f per note), with %zu (%.2f)\n", notes,
            symbols, alone, static_cast<double>(alone) / notes, learning,
            static_cast<double>(learning) / notes);
        // Symbols costing one press now (the first symbol: start + Select).
        const auto cheap_now = [](const Row& r, std::size_t i, const Costs& c) {
            return c.per_slot[i] <= (i == 0 ? 1 + r.start_presses : 1);
        };
        std::printf("  %-28s %8s %8s %14s %14s\n", "predicted by", "notes", "symbols",
                    "bound presses", "per note");
        const auto line = [&](const char* label, auto predicted) {
            int n = 0, s = 0;
            std::size_t presses = 0;
            for (const auto& r : rows) {
                presses +=
                    static_cast<std::size_t>(std::min(r.alone.overhead, r.learning.overhead));
                for (std::size_t i = 0; i < r.exact_rank.size(); ++i) {
                    const int one = i == 0 ? 1 + r.start_presses : 1;
                    int cost = std::min(r.alone.per_slot[i], r.learning.per_slot[i]);
                    if (predicted(r, i)) {
                        n += r.note[i] ? 1 : 0;
                        ++s;
                        cost = std::min(cost, one);
                    }
                    presses += static_cast<std::size_t>(cost);
                }
            }
            std::printf("  %-28s %8d %8d %14zu %14.2f\n", label, n, s, presses,
                        static_cast<double>(presses) / notes);
            char entry[256];
            std::snprintf(entry, sizeof entry,
                          "%s{\"predicted_by\":\"%s\",\"notes\":%d,\"symbols\":%d,"
                          "\"presses\":%zu,\"per_note\":%.3f}",
                          first_bound ? "" : ",", bench::json_escape(label).c_str(), n, s, presses,
                          static_cast<double>(presses) / notes);
            json += entry;
            first_bound = false;
        };
        line("(none: best of both plans)", [](const Row&, std::size_t) { return false; });
        line("one press now, without",
             [&](const Row& r, std::size_t i) { return cheap_now(r, i, r.alone); });
        line("one press now, with",
             [&](const Row& r, std::size_t i) { return cheap_now(r, i, r.learning); });
        for (int k : {1, 2, 3, 1000}) {
            char label[64];
            std::snprintf(label, sizeof label, "registry top-%s exact",
                          k == 1000 ? "all" : std::to_string(k).c_str());
            line(label, [k](const Row& r, std::size_t i) {
                return r.exact_rank[i] != 0 && r.exact_rank[i] <= k;
            });
            std::snprintf(label, sizeof label, "registry top-%s alike",
                          k == 1000 ? "all" : std::to_string(k).c_str());
            line(label, [k](const Row& r, std::size_t i) {
                return r.alike_rank[i] != 0 && r.alike_rank[i] <= k;
            });
        }
        for (int k : {1, 3, 10}) {
            char label[64];
            std::snprintf(label, sizeof label, "registry's %d most frequent", k);
            line(label, [k](const Row& r, std::size_t i) {
                return r.frequency_rank[i] != 0 && r.frequency_rank[i] <= k;
            });
        }
        line("alike anywhere in registry",
             [](const Row& r, std::size_t i) { return bool(r.in_registry[i]); });
        line("top-all exact or 1 press now", [&](const Row& r, std::size_t i) {
            return r.exact_rank[i] != 0 || cheap_now(r, i, r.alone) || cheap_now(r, i, r.learning);
        });
        line("every symbol", [](const Row&, std::size_t) { return true; });
        json += "]}";
    }
    std::printf("{\"benchmark\":\"editor_presses_oracle\",\"registry_scores\":%zu,\"sets\":[%s]}\n",
                registry.size(), json.c_str());
    return 0;
}
