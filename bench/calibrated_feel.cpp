// What `vibscore calibrate --apply` is worth in feel (issue 32, "with measured numbers"): for
// actuators whose truth is off from the declared nominal (resonance up to ±10 %, Q and time
// constants up to ±30 %), the probe recorded by the accelerometer model
// (actuator/vibration_sensor, 400 Hz and 1 kHz, the imperfections), estimated,
// applied to the declaration; then the shipped tactons' feel figures (bench/feel's metrics and
// actuator model) with the measured numbers declared against those with the true numbers
// declared. Prints the worst and median ratio per figure and one JSON line. Recordings come from
// the model, not a phone.
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
#include "bench/feel_metrics.hpp"
#include "bench/feel_plant.hpp"
#include "bench/report.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/drive_planner.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"
#include "tests/support/example_actuators.hpp"

namespace {

using namespace vibscore;
using actuator::Declaration;
namespace cal = actuator::calibration;

constexpr double kRate = 2000.0;  // as bench/feel
constexpr double kTail = 0.5;

// The nine shipped notification tactons (as bench/feel).
const std::vector<std::string> kTactons{
    "alarm",    "failure", "notification-calendar", "notification-mail", "notification-message",
    "ringtone", "success", "touch-click",           "touch-tick"};

// A sine clef's strings inside the declared LRA's band, as bench/feel plays them.
ScoreBundle for_actuator(ScoreBundle bundle, const Declaration& declared) {
    if (declared.kind != actuator::Kind::lra) {
        return bundle;
    }
    for (auto& [id, clef] : bundle.clefs) {
        if (clef.type != ClefType::sine) {
            continue;
        }
        const double half_band = 0.9 * declared.resonance_hz / (2.0 * declared.q);
        const std::size_t n = clef.strings.size();
        for (std::size_t s = 0; s < n; ++s) {
            const double position =
                n > 1 ? static_cast<double>(s) / static_cast<double>(n - 1) : 0.5;
            clef.strings[s].frequency = declared.resonance_hz + (2.0 * position - 1.0) * half_band;
        }
    }
    return bundle;
}

// The tacton planned for `declared` (compensation on), felt on `truth`.
bench::ScoreFeel feel(const std::string& name, const ScoreBundle& bundle,
                      const Declaration& declared, const Declaration& truth) {
    const render::Performance performance(for_actuator(bundle, declared));
    render::CueAdaptation adaptation;
    adaptation.actuator = declared;
    adaptation.uncertainty = render::uncertainty_of(declared);
    adaptation.actuator->compensation = true;
    adaptation.reverse = true;
    auto drives =
        render::adapt_cues(render::cue_schedule(performance), performance.duration(), adaptation);
    std::erase_if(drives,
                  [](const render::Cue& cue) { return cue.kind != render::Cue::Kind::drive; });
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
    return bench::measure(name, bench::note_spans(performance, 1.0), written, produced,
                          produced_until, kRate);
}

// A figure's mean over its notes; INFINITY when any note never gets there.
double mean_of(const std::vector<double>& values) {
    if (values.empty()) {
        return NAN;
    }
    double sum = 0.0;
    for (const double v : values) {
        sum += v;
    }
    return sum / static_cast<double>(values.size());
}

struct Ratios {
    std::vector<double> values;       // measured-declared figure over true-declared figure
    double largest_difference = 0.0;  // |measured - true|, in the figure's unit
    void add(double measured, double truth) {
        if (std::isfinite(measured) && std::isfinite(truth)) {
            largest_difference = std::max(largest_difference, std::abs(measured - truth));
        }
        // Figures of a few milliseconds: a difference under 1 ms (two samples) is none.
        if (!std::isfinite(measured) || !std::isfinite(truth)) {
            if (std::isfinite(measured) != std::isfinite(truth)) {
                values.push_back(INFINITY);
            }
            return;
        }
        values.push_back(std::abs(measured - truth) < 1e-3 ? 1.0
                                                           : measured / std::max(truth, 1e-9));
    }
    double worst() const {
        double w = 1.0;
        for (const double v : values) {
            if (std::abs(v - 1.0) > std::abs(w - 1.0)) {
                w = v;
            }
        }
        return w;
    }
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Feel after calibrate --apply against the true numbers declared (issue 32)",
                 "calibrated_feel"};
    int count = 6;
    std::uint64_t seed = 33;
    app.add_option("--count", count, "true actuators of each kind per rate");
    app.add_option("--seed", seed, "the random actuators' and sensors' seed");
    CLI11_PARSE(app, argc, argv);

    const std::filesystem::path clefs = VIBSCORE_BENCH_CLEFS;
    std::vector<std::pair<std::string, ScoreBundle>> tactons;
    for (const auto& name : kTactons) {
        tactons.push_back({name, load_score_file(clefs / (name + ".score.xml"))});
    }
    std::printf("%-6s %6s %6s %8s %8s %8s %8s\n", "kind", "rate", "cases", "refused", "onset",
                "stop", "envelope");
    std::printf(
        "(worst ratio of the mean figure per tacton, measured numbers applied over true "
        "numbers declared; 1.00 = the same; then the largest difference of the mean figure)\n");
    std::string json;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(random); };
    for (const actuator::Kind kind : {actuator::Kind::lra, actuator::Kind::erm}) {
        for (const double rate : {400.0, 1000.0}) {
            Ratios onset, stop, envelope;
            int refused = 0;
            for (int i = 0; i < count; ++i) {
                Declaration truth =
                    kind == actuator::Kind::lra ? testing::example_lra() : testing::example_erm();
                Declaration nominal = truth;
                if (kind == actuator::Kind::lra) {
                    truth.resonance_hz = between(150.0, 235.0);
                    truth.q = 5.0 * std::pow(6.0, unit(random));
                    nominal.resonance_hz = truth.resonance_hz * between(0.9, 1.1);
                    nominal.q = truth.q * between(0.7, 1.3);
                } else {
                    truth.spin_up_s = between(0.020, 0.080);
                    truth.spin_down_s = between(0.040, 0.200);
                    nominal.spin_up_s = truth.spin_up_s * between(0.7, 1.3);
                    nominal.spin_down_s = truth.spin_down_s * between(0.7, 1.3);
                }
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
                if (!e.trusted) {
                    ++refused;
                    continue;
                }
                const Declaration measured = cal::apply(nominal, e);
                for (const auto& [name, bundle] : tactons) {
                    const bench::ScoreFeel a = feel(name, bundle, truth, truth);
                    const bench::ScoreFeel b = feel(name, bundle, measured, truth);
                    onset.add(mean_of(b.onsets_ms), mean_of(a.onsets_ms));
                    stop.add(mean_of(b.stops_ms), mean_of(a.stops_ms));
                    envelope.add(b.envelope_error, a.envelope_error);
                }
            }
            const std::string key = std::string(kind == actuator::Kind::lra ? "lra" : "erm") + " " +
                                    std::to_string(static_cast<int>(rate));
            std::printf("%-6s %6.0f %6d %8d %8.3f %8.3f %8.3f %10.2f %10.2f %10.3f\n",
                        kind == actuator::Kind::lra ? "lra" : "erm", rate, count, refused,
                        onset.worst(), stop.worst(), envelope.worst(), onset.largest_difference,
                        stop.largest_difference, envelope.largest_difference);
            std::fflush(stdout);
            json += std::string(json.empty() ? "" : ",") + "\"" + key +
                    "\":{\"cases\":" + std::to_string(count) +
                    ",\"refused\":" + std::to_string(refused) +
                    ",\"onset_worst\":" + std::to_string(onset.worst()) +
                    ",\"stop_worst\":" + std::to_string(stop.worst()) +
                    ",\"envelope_worst\":" + std::to_string(envelope.worst()) + "}";
        }
    }
    std::printf("{\"bench\":\"calibrated_feel\",\"cpu\":\"%s\",\"seed\":%llu,\"rows\":{%s}}\n",
                bench::json_escape(bench::cpu_model()).c_str(),
                static_cast<unsigned long long>(seed), json.c_str());
    return 0;
}
