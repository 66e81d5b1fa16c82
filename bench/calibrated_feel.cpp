// What `vibscore calibrate --apply` is worth in feel (issue 32, "with measured numbers: after
// calibrate --apply, the feel figures of bench/feel on the true actuator are within 10 % of those
// with the true numbers declared"). For actuators whose truth is off from the declared nominal
// (resonance up to ±10 %, Q and time constants up to ±30 %), the probe is recorded by the
// accelerometer model (actuator/vibration_sensor, 400 Hz and 1 kHz, the imperfections),
// estimated, and applied as the daemon applies it (calibration::apply_as_daemon: the measured
// numbers, and an LRA's margins tightened to the measurement's). bench/feel's pieces are then
// played on the true actuator, planned
//   (b) for the measured numbers as applied,
//   (a) for the true numbers with the same tolerances as (b): what the estimate costs, alone,
//   (a') for the true numbers as exact (tolerances 0), for information,
// and bench/feel's figures pooled over the pieces (bench::pool) are compared. Prints per row the
// worst ratio b/a of each figure over the cases and the largest difference (then b/a'), and one
// JSON line; --verbose prints every case. Recordings come from the model, not a phone.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "actuator/calibration.hpp"
#include "actuator/vibration_sensor.hpp"
#include "bench/actuator_draw.hpp"
#include "bench/feel_metrics.hpp"
#include "bench/feel_pieces.hpp"
#include "bench/report.hpp"
#include "daemon/render/drive_planner.hpp"
#include "tests/support/example_actuators.hpp"

namespace {

using namespace vibscore;
using actuator::Declaration;
namespace cal = actuator::calibration;

// What the measurement resolves, as bench/feel's robustness table takes it ("worse by more than
// the measurement resolves"). Times: one sample at bench::kRate (0.5 ms). An onset or a stop is
// the first sample past a threshold, so two crossings any fraction of a sample apart can read one
// sample apart; a median moves no more than the notes' figures do, so the same holds for it.
// Envelope error: 0.005, a sum over thousands of samples whose rounding is far below it; below
// that no one feels a difference either. Counts (notes reaching 90 %, silences felt): exact.
constexpr double kTimeResolutionMs = 1000.0 / bench::kRate;
constexpr double kErrorResolution = 0.005;
constexpr double kWithin = 0.10;  // the 10 %

// bench/feel's pieces on `truth`, planned for `declared` with compensation on, within the
// declaration's own tolerances (render::uncertainty_of: what the daemon plans with).
struct Felt {
    std::vector<bench::ScoreFeel> scores;  // per piece
    bench::Pooled pooled;
};
Felt felt(const std::vector<bench::Piece>& pieces, const Declaration& declared,
          const Declaration& truth) {
    Felt out;
    for (const auto& piece : pieces) {
        out.scores.push_back(
            bench::feel(piece, declared, truth, true, render::uncertainty_of(declared)));
    }
    out.pooled = bench::pool(out.scores);
    return out;
}

// One figure compared over the cases: measured (b) against the reference (a or a').
struct Comparison {
    double resolution = 0.0;
    double worst_ratio = 1.0;             // the ratio b/a furthest from 1
    double worst_a = NAN, worst_b = NAN;  // the figures at it
    double largest_difference = 0.0;      // |b - a|, in the figure's unit (finite pairs)
    int worse = 0, better = 0;            // cases where b is more than 10 % worse / better
    bool larger_is_better = false;        // the counts; for times and error, smaller is

    // b/a, with both floored at the resolution; 1 when they are within it of each other (or both
    // never), INFINITY or 0 when only one of them is never.
    double ratio(double b, double a) const {
        if (std::isinf(a) || std::isinf(b)) {
            return std::isinf(a) == std::isinf(b) ? 1.0 : (std::isinf(b) ? INFINITY : 0.0);
        }
        if (std::abs(b - a) <= resolution + 1e-9) {
            return 1.0;
        }
        const double floor = std::max(resolution, 1e-12);
        return std::max(b, floor) / std::max(a, floor);
    }
    void add(double b, double a) {
        if (std::isnan(a) || std::isnan(b)) {
            return;  // no such figure in either (no note followed by silence, say)
        }
        if (std::isfinite(a) && std::isfinite(b)) {
            largest_difference = std::max(largest_difference, std::abs(b - a));
        }
        const double r = ratio(b, a);
        if (!(std::abs(r - 1.0) <= kWithin)) {
            ++((r > 1.0) == larger_is_better ? better : worse);
        }
        if (std::isnan(worst_a) || std::abs(r - 1.0) > std::abs(worst_ratio - 1.0)) {
            worst_ratio = r;
            worst_a = a;
            worst_b = b;
        }
    }
};

// The five figures of bench/feel's table.
struct Comparisons {
    Comparison reached{.resolution = 0.0, .larger_is_better = true},
        onset{.resolution = kTimeResolutionMs}, stop{.resolution = kTimeResolutionMs},
        felt{.resolution = 0.0, .larger_is_better = true}, error{.resolution = kErrorResolution};
    void add(const bench::Pooled& b, const bench::Pooled& a) {
        reached.add(b.reached, a.reached);
        onset.add(b.onset_ms, a.onset_ms);
        stop.add(b.stop_ms, a.stop_ms);
        felt.add(b.felt, a.felt);
        error.add(b.error, a.error);
    }
    std::vector<std::pair<const char*, const Comparison*>> all() const {
        return {{"reach90", &reached},
                {"onset", &onset},
                {"stop", &stop},
                {"silence", &felt},
                {"error", &error}};
    }
};

std::string number(double v, int decimals) {
    if (std::isnan(v)) {
        return "-";
    }
    if (std::isinf(v)) {
        return v > 0 ? "inf" : "-inf";
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    return text;
}

using bench::json_number;

// "1.06 (12.5/13.3; 1.5)": the worst ratio, the two figures at it, the largest difference.
std::string cell(const Comparison& c, int decimals) {
    return number(c.worst_ratio, 2) + " (" + number(c.worst_a, decimals) + "/" +
           number(c.worst_b, decimals) + "; " + number(c.largest_difference, decimals) + ")";
}

// "all within", or which figures are more than 10 % worse (better) in how many cases.
std::string verdict(const Comparisons& c) {
    std::string worse, better;
    for (const auto& [name, comparison] : c.all()) {
        if (comparison->worse > 0) {
            worse += std::string(worse.empty() ? "" : ", ") + name + " " +
                     std::to_string(comparison->worse) + "x";
        }
        if (comparison->better > 0) {
            better += std::string(better.empty() ? "" : ", ") + name + " " +
                      std::to_string(comparison->better) + "x";
        }
    }
    if (worse.empty() && better.empty()) {
        return "all within";
    }
    return (worse.empty() ? "" : "worse: " + worse) +
           (worse.empty() || better.empty() ? "" : "; ") +
           (better.empty() ? "" : "better: " + better);
}

void print_comparisons(const char* label, const Comparisons& c) {
    std::printf("  %-14s %-22s %-22s %-22s %-22s %-24s %s\n", label, cell(c.reached, 0).c_str(),
                cell(c.onset, 1).c_str(), cell(c.stop, 1).c_str(), cell(c.felt, 0).c_str(),
                cell(c.error, 3).c_str(), verdict(c).c_str());
}

std::string json_comparisons(const Comparisons& c) {
    std::string json = "{";
    for (const auto& [name, comparison] : c.all()) {
        json += std::string(json.size() > 1 ? "," : "") + "\"" + name +
                "\":{\"worst_ratio\":" + json_number(comparison->worst_ratio) +
                ",\"largest_difference\":" + json_number(comparison->largest_difference) +
                ",\"worse\":" + std::to_string(comparison->worse) +
                ",\"better\":" + std::to_string(comparison->better) + "}";
    }
    return json + "}";
}

std::string numbers_text(const Declaration& d) {
    char text[96];
    if (d.kind == actuator::Kind::lra) {
        std::snprintf(text, sizeof text, "%.2f Hz Q %.2f", d.resonance_hz, d.q);
    } else {
        std::snprintf(text, sizeof text, "%.1f/%.1f ms", 1000.0 * d.spin_up_s,
                      1000.0 * d.spin_down_s);
    }
    return text;
}

// How far the measured numbers are from the truth, in per cent.
std::string off_text(const Declaration& measured, const Declaration& truth) {
    const auto percent = [](double m, double t) { return 100.0 * (m / t - 1.0); };
    char text[96];
    if (truth.kind == actuator::Kind::lra) {
        std::snprintf(text, sizeof text, "resonance %+.2f %%, Q %+.1f %%",
                      percent(measured.resonance_hz, truth.resonance_hz),
                      percent(measured.q, truth.q));
    } else {
        std::snprintf(text, sizeof text, "spin-up %+.1f %%, spin-down %+.1f %%",
                      percent(measured.spin_up_s, truth.spin_up_s),
                      percent(measured.spin_down_s, truth.spin_down_s));
    }
    return text;
}

// The uncertainty the estimate states for its numbers, in per cent (a standard error: twice it
// is what calibrate promises).
std::string stated_text(const cal::Estimate& e) {
    const auto percent = [](const std::optional<double>& u) { return u ? 100.0 * *u : 0.0; };
    char text[96];
    if (e.kind == actuator::Kind::lra) {
        std::snprintf(text, sizeof text, "%.2f %%, %.1f %%", percent(e.resonance_uncertainty),
                      percent(e.q_uncertainty));
    } else {
        std::snprintf(text, sizeof text, "%.1f %%, %.1f %%", percent(e.spin_up_uncertainty),
                      percent(e.spin_down_uncertainty));
    }
    return text;
}

// --verbose: where a gap in envelope error between (a) and (b) comes from. The piece whose error
// moves most; the pooled error planned for the truth with one measured number in place of the
// true one (which number costs it); and with one true number off by about what calibrate may
// be off (ERM ±5 %; LRA resonance ±1 %, Q ±15 %: the margins), to show how steep the
// compensation is in each constant.
void print_attribution(const std::vector<bench::Piece>& pieces, const Felt& a, const Felt& b,
                       const Declaration& reference, const Declaration& measured,
                       const Declaration& truth) {
    std::size_t worst = 0;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        const auto gap = [&](std::size_t i) {
            return std::abs(b.scores[i].envelope_error - a.scores[i].envelope_error);
        };
        worst = gap(p) > gap(worst) ? p : worst;
    }
    const bench::ScoreFeel &pa = a.scores[worst], &pb = b.scores[worst];
    std::printf(
        "      piece moving most: %s error %.3f -> %.3f, rebound %.1f -> %.1f %%, overshoot %.1f "
        "-> %.1f %%, stop %s -> %s ms\n",
        pieces[worst].name.c_str(), pa.envelope_error, pb.envelope_error, 100.0 * pa.max_rebound,
        100.0 * pb.max_rebound, 100.0 * pa.max_overshoot, 100.0 * pb.max_overshoot,
        number(bench::median(pa.stops_ms), 1).c_str(),
        number(bench::median(pb.stops_ms), 1).c_str());
    const auto error_with = [&](const auto& change) {
        Declaration declared = reference;
        change(declared);
        return felt(pieces, declared, truth).pooled.error;
    };
    if (truth.kind == actuator::Kind::erm) {
        std::printf(
            "      error with only the measured spin-up %.3f, only the measured spin-down %.3f; "
            "true with spin-up x0.95/x1.05 %.3f/%.3f, spin-down x0.95/x1.05 %.3f/%.3f\n",
            error_with([&](Declaration& d) { d.spin_up_s = measured.spin_up_s; }),
            error_with([&](Declaration& d) { d.spin_down_s = measured.spin_down_s; }),
            error_with([&](Declaration& d) { d.spin_up_s *= 0.95; }),
            error_with([&](Declaration& d) { d.spin_up_s *= 1.05; }),
            error_with([&](Declaration& d) { d.spin_down_s *= 0.95; }),
            error_with([&](Declaration& d) { d.spin_down_s *= 1.05; }));
    } else {
        std::printf(
            "      error with only the measured resonance %.3f, only the measured Q %.3f; true "
            "with resonance x0.99/x1.01 %.3f/%.3f, Q x0.85/x1.15 %.3f/%.3f\n",
            error_with([&](Declaration& d) { d.resonance_hz = measured.resonance_hz; }),
            error_with([&](Declaration& d) { d.q = measured.q; }),
            error_with([&](Declaration& d) { d.resonance_hz *= 0.99; }),
            error_with([&](Declaration& d) { d.resonance_hz *= 1.01; }),
            error_with([&](Declaration& d) { d.q *= 0.85; }),
            error_with([&](Declaration& d) { d.q *= 1.15; }));
    }
}

void print_figures(const char* label, const bench::Pooled& p) {
    std::printf(
        "      %-3s reach90 %3d/%-3d onset %6s stop %6s silence %3d/%-3d error %.3f rebound "
        "%4.1f %% overshoot %4.1f %%\n",
        label, p.reached, p.notes, number(p.onset_ms, 1).c_str(), number(p.stop_ms, 1).c_str(),
        p.felt, p.silences, p.error, 100.0 * p.rebound, 100.0 * p.overshoot);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Feel after calibrate --apply against the true numbers declared (issue 32)",
                 "calibrated_feel"};
    int count = 6;
    std::uint64_t seed = 33;
    bool verbose = false;
    app.add_option("--count", count, "true actuators of each kind per rate")
        ->check(CLI::Range(1, 1000));
    app.add_option("--seed", seed, "the random actuators' and sensors' seed");
    app.add_flag("--verbose", verbose,
                 "every case: true, nominal and measured numbers, and the figures each way");
    CLI11_PARSE(app, argc, argv);

    const auto pieces = bench::pieces(VIBSCORE_BENCH_CLEFS);
    std::printf("bench/calibrated_feel on %s, seed %llu\n", bench::cpu_model().c_str(),
                static_cast<unsigned long long>(seed));
    std::printf(
        "bench/feel's figures pooled over its %zu pieces, on the true actuator, compensation on:\n"
        "(b) planned for the measured numbers as the daemon applies them, (a) for the true "
        "numbers with (b)'s tolerances,\n(a') for the true numbers as exact. Per figure: the "
        "worst ratio b/a over the cases (a/b at it; the largest |b - a|);\nequal within the "
        "resolution (%.1f ms, %.3f of error, counts exact). Second line: b/a' (for an ERM a' "
        "is a: it has no tolerances).\n",
        pieces.size(), kTimeResolutionMs, kErrorResolution);
    std::printf("%-6s %5s %5s %7s %-22s %-22s %-22s %-22s %-24s %s\n", "kind", "rate", "cases",
                "refused", "reach90", "onset ms", "stop ms", "silences felt", "envelope error",
                "within 10 %");

    std::string json;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(random); };
    for (const actuator::Kind kind : {actuator::Kind::lra, actuator::Kind::erm}) {
        for (const double rate : {400.0, 1000.0}) {
            const char* kind_name = kind == actuator::Kind::lra ? "lra" : "erm";
            Comparisons same_tolerances, exact;
            int refused = 0;
            for (int i = 0; i < count; ++i) {
                Declaration truth =
                    kind == actuator::Kind::lra ? testing::example_lra() : testing::example_erm();
                Declaration nominal = truth;
                bench::draw_actuator(kind, between, truth, nominal);
                actuator::SensorOptions sensor;
                sensor.rate_hz = rate * between(0.98, 1.02);
                sensor.peak_accel = between(4.0, 16.0);
                sensor.erm_full_speed_hz = between(100.0, 250.0);
                sensor.jittered_sampling = unit(random) < 0.5;
                sensor.seed = random();
                const cal::Plan plan = cal::make_plan(kind, nominal);
                const auto samples =
                    actuator::record(plan, truth, sensor, between(0.0, 0.015), 0.05);
                const cal::Estimate e = cal::estimate(plan, samples, nominal);
                if (verbose) {
                    std::printf("    %s %.0f #%d: true %s, nominal %s", kind_name, rate, i,
                                numbers_text(truth).c_str(), numbers_text(nominal).c_str());
                }
                if (!e.trusted) {
                    ++refused;
                    if (verbose) {
                        std::printf(", refused: %s\n",
                                    e.problems.empty() ? "?" : e.problems.front().c_str());
                    }
                    continue;
                }
                const Declaration measured = cal::apply_as_daemon(nominal, e);
                Declaration truth_alike = truth;  // (a): the truth, planned with (b)'s margins
                truth_alike.resonance_tolerance = measured.resonance_tolerance;
                truth_alike.q_tolerance = measured.q_tolerance;
                Declaration truth_exact = truth;  // (a')
                truth_exact.resonance_tolerance = 0.0;
                truth_exact.q_tolerance = 0.0;
                const Felt a = felt(pieces, truth_alike, truth);
                const Felt a_exact = felt(pieces, truth_exact, truth);
                const Felt b = felt(pieces, measured, truth);
                same_tolerances.add(b.pooled, a.pooled);
                exact.add(b.pooled, a_exact.pooled);
                if (verbose) {
                    std::printf(", measured %s (%s; stated +-%s)\n", numbers_text(measured).c_str(),
                                off_text(measured, truth).c_str(), stated_text(e).c_str());
                    std::printf("      sensor %.1f Hz%s", sensor.rate_hz,
                                sensor.jittered_sampling ? ", readings at jittered instants" : "");
                    if (kind == actuator::Kind::erm) {
                        std::printf(", the motor turning at %.0f Hz at full speed",
                                    sensor.erm_full_speed_hz);
                    }
                    std::printf("\n");
                    print_figures("a", a.pooled);
                    print_figures("a'", a_exact.pooled);
                    print_figures("b", b.pooled);
                    print_attribution(pieces, a, b, truth_alike, measured, truth);
                }
            }
            std::printf("%-6s %5.0f %5d %7d\n", kind_name, rate, count, refused);
            print_comparisons("b/a", same_tolerances);
            print_comparisons("b/a' (exact)", exact);
            std::fflush(stdout);
            json += std::string(json.empty() ? "" : ",") + "\"" + kind_name + " " +
                    std::to_string(static_cast<int>(rate)) +
                    "\":{\"cases\":" + std::to_string(count) +
                    ",\"refused\":" + std::to_string(refused) +
                    ",\"b_over_a\":" + json_comparisons(same_tolerances) +
                    ",\"b_over_a_exact\":" + json_comparisons(exact) + "}";
        }
    }
    std::printf("{\"bench\":\"calibrated_feel\",\"cpu\":\"%s\",\"seed\":%llu,\"rows\":{%s}}\n",
                bench::json_escape(bench::cpu_model()).c_str(),
                static_cast<unsigned long long>(seed), json.c_str());
    return 0;
}
