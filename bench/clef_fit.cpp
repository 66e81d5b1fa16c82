// bench/clef_fit: how much of the strength the shipped tactons ask is never produced, through
// their written clefs and through the same clefs fitted to the actuator (render::fit_clef), on
// the feel issue's ERM and LRA, compensation off and on; and how far apart the fitted strings
// are (frequency ratio, or roughness period). Judged by bench/feel's own actuator model
// (feel_plant.hpp), not the renderer's. Prints tables and one JSON line; asserts nothing.
//
// Strength lost, per note: the part of its written strength (its peak through the written clef)
// that the produced strength never reaches while the note sounds, max(0, asked - produced peak),
// summed over the notes weighted by their length, over the asked strength summed alike.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bench/feel_plant.hpp"
#include "bench/report.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/fitting/clef_fit.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"
#include "tests/support/example_actuators.hpp"

namespace {

using vibscore::testing::example_erm;
using vibscore::testing::example_lra;

using namespace vibscore;
using actuator::Declaration;

constexpr double kRate = 2000.0;  // samples per second of every strength compared
constexpr double kTail = 0.3;

// The nine shipped notification tactons bench/feel measures.
const std::vector<std::string> kTactons{
    "alarm",    "failure", "notification-calendar", "notification-mail", "notification-message",
    "ringtone", "success", "touch-click",           "touch-tick"};

ScoreBundle fitted(const ScoreBundle& written, const Declaration& declared) {
    return bind_clefs(ParsedScore{written.score, written.where}, written.file,
                      [&](const ClefDeclaration& declaration, const SourceLocation&) {
                          return render::fit_clef(written.clefs.at(declaration.id), declared).clef;
                      });
}

std::vector<render::Cue> drives_for(const render::Performance& performance,
                                    const Declaration& declared, bool compensation) {
    render::CueAdaptation adaptation;
    adaptation.actuator = declared;
    adaptation.actuator->compensation = compensation;
    adaptation.reverse = declared.brake == actuator::Brake::reverse;
    auto cues =
        render::adapt_cues(render::cue_schedule(performance), performance.duration(), adaptation);
    std::erase_if(cues,
                  [](const render::Cue& cue) { return cue.kind != render::Cue::Kind::drive; });
    return cues;
}

struct Loss {
    double lost = 0.0, asked = 0.0;  // length-weighted sums
    int notes = 0, reached = 0;      // notes whose produced peak reaches 90 % of the asked one
    double share() const { return asked > 0.0 ? lost / asked : 0.0; }
    void add(const Loss& other) {
        lost += other.lost;
        asked += other.asked;
        notes += other.notes;
        reached += other.reached;
    }
};

// `asked`: the written bundle's performance (what the score asks); `played`: the bundle whose
// drives the actuator gets (the written or the fitted clefs).
Loss strength_lost(const render::Performance& asked, const render::Performance& played,
                   const Declaration& declared, bool compensation) {
    const auto count = static_cast<std::size_t>(
        std::ceil((std::max(asked.duration(), played.duration()) + kTail) * kRate));
    const auto produced =
        bench::Plant(declared).respond(drives_for(played, declared, compensation), kRate, count);
    const auto index = [&](double t) {
        return std::min(count, static_cast<std::size_t>(std::ceil(t * kRate - 1e-9)));
    };
    Loss loss;
    for (const auto& tone : asked.tones()) {
        double wanted = 0.0, got = 0.0;
        for (std::size_t k = index(tone.onset); k < index(tone.end()); ++k) {
            const double t = static_cast<double>(k) / kRate;
            wanted = std::max(wanted, asked.envelope_at(t));
            got = std::max(got, produced[k]);
        }
        if (!(wanted > 0.0)) {
            continue;
        }
        loss.lost += tone.duration * std::max(0.0, wanted - got);
        loss.asked += tone.duration * wanted;
        ++loss.notes;
        loss.reached += got >= 0.9 * wanted ? 1 : 0;
    }
    return loss;
}

std::string percent(double share) {
    char text[16];
    std::snprintf(text, sizeof text, "%.0f %%", share * 100.0);
    return text;
}

std::string json_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

// The fitted strings of a clef: "155->175 Hz ..." or roughness periods, and the closest
// neighbours' ratio.
std::string strings_line(const render::ClefFit& fit, double& closest) {
    std::string line = std::string(render::to_string(fit.strings)) + ":";
    closest = INFINITY;
    if (fit.strings == render::ClefFit::Strings::roughness) {
        for (std::size_t s = 0; s < fit.periods_s.size(); ++s) {
            char text[32];
            std::snprintf(text, sizeof text, " %.0f", fit.periods_s[s] * 1000.0);
            line += text;
            if (s > 0) {
                closest = std::min(closest, fit.periods_s[s - 1] / fit.periods_s[s]);
            }
        }
        line += " ms";
    } else if (fit.clef.type == ClefType::sine) {
        for (std::size_t s = 0; s < fit.clef.strings.size(); ++s) {
            char text[32];
            std::snprintf(text, sizeof text, " %.1f", fit.clef.strings[s].frequency);
            line += text;
            if (s > 0) {
                const double a = fit.clef.strings[s - 1].frequency,
                             b = fit.clef.strings[s].frequency;
                closest = std::min(closest, std::max(a, b) / std::min(a, b));
            }
        }
        line += " Hz";
    }
    if (std::isfinite(closest)) {
        char text[48];
        std::snprintf(text, sizeof text, " (closest neighbours %.2f apart)", closest);
        line += text;
    }
    return line;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Strength the shipped tactons lose through written and fitted clefs, on the feel "
        "issue's ERM and LRA (bench/feel's actuator model); prints tables and a JSON "
        "line.",
        "clef_fit"};
    std::string clefs = VIBSCORE_BENCH_CLEFS;
    app.add_option("--clefs", clefs, "the shipped clefs and scores");
    CLI11_PARSE(app, argc, argv);

    const std::vector<std::pair<std::string, Declaration>> actuators{{"erm", example_erm()},
                                                                     {"lra", example_lra()}};
    std::printf(
        "strength lost (per note: written peak the produced strength never reaches while "
        "it sounds, length-weighted)\n");
    std::printf("%-22s %-4s %12s %12s %12s %12s\n", "tacton", "act", "written/off", "written/on",
                "fitted/off", "fitted/on");
    std::map<std::string, Loss> totals;  // "erm written on" ...
    std::map<std::string, std::pair<double, double>> ranges;
    std::string json_tactons;
    for (const auto& name : kTactons) {
        const auto written = load_score_file(std::filesystem::path(clefs) / (name + ".score.xml"));
        const render::Performance asked(written);
        for (const auto& [label, declared] : actuators) {
            const render::Performance through_fitted(fitted(written, declared));
            std::printf("%-22s %-4s", name.c_str(), label.c_str());
            json_tactons += std::string(json_tactons.empty() ? "" : ",") + "{\"tacton\":\"" +
                            bench::json_escape(name) + "\",\"actuator\":\"" + label + "\"";
            for (const bool fit : {false, true}) {
                for (const bool compensation : {false, true}) {
                    const Loss loss =
                        strength_lost(asked, fit ? through_fitted : asked, declared, compensation);
                    const std::string key =
                        label + (fit ? " fitted" : " written") + (compensation ? " on" : " off");
                    totals[key].add(loss);
                    auto& range = ranges.try_emplace(key, INFINITY, 0.0).first->second;
                    range = {std::min(range.first, loss.share()),
                             std::max(range.second, loss.share())};
                    std::printf(" %12s", percent(loss.share()).c_str());
                    json_tactons += ",\"" + std::string(fit ? "fitted" : "written") + "_" +
                                    (compensation ? "on" : "off") +
                                    "\":" + json_number(loss.share());
                }
            }
            json_tactons += "}";
            std::printf("\n");
        }
    }
    std::printf(
        "\nall nine tactons (pooled; range over tactons; notes reaching 90 %% of their "
        "written peak)\n");
    std::string json_totals;
    for (const auto& [label, declared] : actuators) {
        for (const char* clef : {"written", "fitted"}) {
            for (const char* compensation : {"off", "on"}) {
                const std::string key = label + " " + clef + " " + compensation;
                const Loss& loss = totals[key];
                const auto& range = ranges[key];
                std::printf("  %-3s %-7s compensation %-3s  lost %5s  (%s..%s)  reached %d of %d\n",
                            label.c_str(), clef, compensation, percent(loss.share()).c_str(),
                            percent(range.first).c_str(), percent(range.second).c_str(),
                            loss.reached, loss.notes);
                json_totals += std::string(json_totals.empty() ? "" : ",") + "\"" + label + "_" +
                               clef + "_" + compensation +
                               "\":{\"lost\":" + json_number(loss.share()) +
                               ",\"min\":" + json_number(range.first) +
                               ",\"max\":" + json_number(range.second) +
                               ",\"reached\":" + std::to_string(loss.reached) +
                               ",\"notes\":" + std::to_string(loss.notes) + "}";
            }
        }
    }

    std::printf("\nfitted strings of the shipped clefs (string 1 first)\n");
    std::string json_strings;
    std::vector<std::filesystem::path> clef_files;
    for (const auto& entry : std::filesystem::directory_iterator(clefs)) {
        if (entry.path().filename().string().ends_with(".clef.xml")) {
            clef_files.push_back(entry.path());
        }
    }
    std::sort(clef_files.begin(), clef_files.end());
    for (const auto& path : clef_files) {
        const Clef written = load_clef_file(path);
        for (const auto& [label, declared] : actuators) {
            const auto fit = render::fit_clef(written, declared);
            double closest = INFINITY;
            const auto line = strings_line(fit, closest);
            const auto clef_name = path.filename().string();
            std::printf("  %-26s %-3s %s\n", clef_name.c_str(), label.c_str(), line.c_str());
            json_strings +=
                std::string(json_strings.empty() ? "" : ",") + "{\"clef\":\"" +
                bench::json_escape(clef_name) + "\",\"actuator\":\"" + label + "\",\"strings\":\"" +
                std::string(render::to_string(fit.strings)) +
                "\",\"closest_ratio\":" + (std::isfinite(closest) ? json_number(closest) : "null") +
                "}";
        }
    }
    std::printf(
        "{\"bench\":\"clef_fit\",\"cpu\":\"%s\",\"totals\":{%s},\"tactons\":[%s],"
        "\"strings\":[%s]}\n",
        bench::json_escape(bench::cpu_model()).c_str(), json_totals.c_str(), json_tactons.c_str(),
        json_strings.c_str());
    return 0;
}
