// bench/feel: what a person feels of vibscore's playback on a real actuator, compensation off and
// on (issue 22). The ERM and the LRA the issue declares play the nine shipped notification
// tactons, ten 50 ms taps a second and a typing pattern; the drives the renderer makes for them
// go into the benchmark's own model of the actuator (bench/feel_plant: the differential
// equations integrated step by step, not the renderer's closed forms), and bench/feel_metrics
// measures the result against the written envelope. The same again for other constants, for
// actuators that differ from their declaration, and the felt latency through the real daemon
// (Play call -> 90 % of the first note's strength, read from the sim's trace). Prints tables and
// one JSON line; asserts nothing.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/feel_metrics.hpp"
#include "bench/feel_plant.hpp"
#include "bench/report.hpp"
#include "common/monotonic_clock.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"
#include "tests/support/daemon_fixture.hpp"

namespace {

using namespace vibscore;
using actuator::Declaration;
using bench::ScoreFeel;

constexpr double kRate = 2000.0;  // samples per second of every strength compared
constexpr double kTail = 0.5;     // seconds after a score's end, for the ringing

// The nine shipped notification tactons (bench/press_targets.hpp names the same set).
const std::vector<std::string> kTactons{
    "alarm",    "failure", "notification-calendar", "notification-mail", "notification-message",
    "ringtone", "success", "touch-click",           "touch-tick"};

// Ten 50 ms taps a second, and keystrokes while typing (25 ms clicks, 50-150 ms apart).
const char* const kTaps =
    "<VibScore><Title>ten taps a second</Title><Clef id=\"lra\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"lra\">"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "</Bar></VibScore>";
const char* const kTyping =
    "<VibScore><Title>typing</Title><Clef id=\"lra\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"lra\">"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"16th_dot\"/>"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"8th\"/>"
    "<Note length=\"32th\" number=\"8\" string=\"5\"/><Rest length=\"16th\"/>"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"8th_dot\"/>"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"16th\"/>"
    "<Note length=\"32th\" number=\"9\" string=\"5\"/><Rest length=\"8th\"/>"
    "</Bar></VibScore>";

struct Piece {
    std::string name;
    ScoreBundle bundle;
};

Declaration issue_erm() {
    Declaration d;
    d.kind = actuator::Kind::erm;
    d.rated_drive = 0.7;
    d.spin_up_s = 0.040;
    d.spin_down_s = 0.080;
    d.brake = actuator::Brake::reverse;
    return d;
}

Declaration issue_lra(double f0 = 175.0, double q = 15.0) {
    Declaration d;
    d.kind = actuator::Kind::lra;
    d.rated_drive = 0.7;
    d.resonance_hz = f0;
    d.q = q;
    d.brake = actuator::Brake::reverse;
    return d;
}

// A sine clef's strings moved inside an LRA's band (where it gives more than 1/sqrt(2) of its
// strength: f0 +- f0/2Q), evenly, in their order: "a clef whose strings sit inside its band".
Clef inside_band(Clef clef, const Declaration& lra) {
    const double half_band = 0.9 * lra.resonance_hz / (2.0 * lra.q);
    const std::size_t n = clef.strings.size();
    for (std::size_t s = 0; s < n; ++s) {
        const double position = n > 1 ? static_cast<double>(s) / static_cast<double>(n - 1) : 0.5;
        clef.strings[s].frequency = lra.resonance_hz + (2.0 * position - 1.0) * half_band;
    }
    return clef;
}

std::vector<Piece> pieces(const std::filesystem::path& clefs) {
    std::vector<Piece> all;
    for (const auto& name : kTactons) {
        all.push_back({name, load_score_file(clefs / (name + ".score.xml"))});
    }
    const Clef lra_phone = load_clef_file(clefs / "lra-phone.clef.xml");
    for (const auto& [name, text] : {std::pair{"taps", kTaps}, std::pair{"typing", kTyping}}) {
        all.push_back({name, bind_clefs(read_score(text, name), name,
                                        [&](const ClefDeclaration&, const SourceLocation&) {
                                            return lra_phone;
                                        })});
    }
    return all;
}

// The piece as the declared LRA plays it: every sine clef moved into its band.
ScoreBundle for_actuator(ScoreBundle bundle, const Declaration& declared) {
    if (declared.kind == actuator::Kind::lra) {
        for (auto& [id, clef] : bundle.clefs) {
            if (clef.type == ClefType::sine) {
                clef = inside_band(clef, declared);
            }
        }
    }
    return bundle;
}

std::vector<render::Cue> drives_for(const render::Performance& performance,
                                    const Declaration& declared, bool compensation) {
    render::CueAdaptation adaptation;
    adaptation.actuator = declared;
    adaptation.actuator->compensation = compensation;
    adaptation.reverse = true;
    auto cues =
        render::adapt_cues(render::cue_schedule(performance), performance.duration(), adaptation);
    std::erase_if(cues,
                  [](const render::Cue& cue) { return cue.kind != render::Cue::Kind::drive; });
    return cues;
}

// One piece on one actuator: planned for `declared`, felt on `truth`.
ScoreFeel feel(const Piece& piece, const Declaration& declared, const Declaration& truth,
               bool compensation) {
    const render::Performance performance(for_actuator(piece.bundle, declared));
    const auto drives = drives_for(performance, declared, compensation);
    const auto count =
        static_cast<std::size_t>(std::ceil((performance.duration() + kTail) * kRate));
    std::vector<double> written;
    for (std::size_t k = 0; k < count; ++k) {
        written.push_back(performance.envelope_at(static_cast<double>(k) / kRate));
    }
    const bench::Plant plant(truth);
    const auto produced = plant.respond(drives, kRate, count);
    const auto produced_until = [&](double t) {
        std::vector<render::Cue> before;
        for (const auto& cue : drives) {
            if (cue.at < t) {
                before.push_back(cue);
            }
        }
        return plant.respond(before, kRate, count);
    };
    return bench::measure(piece.name, bench::note_spans(performance, 1.0), written, produced,
                          produced_until, kRate);
}

// Everything measured of one actuator, one way.
struct Totals {
    int notes = 0, reached = 0, silences = 0, felt = 0;
    double onset_ms = 0, stop_ms = 0, error = 0;  // medians
    int taps_felt = 0, taps_gaps = 0;
    std::vector<ScoreFeel> scores;
};

Totals run(const std::vector<Piece>& all, const Declaration& declared, const Declaration& truth,
           bool compensation) {
    Totals totals;
    std::vector<double> onsets, stops, errors;
    for (const auto& piece : all) {
        ScoreFeel score = feel(piece, declared, truth, compensation);
        totals.notes += score.notes;
        totals.reached += score.reached;
        totals.silences += score.silences;
        totals.felt += score.felt;
        onsets.insert(onsets.end(), score.onsets_ms.begin(), score.onsets_ms.end());
        stops.insert(stops.end(), score.stops_ms.begin(), score.stops_ms.end());
        errors.push_back(score.envelope_error);
        if (piece.name == "taps") {
            totals.taps_felt = score.felt;
            totals.taps_gaps = score.silences;
        }
        totals.scores.push_back(std::move(score));
    }
    totals.onset_ms = bench::median(onsets);
    totals.stop_ms = bench::median(stops);
    totals.error = bench::median(errors);
    return totals;
}

std::string ms_text(double ms) {
    if (std::isnan(ms)) {
        return "-";
    }
    if (!std::isfinite(ms)) {
        return "never";
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", ms);
    return text;
}

std::string json_number(double value) {
    if (!std::isfinite(value)) {
        return "null";
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

std::string json_totals(const Totals& t) {
    std::ostringstream out;
    out << "{\"notes\":" << t.notes << ",\"reached\":" << t.reached
        << ",\"onset_ms\":" << json_number(t.onset_ms) << ",\"stop_ms\":" << json_number(t.stop_ms)
        << ",\"silences\":" << t.silences << ",\"felt\":" << t.felt
        << ",\"envelope_error\":" << json_number(t.error) << ",\"taps_felt\":" << t.taps_felt
        << ",\"taps_gaps\":" << t.taps_gaps << "}";
    return out.str();
}

struct Targets {
    std::optional<int> silences_missed_at_most;
    std::optional<int> reached_at_least;
    double onset_ms, stop_ms, error;
    bool separate_taps;
};

bool met(const Totals& t, const Targets& target) {
    bool ok =
        t.onset_ms <= target.onset_ms && t.stop_ms <= target.stop_ms && t.error <= target.error;
    if (target.silences_missed_at_most) {
        ok = ok && t.silences - t.felt <= *target.silences_missed_at_most;
    }
    if (target.reached_at_least) {
        ok = ok && t.reached >= *target.reached_at_least;
    }
    if (target.separate_taps) {
        ok = ok && t.taps_felt == t.taps_gaps;
    }
    return ok;
}

void print_row(const std::string& label, const Totals& t) {
    std::printf("  %-34s %3d/%-3d %7s %7s   %3d/%-3d %6.2f   %d/%d\n", label.c_str(), t.reached,
                t.notes, ms_text(t.onset_ms).c_str(), ms_text(t.stop_ms).c_str(), t.felt,
                t.silences, t.error, t.taps_felt, t.taps_gaps);
}

void print_header(const char* title) {
    std::printf("\n%s\n  %-34s %7s %7s %7s   %7s %6s   %s\n", title, "", "reach90", "onset", "stop",
                "silence", "error", "taps");
}

// ---- the felt latency through the real daemon ----------------------------------------------

struct Latency {
    std::vector<double> ms;
    int never = 0;
};

std::string declaration_lines(const Declaration& d, bool compensation) {
    std::string lines = "[actuator]\n";
    Declaration copy = d;
    copy.compensation = compensation;
    for (const auto& [key, value] : actuator::to_settings(copy)) {
        lines += key + " = " + value + "\n";
    }
    return lines;
}

// Plays each tacton's score inline (with the clef the actuator plays it through) and reads the
// sim's trace: the time from just before the Play call until the strength the drives make reaches
// 90 % of the first note's written peak.
class DaemonUnderTest {
  public:
    DaemonUnderTest(const Declaration& declared, bool compensation)
        : declared_(declared),
          daemon_("requests-per-second = 1000\nrequest-burst = 1000\n" +
                  declaration_lines(declared, compensation)),
          client_(daemon_.client()) {}

    void play(const Piece& piece, Latency& latency) {
        const ScoreBundle bundle = for_actuator(piece.bundle, declared_);
        const render::Performance performance(bundle);
        const auto notes = bench::note_spans(performance, 1.0);
        std::string score = write_score(bundle.score);
        std::map<std::string, std::string> clefs;
        for (const auto& declaration : bundle.score.clefs) {
            clefs[declaration.href] = write_clef(bundle.clefs.at(declaration.id));
        }
        std::map<std::string, sdbus::Variant> options{
            {"clefs", sdbus::Variant(clefs)}, {"usage", sdbus::Variant(std::string("alarm"))}};
        const std::int64_t t0 = monotonic_now_ns();
        const auto id = client_->Play(score, options);
        client_->wait_finished(id);
        std::vector<render::Cue> drives;
        for (const auto& row : daemon_.trace_rows()) {
            if (row.time_ns >= t0) {
                drives.push_back(render::drive_at(static_cast<double>(row.time_ns - t0) / 1e9,
                                                  row.amplitude, row.frequency_hz));
            }
        }
        const NoteSpanLimits first{notes.front().peak, notes.front().end};
        const double rate = 10000.0;
        const auto count = static_cast<std::size_t>((first.end_s + 0.2) * rate);
        const auto strength = bench::Plant(declared_).respond(drives, rate, count);
        for (std::size_t k = 0; k < strength.size(); ++k) {
            if (strength[k] >= 0.9 * first.peak) {
                latency.ms.push_back(static_cast<double>(k) / rate * 1000.0);
                return;
            }
        }
        ++latency.never;
    }

  private:
    struct NoteSpanLimits {
        double peak;
        double end_s;
    };
    Declaration declared_;
    testing::DaemonFixture daemon_;
    std::unique_ptr<testing::HapticsClient> client_;
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app("bench/feel: what people feel, compensation off and on (issue 22)");
    std::string clefs = VIBSCORE_BENCH_CLEFS;
    bool quick = false, no_daemon = false;
    int rounds = 5;
    app.add_option("--clefs", clefs, "the shipped clefs and scores");
    app.add_option("--rounds", rounds, "Play calls per tacton and daemon for the felt latency");
    app.add_flag("--quick", quick, "one latency round, and a smaller sweep");
    app.add_flag("--no-daemon", no_daemon, "leave out the felt latency through the daemon");
    CLI11_PARSE(app, argc, argv);
    if (quick) {
        rounds = 1;
    }
    setenv("VIBSCORE_CLEFS", clefs.c_str(), 0);
    setenv("VIBSCORED", VIBSCORE_BENCH_VIBSCORED, 0);
    setenv("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF, 0);

    const auto all = pieces(clefs);
    std::printf("bench/feel on %s\n", bench::cpu_model().c_str());
    std::printf(
        "the nine notification tactons, ten 50 ms taps a second and typing; the issue's "
        "ERM and LRA, brake reverse\n");
    std::printf(
        "reach90: notes reaching 90 %% of their written strength; onset: note start -> "
        "90 %% (median ms);\nstop: note end -> below 10 %% (median ms); silence: silences "
        "felt as a dip to half; error: median\nenvelope error; taps: gaps felt between "
        "the ten taps\n");

    const Declaration erm = issue_erm();
    const Declaration lra = issue_lra();
    const Totals erm_off = run(all, erm, erm, false), erm_on = run(all, erm, erm, true);
    const Totals lra_off = run(all, lra, lra, false), lra_on = run(all, lra, lra, true);
    print_header("the issue's actuators");
    print_row("ERM 40/80 ms, compensation off", erm_off);
    print_row("ERM 40/80 ms, compensation on", erm_on);
    print_row("LRA 175 Hz Q 15, compensation off", lra_off);
    print_row("LRA 175 Hz Q 15, compensation on", lra_on);

    const int total_silences = erm_on.silences;
    const Targets erm_targets{2, std::nullopt, 45.0, 25.0, 0.6, true};
    const Targets lra_targets{std::nullopt, (40 * lra_on.notes + 47) / 48, 35.0, 18.0, 0.55, false};
    std::printf(
        "  targets: ERM every silence but two (%d of %d), onset <= 45, stop <= 25, error "
        "<= 0.6, ten separate taps: %s\n",
        total_silences - 2, total_silences, met(erm_on, erm_targets) ? "met" : "MISSED");
    std::printf(
        "           LRA >= 40 of 48 notes reach (%d of %d), onset <= 35, stop <= 18, "
        "error <= 0.55: %s\n",
        *lra_targets.reached_at_least, lra_on.notes, met(lra_on, lra_targets) ? "met" : "MISSED");

    std::printf("\nper score, compensation off -> on (error; silences felt)\n");
    for (std::size_t i = 0; i < all.size(); ++i) {
        std::printf(
            "  %-22s ERM %.2f -> %.2f (%d -> %d of %d)   LRA %.2f -> %.2f (%d -> %d of %d)\n",
            all[i].name.c_str(), erm_off.scores[i].envelope_error, erm_on.scores[i].envelope_error,
            erm_off.scores[i].felt, erm_on.scores[i].felt, erm_on.scores[i].silences,
            lra_off.scores[i].envelope_error, lra_on.scores[i].envelope_error,
            lra_off.scores[i].felt, lra_on.scores[i].felt, lra_on.scores[i].silences);
    }

    // Other constants, each declared as it is.
    std::string sweep_json;
    print_header("other actuators, declared as they are (compensation on)");
    const std::vector<double> spin_ups =
        quick ? std::vector<double>{30, 60} : std::vector<double>{30, 40, 50, 60};
    const std::vector<double> spin_downs =
        quick ? std::vector<double>{60, 150} : std::vector<double>{60, 80, 110, 150};
    for (const double up : spin_ups) {
        for (const double down : spin_downs) {
            Declaration d = issue_erm();
            d.spin_up_s = up / 1000.0;
            d.spin_down_s = down / 1000.0;
            const Totals on = run(all, d, d, true);
            const Totals off = run(all, d, d, false);
            char label[64];
            std::snprintf(label, sizeof label, "ERM %g/%g ms (off error %.2f)", up, down,
                          off.error);
            print_row(label, on);
            sweep_json += std::string(sweep_json.empty() ? "" : ",") +
                          "{\"kind\":\"erm\",\"spin_up_ms\":" + json_number(up) +
                          ",\"spin_down_ms\":" + json_number(down) +
                          ",\"off\":" + json_totals(off) + ",\"on\":" + json_totals(on) + "}";
        }
    }
    const std::vector<double> f0s =
        quick ? std::vector<double>{150, 235} : std::vector<double>{150, 175, 205, 235};
    const std::vector<double> qs =
        quick ? std::vector<double>{8, 25} : std::vector<double>{8, 15, 20, 25};
    for (const double f0 : f0s) {
        for (const double q : qs) {
            const Declaration d = issue_lra(f0, q);
            const Totals on = run(all, d, d, true);
            const Totals off = run(all, d, d, false);
            char label[64];
            std::snprintf(label, sizeof label, "LRA %g Hz Q %g (off error %.2f)", f0, q, off.error);
            print_row(label, on);
            sweep_json += std::string(sweep_json.empty() ? "" : ",") +
                          "{\"kind\":\"lra\",\"resonance_hz\":" + json_number(f0) +
                          ",\"q\":" + json_number(q) + ",\"off\":" + json_totals(off) +
                          ",\"on\":" + json_totals(on) + "}";
        }
    }

    // Actuators that differ from what was declared for them.
    std::string mismatch_json;
    print_header("declared as the issue's, but built otherwise (off / on)");
    struct Mismatch {
        const char* label;
        Declaration declared, truth;
    };
    std::vector<Mismatch> mismatches;
    for (const auto& [up, down] : {std::pair{30.0, 60.0}, std::pair{60.0, 150.0}}) {
        Declaration truth = issue_erm();
        truth.spin_up_s = up / 1000.0;
        truth.spin_down_s = down / 1000.0;
        mismatches.push_back(
            {up < 40 ? "ERM is 30/60 ms" : "ERM is 60/150 ms", issue_erm(), truth});
    }
    mismatches.push_back({"LRA is 170 Hz Q 12", issue_lra(), issue_lra(170.0, 12.0)});
    mismatches.push_back({"LRA is 180 Hz Q 20", issue_lra(), issue_lra(180.0, 20.0)});
    for (const auto& m : mismatches) {
        const Totals off = run(all, m.declared, m.truth, false);
        const Totals on = run(all, m.declared, m.truth, true);
        print_row(std::string(m.label) + ", off", off);
        print_row(std::string(m.label) + ", on", on);
        mismatch_json += std::string(mismatch_json.empty() ? "" : ",") + "{\"truth\":\"" +
                         bench::json_escape(m.label) + "\",\"off\":" + json_totals(off) +
                         ",\"on\":" + json_totals(on) + "}";
    }

    std::string latency_json = "null";
    if (!no_daemon) {
        std::printf(
            "\nfelt latency through the real daemon (sim backend): Play call -> 90 %% of the "
            "first note's written strength\n");
        struct Under {
            const char* label;
            std::unique_ptr<DaemonUnderTest> daemon;
            Latency latency;
        };
        std::vector<Under> unders;
        unders.push_back(
            {"ERM compensation off", std::make_unique<DaemonUnderTest>(erm, false), {}});
        unders.push_back({"ERM compensation on", std::make_unique<DaemonUnderTest>(erm, true), {}});
        unders.push_back(
            {"LRA compensation off", std::make_unique<DaemonUnderTest>(lra, false), {}});
        unders.push_back({"LRA compensation on", std::make_unique<DaemonUnderTest>(lra, true), {}});
        for (int round = 0; round < rounds; ++round) {
            for (std::size_t p = 0; p < kTactons.size(); ++p) {
                for (auto& under : unders) {  // interleaved, so load affects all alike
                    under.daemon->play(all[p], under.latency);
                }
            }
        }
        latency_json = "{";
        for (std::size_t i = 0; i < unders.size(); ++i) {
            const auto& under = unders[i];
            const double p50 = bench::median(under.latency.ms);
            std::printf("  %-24s median %7s ms over %zu plays (%d first notes never reach 90 %%)\n",
                        under.label, ms_text(p50).c_str(), under.latency.ms.size(),
                        under.latency.never);
            latency_json += std::string(i ? "," : "") + "\"" + under.label +
                            "\":{\"p50_ms\":" + json_number(p50) +
                            ",\"n\":" + std::to_string(under.latency.ms.size()) +
                            ",\"never\":" + std::to_string(under.latency.never) + "}";
        }
        latency_json += "}";
    }

    std::printf(
        "\n{\"bench\":\"feel\",\"machine\":\"%s\",\"erm\":{\"off\":%s,\"on\":%s},"
        "\"lra\":{\"off\":%s,\"on\":%s},\"targets_met\":{\"erm\":%s,\"lra\":%s},"
        "\"sweep\":[%s],\"mismatch\":[%s],\"latency\":%s}\n",
        bench::json_escape(bench::cpu_model()).c_str(), json_totals(erm_off).c_str(),
        json_totals(erm_on).c_str(), json_totals(lra_off).c_str(), json_totals(lra_on).c_str(),
        met(erm_on, erm_targets) ? "true" : "false", met(lra_on, lra_targets) ? "true" : "false",
        sweep_json.c_str(), mismatch_json.c_str(), latency_json.c_str());
    return 0;
}
