// Phrases of six notes drawn at random (strength 0.3-1, up to 15 % off the resonance, 25-75 ms
// each with as long a silence after), planned for six LRAs as exact, with the part-to-part
// margins and with a calibration's, and played on bench/feel's plant of the declared LRA: the
// most any note goes above its strength and rises again after its end, against issue 32's bounds
// (5 %, 10 %). The draws beyond a bound are printed whole, to become the drive planner's tests
// (docs/performance.md, "Compensation against a wrong declaration").
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench/note_phrases.hpp"
#include "bench/report.hpp"
#include "tests/support/example_actuators.hpp"

namespace {

using vibscore::bench::json_number;
using vibscore::render::Uncertainty;

constexpr double kOvershootBound = 0.05;  // issue 32: no note more than 5 % above its strength
constexpr double kReboundBound = 0.10;    // nor above 10 % of it again once stopped

struct Lra {
    double resonance_hz, q;
};
// Across the band and the Q the issue names, where the random searches behind the planner's
// tests found their cases.
constexpr Lra kLras[] = {{150.0, 25.0}, {175.0, 8.0},  {175.0, 15.0},
                         {175.0, 25.0}, {205.0, 15.0}, {235.0, 8.0}};

struct Planning {
    const char* name;
    Uncertainty margins;
};
constexpr Planning kPlannings[] = {{"exact", Uncertainty{}},
                                   {"part-to-part", vibscore::render::kPartToPart},
                                   {"calibrated", Uncertainty{0.01, 0.15}}};

struct Row {
    double overshoot = 0.0, rebound = 0.0;
    int beyond = 0;
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Random six-note phrases planned for six LRAs (exact, part-to-part and calibrated "
        "margins) and played on bench/feel's plant: the largest overshoot and rebound against "
        "issue 32's 5 % and 10 %; prints a table, the draws beyond them and a JSON line.",
        "planner_search"};
    int draws = 50;
    std::uint64_t seed = 20261202;
    app.add_option("--draws", draws, "phrases per LRA (each planned three ways)")
        ->check(CLI::PositiveNumber);
    app.add_option("--seed", seed, "the phrases' seed");
    CLI11_PARSE(app, argc, argv);

    const auto started = std::chrono::steady_clock::now();
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> strength(0.3, 1.0), off(0.85, 1.15),
        length_s(0.025, 0.075);
    std::vector<Row> rows(std::size(kLras) * std::size(kPlannings));
    for (std::size_t l = 0; l < std::size(kLras); ++l) {
        const auto lra = vibscore::testing::example_lra(kLras[l].resonance_hz, kLras[l].q);
        for (int d = 0; d < draws; ++d) {
            vibscore::bench::Notes notes;
            for (int i = 0; i < 6; ++i) {
                // (Drawn one after the other: an argument list's order is the compiler's.)
                const double s = strength(random);
                notes.emplace_back(s, kLras[l].resonance_hz * off(random));
            }
            const double length = length_s(random);
            for (std::size_t p = 0; p < std::size(kPlannings); ++p) {
                const auto played = vibscore::bench::play_notes(
                    lra, lra, {.reverse = true, .uncertainty = kPlannings[p].margins}, notes,
                    length);
                const auto seen = vibscore::bench::artefacts(played, notes, length);
                Row& row = rows[l * std::size(kPlannings) + p];
                row.overshoot = std::max(row.overshoot, seen.overshoot);
                row.rebound = std::max(row.rebound, seen.rebound);
                if (seen.overshoot > kOvershootBound || seen.rebound > kReboundBound) {
                    ++row.beyond;
                    std::printf(
                        "beyond: %.0f Hz Q %.0f, %s, draw %d: overshoot %.2f %%, rebound "
                        "%.3f %%; length %.17g s, notes",
                        kLras[l].resonance_hz, kLras[l].q, kPlannings[p].name, d,
                        100.0 * seen.overshoot, 100.0 * seen.rebound, length);
                    for (const auto& [s, f] : notes) {
                        std::printf(" {%.17g, %.17g}", s, f);
                    }
                    std::printf("\n");
                }
            }
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    std::printf("\n%-16s %-13s %10s %10s %8s\n", "LRA", "planning", "overshoot", "rebound",
                "beyond");
    Row all;
    std::string json;
    for (std::size_t l = 0; l < std::size(kLras); ++l) {
        for (std::size_t p = 0; p < std::size(kPlannings); ++p) {
            const Row& row = rows[l * std::size(kPlannings) + p];
            char lra[32];
            std::snprintf(lra, sizeof lra, "%.0f Hz Q %.0f", kLras[l].resonance_hz, kLras[l].q);
            std::printf("%-16s %-13s %8.2f %% %8.3f %% %5d/%d\n", lra, kPlannings[p].name,
                        100.0 * row.overshoot, 100.0 * row.rebound, row.beyond, draws);
            all.overshoot = std::max(all.overshoot, row.overshoot);
            all.rebound = std::max(all.rebound, row.rebound);
            all.beyond += row.beyond;
            json += std::string(json.empty() ? "" : ",") +
                    "{\"resonance_hz\":" + json_number(kLras[l].resonance_hz) +
                    ",\"q\":" + json_number(kLras[l].q) + ",\"planning\":\"" + kPlannings[p].name +
                    "\",\"overshoot\":" + json_number(row.overshoot) +
                    ",\"rebound\":" + json_number(row.rebound) +
                    ",\"beyond\":" + std::to_string(row.beyond) + "}";
        }
    }
    const int plannings = static_cast<int>(rows.size()) * draws;
    std::printf(
        "\nall %d plannings: overshoot at most %.2f %% (bound 5), rebound at most %.3f %% "
        "(bound 10), %d beyond a bound; %.1f s on %s\n",
        plannings, 100.0 * all.overshoot, 100.0 * all.rebound, all.beyond, seconds,
        vibscore::bench::cpu_model().c_str());
    std::printf(
        "{\"bench\":\"planner_search\",\"seed\":%llu,\"draws\":%d,\"plannings\":%d,"
        "\"overshoot\":%s,\"rebound\":%s,\"beyond\":%d,\"seconds\":%s,\"rows\":[%s]}\n",
        static_cast<unsigned long long>(seed), draws, plannings, json_number(all.overshoot).c_str(),
        json_number(all.rebound).c_str(), all.beyond, json_number(seconds).c_str(), json.c_str());
    return 0;
}
