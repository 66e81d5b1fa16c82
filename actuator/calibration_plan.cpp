// The probes vibscore plays to measure an actuator (make_plan) and their CSV form.
#include <algorithm>
#include <cmath>

#include "actuator/calibration.hpp"
#include "actuator/calibration_text.hpp"
#include "common/number_text.hpp"

namespace vibscore::actuator::calibration {

using text::csv_lines;
using text::CsvLine;
using text::looks_numeric;
using text::parse_number;

namespace {

// A quiet lead-in before the first drive: the recording's noise floor (the signal-to-noise ratio
// is measured against it) and room for a recorder that starts a little late.
constexpr double kLeadInS = 0.1;

// ERM: full-scale steps. 0.35 s on brings a motor with a spin-up time constant of 80 ms within
// 1.3 % of full speed; 0.55 s off lets one with a 200 ms spin-down coast to where its vibration
// (which goes with speed squared) is 1/250 of full. The model carries the state from one step to
// the next, so neither has to settle completely. Three cycles: each rise and fall is another
// look at the time constants, and the energy of a vibration the sensor samples at random phases
// is noisy (bench/calibrate: three cycles halve the worst spin-up error of two). Six: at 400 Hz
// the spin-up was still 5-15 % off now and then with three, which costs an ERM's compensation
// 8-15 % of its envelope error per 5 % (bench/calibrated_feel, seed 33: 4 of 16 motors' feel
// beyond 10 % of the truth's with three, 1 with six; shorter or fewer cycles in the same
// 3 s were worse). 2.1 s of vibration.
constexpr double kErmOnS = 0.35;
constexpr double kErmOffS = 0.55;
constexpr int kErmCycles = 6;

// LRA: stepped tones, each followed by a free ring-down. The ring-downs give the resonance and
// the decay whatever tone drove them; the tones' steady strengths, which peak at resonance,
// tell a resonance from its alias when the sampling is slower than twice it.
constexpr int kLraTones = 7;
constexpr double kLraToneS = 0.12;  // builds a Q 30 LRA at 150 Hz (time constant 64 ms) to 85 %
constexpr double kLraRingS = 0.18;  // lets it ring down to 6 %
// With a declared resonance the tones span -25 % .. +25 % of it (parts vary by 5-10 %, mounting
// and temperature add more); without, every phone LRA the issue names (150-235 Hz) and beyond.
constexpr double kLraSpan = 0.25;
constexpr double kLraLowHz = 130.0, kLraHighHz = 270.0;

}  // namespace

LraRange lra_range(const std::optional<Declaration>& nominal) {
    if (nominal && nominal->kind == Kind::lra && nominal->resonance_hz > 0.0) {
        return {nominal->resonance_hz * (1.0 - kLraSpan), nominal->resonance_hz * (1.0 + kLraSpan)};
    }
    return {kLraLowHz, kLraHighHz};
}

Plan make_plan(Kind kind, const std::optional<Declaration>& nominal) {
    Plan plan;
    plan.kind = kind;
    plan.rows.push_back({0.0, 0.0, 0.0});
    double t = kLeadInS;
    if (kind == Kind::erm) {
        for (int cycle = 0; cycle < kErmCycles; ++cycle) {
            plan.rows.push_back({t, 1.0, 0.0});
            t += kErmOnS;
            plan.rows.push_back({t, 0.0, 0.0});
            t += kErmOffS;
        }
    } else {
        const LraRange range = lra_range(nominal);
        // Geometric steps, visited from the middle outwards alternately, so neighbouring tones
        // are far apart in frequency and one ring-down is never mistaken for the next tone.
        std::vector<double> tones;
        for (int i = 0; i < kLraTones; ++i) {
            tones.push_back(range.low_hz *
                            std::pow(range.high_hz / range.low_hz, i / (kLraTones - 1.0)));
        }
        const std::vector<int> order = {3, 0, 5, 2, 6, 1, 4};
        for (const int i : order) {
            plan.rows.push_back({t, 1.0, std::round(tones[i] * 10.0) / 10.0});
            t += kLraToneS;
            plan.rows.push_back({t, 0.0, 0.0});
            t += kLraRingS;
        }
    }
    plan.rows.push_back({t, 0.0, 0.0});  // the end of the last ring-down or coast
    return plan;
}

std::string plan_csv(const Plan& plan) {
    std::string out = "time_ns,amplitude,frequency_hz\n";
    for (const PlanRow& row : plan.rows) {
        out += std::to_string(std::llround(row.t_s * 1e9)) + "," + number_text(row.amplitude) +
               "," + number_text(row.frequency_hz) + "\n";
    }
    return out;
}

Plan parse_plan_csv(const std::string& text, const std::string& file, Kind kind) {
    Plan plan;
    plan.kind = kind;
    double first_ns = 0.0;
    double previous_s = -1.0;
    for (const CsvLine& line : csv_lines(text)) {
        const std::string where = file + ":" + std::to_string(line.number);
        if (line.fields.size() < 3) {
            throw std::invalid_argument(
                where + ": a plan row is time_ns,amplitude,frequency_hz, not '" + line.text + "'");
        }
        if (line.first && !looks_numeric(line.fields[0])) {
            if (line.fields[0] != "time_ns" || line.fields[1] != "amplitude" ||
                line.fields[2] != "frequency_hz") {
                throw std::invalid_argument(where +
                                            ": the header must be time_ns,amplitude,frequency_hz, "
                                            "not '" +
                                            line.text + "'");
            }
            continue;
        }
        const double ns = parse_number(line.fields[0], where, "time_ns");
        const double amplitude = parse_number(line.fields[1], where, "amplitude");
        const double frequency = parse_number(line.fields[2], where, "frequency_hz");
        if (amplitude < -1.0 || amplitude > 1.0) {
            throw std::invalid_argument(where + ": amplitude must be within -1..1, not " +
                                        line.fields[1]);
        }
        if (frequency < 0.0) {
            throw std::invalid_argument(where + ": frequency_hz must not be negative, not " +
                                        line.fields[2]);
        }
        if (plan.rows.empty()) {
            first_ns = ns;  // a sim trace's times are CLOCK_MONOTONIC: count from its first row
        }
        const double t = (ns - first_ns) * 1e-9;
        if (t < previous_s) {
            throw std::invalid_argument(where + ": time_ns goes backwards (" + line.fields[0] +
                                        ")");
        }
        previous_s = t;
        plan.rows.push_back({t, amplitude, frequency});
    }
    if (plan.rows.size() < 2) {
        throw std::invalid_argument(file +
                                    ": a plan needs at least two rows (a drive and its end)");
    }
    if (plan.rows.back().amplitude != 0.0) {
        throw std::invalid_argument(file +
                                    ": the last row must end the plan with amplitude 0, not " +
                                    number_text(plan.rows.back().amplitude));
    }
    return plan;
}

std::vector<Sample> parse_samples_csv(const std::string& text, const std::string& file) {
    std::vector<Sample> samples;
    for (const CsvLine& line : csv_lines(text)) {
        const std::string where = file + ":" + std::to_string(line.number);
        if (line.first && !looks_numeric(line.fields[0])) {
            continue;  // a header (t,x,y,z or the recorder's own names)
        }
        if (line.fields.size() != 4) {
            throw std::invalid_argument(where + ": a sample is t,x,y,z, not '" + line.text + "'");
        }
        Sample s;
        s.t_s = parse_number(line.fields[0], where, "t");
        s.x = parse_number(line.fields[1], where, "x");
        s.y = parse_number(line.fields[2], where, "y");
        s.z = parse_number(line.fields[3], where, "z");
        samples.push_back(s);
    }
    return samples;
}

}  // namespace vibscore::actuator::calibration
