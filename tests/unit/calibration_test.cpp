// The actuator calibration (issue 32): the probe's plan and its CSV, recordings read back, and
// estimates from recordings the accelerometer model makes of actuators whose true constants
// differ from the declared ones; what is refused and why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include "actuator/calibration.hpp"
#include "actuator/calibration_fit.hpp"
#include "actuator/vibration_sensor.hpp"
#include "tests/support/example_actuators.hpp"

namespace vibscore::actuator::calibration {
namespace {

using testing::example_erm;
using testing::example_lra;

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no error)";
}

bool mentions(const std::vector<std::string>& lines, const std::string& part) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) {
        return line.find(part) != std::string::npos;
    });
}

Estimate measure(const Declaration& truth, const Declaration& declared, SensorOptions sensor,
                 double delay_s = 0.004) {
    const Plan plan = make_plan(declared.kind, declared);
    return estimate(plan, record(plan, truth, sensor, delay_s, 0.05), declared);
}

SensorOptions at(double rate_hz, std::uint64_t seed = 1) {
    SensorOptions sensor;
    sensor.rate_hz = rate_hz;
    sensor.seed = seed;
    return sensor;
}

// A sensor with none of the imperfections (noise, quantisation, timestamp jitter): what is left
// of an estimate's error is the estimate's own.
SensorOptions flawless(double rate_hz, std::uint64_t seed = 1) {
    SensorOptions sensor = at(rate_hz, seed);
    sensor.noise_rms = 0.0;
    sensor.bits = 0;
    sensor.jitter_s = 0.0;
    return sensor;
}

// An ERM with these time constants.
Declaration erm(double up_s, double down_s) {
    Declaration d = example_erm();
    d.spin_up_s = up_s;
    d.spin_down_s = down_s;
    return d;
}

// Trusted (else what it said was wrong), and the LRA's resonance within the 1 % of the
// truth and its Q within 15 %.
void expect_lra_read_right(const Estimate& e, double resonance_hz, double q) {
    ASSERT_TRUE(e.trusted) << (e.problems.empty() ? "" : e.problems.front());
    EXPECT_NEAR(*e.resonance_hz, resonance_hz, resonance_hz * 0.01);
    EXPECT_NEAR(*e.q, q, q * 0.15);
}

// Trusted (else what it said was wrong), and the ERM's time constants each within `within` of
// the truth (the 15 % unless said).
void expect_erm_read_right(const Estimate& e, double spin_up_s, double spin_down_s,
                           double within = 0.15) {
    ASSERT_TRUE(e.trusted) << (e.problems.empty() ? "" : e.problems.front());
    EXPECT_NEAR(*e.spin_up_s, spin_up_s, spin_up_s * within);
    EXPECT_NEAR(*e.spin_down_s, spin_down_s, spin_down_s * within);
}

// A motor read by `sensor` (its rate, rotation, imperfections) at jittered instants, the drive
// reaching it `delay_s` late: for each recording's seed trusted, both time constants within
// `within` of the truth, and twice each stated doubt reaching it wherever the error is more than
// the half per cent that is as good as exact (bench/calibrate's worst at jittered instants).
void expect_jittered_erm_read_right(SensorOptions sensor, double spin_up_s, double spin_down_s,
                                    std::initializer_list<std::uint64_t> seeds, double within,
                                    double delay_s = 0.004) {
    sensor.jittered_sampling = true;
    for (const std::uint64_t seed : seeds) {
        sensor.seed = seed;
        SCOPED_TRACE(seed);
        const Estimate e = measure(erm(spin_up_s, spin_down_s), example_erm(), sensor, delay_s);
        ASSERT_NO_FATAL_FAILURE(expect_erm_read_right(e, spin_up_s, spin_down_s, within));
        constexpr double kExact = 0.005;
        EXPECT_LE(std::abs(*e.spin_up_s / spin_up_s - 1.0),
                  std::max(kExact, 2.0 * *e.spin_up_uncertainty))
            << seed;
        EXPECT_LE(std::abs(*e.spin_down_s / spin_down_s - 1.0),
                  std::max(kExact, 2.0 * *e.spin_down_uncertainty))
            << seed;
    }
}

// A sensor at `rate_hz` feeling a motor that turns at `full_speed_hz` at full speed.
SensorOptions feeling(double rate_hz, double full_speed_hz) {
    SensorOptions sensor = at(rate_hz);
    sensor.erm_full_speed_hz = full_speed_hz;
    return sensor;
}

TEST(CalibrationPlan, EveryProbeIsShortAndWithinFullScale) {
    std::vector<Plan> plans{make_plan(Kind::erm, std::nullopt), make_plan(Kind::lra, std::nullopt),
                            make_plan(Kind::erm, example_erm()),
                            make_plan(Kind::lra, example_lra())};
    Declaration lowest = example_lra(kResonanceHz.min), highest = example_lra(kResonanceHz.max);
    plans.push_back(make_plan(Kind::lra, lowest));
    plans.push_back(make_plan(Kind::lra, highest));
    for (const Plan& plan : plans) {
        ASSERT_GE(plan.rows.size(), 3u);
        EXPECT_EQ(plan.rows.front().t_s, 0.0);
        EXPECT_EQ(plan.rows.front().amplitude, 0.0) << "a quiet lead-in to measure the noise";
        EXPECT_EQ(plan.rows.back().amplitude, 0.0);
        EXPECT_LE(plan.duration_s(), kMaxPlanSeconds);
        EXPECT_GT(plan.duration_s(), 1.0);
        double driven_s = 0.0;
        for (std::size_t i = 0; i + 1 < plan.rows.size(); ++i) {
            if (plan.rows[i].amplitude != 0.0) {
                driven_s += plan.rows[i + 1].t_s - plan.rows[i].t_s;
            }
        }
        EXPECT_LE(driven_s, kMaxVibrationSeconds) << "the issue's 3 s of vibration in all";
        EXPECT_GT(driven_s, 0.5);
        for (std::size_t i = 0; i < plan.rows.size(); ++i) {
            EXPECT_GE(plan.rows[i].amplitude, -1.0);
            EXPECT_LE(plan.rows[i].amplitude, 1.0);
            if (i > 0) {
                EXPECT_GT(plan.rows[i].t_s, plan.rows[i - 1].t_s);
            }
        }
    }
}

TEST(CalibrationPlan, AnLrasTonesSpanTheDeclaredResonanceByAFifthEachWay) {
    const Plan plan = make_plan(Kind::lra, example_lra(200.0));
    double low = 1e9, high = 0.0;
    int tones = 0;
    for (const PlanRow& row : plan.rows) {
        if (row.amplitude != 0.0) {
            low = std::min(low, row.frequency_hz);
            high = std::max(high, row.frequency_hz);
            ++tones;
        }
    }
    EXPECT_GE(tones, 5);
    EXPECT_LE(low, 160.0);
    EXPECT_GE(high, 240.0);
    const LraRange range = lra_range(std::nullopt);
    EXPECT_LE(range.low_hz, 150.0 * 0.9) << "without a declaration: every phone LRA";
    EXPECT_GE(range.high_hz, 235.0 * 1.1);
}

TEST(CalibrationPlan, ItsCsvReadsBackTheSame) {
    const Plan plan = make_plan(Kind::lra, example_lra());
    const std::string csv = plan_csv(plan);
    EXPECT_EQ(csv.rfind("time_ns,amplitude,frequency_hz\n", 0), 0u);
    const Plan back = parse_plan_csv(csv, "plan.csv", Kind::lra);
    ASSERT_EQ(back.rows.size(), plan.rows.size());
    for (std::size_t i = 0; i < plan.rows.size(); ++i) {
        EXPECT_NEAR(back.rows[i].t_s, plan.rows[i].t_s, 1e-9);
        EXPECT_EQ(back.rows[i].amplitude, plan.rows[i].amplitude);
        EXPECT_EQ(back.rows[i].frequency_hz, plan.rows[i].frequency_hz);
    }
}

TEST(CalibrationPlan, ASimTraceCountsFromItsFirstRow) {
    const Plan plan = parse_plan_csv(
        "time_ns,amplitude,frequency_hz,response\n5000000000,0,0,0\n5100000000,1,175,0.2\n"
        "5300000000,0,0,0\n",
        "trace.csv", Kind::lra);
    ASSERT_EQ(plan.rows.size(), 3u);
    EXPECT_EQ(plan.rows[0].t_s, 0.0);
    EXPECT_NEAR(plan.rows[1].t_s, 0.1, 1e-12);
    EXPECT_NEAR(plan.duration_s(), 0.3, 1e-12);
}

TEST(CalibrationPlan, AmplitudesHoldAtFullScaleAndNotBeyond) {
    const auto with = [](const std::string& amplitude) {
        return "0,0,0\n100000000," + amplitude + ",175\n200000000,0,0\n";
    };
    EXPECT_EQ(parse_plan_csv(with("1"), "p.csv", Kind::lra).rows[1].amplitude, 1.0);
    EXPECT_EQ(parse_plan_csv(with("-1"), "p.csv", Kind::lra).rows[1].amplitude, -1.0);
    EXPECT_EQ(error_of([&] { parse_plan_csv(with("1.001"), "p.csv", Kind::lra); }),
              "p.csv:2: amplitude must be within -1..1, not 1.001");
    EXPECT_EQ(error_of([&] { parse_plan_csv(with("-1.001"), "p.csv", Kind::lra); }),
              "p.csv:2: amplitude must be within -1..1, not -1.001");
}

TEST(CalibrationPlan, MalformedLinesNameFileLineAndValue) {
    EXPECT_EQ(
        error_of([] { parse_plan_csv("0,0,0\n\n1e8,loud,175\n2e8,0,0\n", "p.csv", Kind::lra); }),
        "p.csv:3: amplitude must be a number, not 'loud'");
    EXPECT_EQ(error_of([] { parse_plan_csv("0,0,0\n1e8,1\n", "p.csv", Kind::lra); }),
              "p.csv:2: a plan row is time_ns,amplitude,frequency_hz, not '1e8,1'");
    EXPECT_EQ(error_of([] { parse_plan_csv("time,amp,f\n0,0,0\n", "p.csv", Kind::lra); }),
              "p.csv:1: the header must be time_ns,amplitude,frequency_hz, not 'time,amp,f'");
    EXPECT_EQ(error_of([] { parse_plan_csv("0,0,0\n1e8,1,-5\n2e8,0,0\n", "p.csv", Kind::lra); }),
              "p.csv:2: frequency_hz must not be negative, not -5");
    EXPECT_EQ(error_of([] { parse_plan_csv("2e8,0,0\n1e8,1,0\n3e8,0,0\n", "p.csv", Kind::erm); }),
              "p.csv:2: time_ns goes backwards (1e8)");
    EXPECT_EQ(error_of([] { parse_plan_csv("0,0,0\n1e8,1,0\n", "p.csv", Kind::erm); }),
              "p.csv: the last row must end the plan with amplitude 0, not 1");
    EXPECT_EQ(error_of([] { parse_plan_csv("0,0,0\n", "p.csv", Kind::erm); }),
              "p.csv: a plan needs at least two rows (a drive and its end)");
}

TEST(CalibrationSamples, ReadWithOrWithoutAHeader) {
    const std::vector<Sample> with =
        parse_samples_csv("t,x,y,z\n0,1,2,9.8\n0.001,-1,2.5,9.7\n", "a.csv");
    ASSERT_EQ(with.size(), 2u);
    EXPECT_EQ(with[1].t_s, 0.001);
    EXPECT_EQ(with[1].x, -1.0);
    EXPECT_EQ(with[1].z, 9.7);
    EXPECT_EQ(parse_samples_csv("0,1,2,3\n", "a.csv").size(), 1u);
}

TEST(CalibrationSamples, MalformedLinesNameFileLineAndValue) {
    EXPECT_EQ(error_of([] { parse_samples_csv("t,x,y,z\n0,1,2,3\n0.1,1,abc,3\n", "a.csv"); }),
              "a.csv:3: y must be a number, not 'abc'");
    EXPECT_EQ(error_of([] { parse_samples_csv("0,1,2\n", "a.csv"); }),
              "a.csv:1: a sample is t,x,y,z, not '0,1,2'");
    EXPECT_EQ(error_of([] { parse_samples_csv("0,1,2,3\nt,x,y,z\n", "a.csv"); }),
              "a.csv:2: t must be a number, not 't'");
    EXPECT_EQ(error_of([] { parse_samples_csv("0,1,2,nan\n", "a.csv"); }),
              "a.csv:1: z must be a number, not 'nan'");
}

TEST(VibrationSensor, ReadingsFedAsTheyComeAreTheRecordingsReadings) {
    const Plan plan = make_plan(Kind::lra, example_lra());
    const SensorOptions sensor = at(500.0, 7);
    const std::vector<Sample> whole = record(plan, example_lra(180.0, 10.0), sensor);
    VibrationSensor live(example_lra(180.0, 10.0), sensor);
    std::vector<Sample> pieces;
    for (const PlanRow& row : plan.rows) {
        const auto due = live.sample_until(row.t_s - 1e-9);
        pieces.insert(pieces.end(), due.begin(), due.end());
        live.command(row.t_s, {row.amplitude, row.frequency_hz});
    }
    const auto rest = live.sample_until(plan.duration_s());
    pieces.insert(pieces.end(), rest.begin(), rest.end());
    ASSERT_EQ(pieces.size(), whole.size());
    for (std::size_t i = 0; i < whole.size(); ++i) {
        EXPECT_EQ(pieces[i].t_s, whole[i].t_s);
        EXPECT_NEAR(pieces[i].x, whole[i].x, 1e-9);
    }
    // About 500 readings a second, and the vibration on top of gravity.
    EXPECT_NEAR(static_cast<double>(whole.size()) / plan.duration_s(), 500.0, 5.0);
}

TEST(CalibrationEstimate, FindsAnLrasResonanceAndQAt1kHz) {
    const Estimate e = measure(example_lra(168.0, 22.0), example_lra(), at(1000.0));
    ASSERT_NO_FATAL_FAILURE(expect_lra_read_right(e, 168.0, 22.0));
    EXPECT_NEAR(*e.full_scale_accel, 10.0, 1.5);
    EXPECT_NEAR(e.sample_rate_hz, 1000.0, 5.0);
    EXPECT_GT(e.snr_db, 30.0);
    EXPECT_LT(e.residual, 0.1);
}

TEST(CalibrationEstimate, FindsAnLraAboveHalfTheSamplingRateAt400Hz) {
    // 226 Hz sampled at 400 Hz looks like 174 Hz: the tones' strengths tell which it is.
    const Estimate e = measure(example_lra(226.0, 7.0), example_lra(205.0, 10.0), at(400.0, 3));
    expect_lra_read_right(e, 226.0, 7.0);
}

TEST(CalibrationEstimate, FindsAHighQLraAt400HzWithSamplesTakenAtJitteredTimes) {
    SensorOptions sensor = at(400.0, 4);
    sensor.jittered_sampling = true;
    const Estimate e = measure(example_lra(152.0, 28.0), example_lra(165.0, 20.0), sensor);
    expect_lra_read_right(e, 152.0, 28.0);
}

TEST(CalibrationErmModel, TheSpeedFollowsEachRowFromWhereThePreviousOneLeftIt) {
    // Drive from 0.1 s to 0.4 s, coast after; the model shifted 5 ms late.
    Plan plan;
    plan.kind = Kind::erm;
    plan.rows = {{0.0, 0.0, 0.0}, {0.1, 1.0, 0.0}, {0.4, 0.0, 0.0}, {0.8, 0.0, 0.0}};
    const double up = 0.04, down = 0.09, delay = 0.005;
    const std::vector<double> t{-0.01, 0.1, 0.105, 0.155, 0.405, 0.505, 0.9};
    const std::vector<double> speed = fit::erm_speeds(plan, up, down, delay, t);
    const double at_end = 1.0 - std::exp(-0.3 / up);
    EXPECT_EQ(speed[0], 0.0);  // before the plan
    EXPECT_EQ(speed[1], 0.0);
    EXPECT_EQ(speed[2], 0.0);  // the drive's first instant, 5 ms late
    EXPECT_NEAR(speed[3], 1.0 - std::exp(-0.05 / up), 1e-12);
    EXPECT_NEAR(speed[4], at_end, 1e-12);
    EXPECT_NEAR(speed[5], at_end * std::exp(-0.1 / down), 1e-12);
    EXPECT_NEAR(speed[6], at_end * std::exp(-0.495 / down), 1e-12);
}

TEST(CalibrationErmModel, ReadingsOutOfOrderGetTheSpeedsTheyGetInOrder) {
    Plan plan;
    plan.kind = Kind::erm;
    plan.rows = {
        {0.0, 0.6, 0.0}, {0.2, 0.0, 0.0}, {0.2, 1.0, 0.0}, {0.5, -0.5, 0.0}, {0.7, 0.0, 0.0}};
    std::vector<double> in_order;
    for (double t = -0.05; t < 0.9; t += 0.0037) {
        in_order.push_back(t);
    }
    std::vector<double> shuffled = in_order;
    std::reverse(shuffled.begin() + 40, shuffled.end());
    std::rotate(shuffled.begin(), shuffled.begin() + 90, shuffled.end());
    const std::vector<double> ordered = fit::erm_speeds(plan, 0.03, 0.07, -0.002, in_order);
    const std::vector<double> mixed = fit::erm_speeds(plan, 0.03, 0.07, -0.002, shuffled);
    for (std::size_t k = 0; k < shuffled.size(); ++k) {
        const auto where = std::find(in_order.begin(), in_order.end(), shuffled[k]);
        ASSERT_NE(where, in_order.end());
        EXPECT_EQ(mixed[k], ordered[static_cast<std::size_t>(where - in_order.begin())])
            << "at " << shuffled[k] << " s";
    }
}

TEST(CalibrationEstimate, FindsAnErmsTimeConstantsAt1kHz) {
    const Estimate e = measure(erm(0.055, 0.150), example_erm(), at(1000.0, 5));
    ASSERT_NO_FATAL_FAILURE(expect_erm_read_right(e, 0.055, 0.150));
    EXPECT_NEAR(*e.full_scale_accel, 10.0, 2.0);
}

TEST(CalibrationEstimate, ASlowMotorsCoastIsNotTimedShortByTheHighPassThatTakesGravityOut) {
    // A motor turning at 104 Hz at full speed slows, as it coasts, to where a high-pass of
    // ±10 ms takes much of its vibration out: timed 2.8 % short that way, with a doubt of
    // hundredths of a per cent (bench/calibrate at 1 kHz without noise, jitter or delay).
    SensorOptions sensor = flawless(1000.0, 3);
    sensor.erm_full_speed_hz = 104.0;
    const Estimate e = measure(erm(0.0533, 0.0858), example_erm(), sensor, 0.0);
    expect_erm_read_right(e, 0.0533, 0.0858, 0.005);
}

TEST(CalibrationEstimate, FindsAnErmsTimeConstantsAt400HzWithARotatingForce) {
    SensorOptions sensor = at(400.0, 6);
    sensor.erm_rotating = true;
    sensor.erm_full_speed_hz = 210.0;
    const Estimate e = measure(erm(0.025, 0.060), example_erm(), sensor);
    expect_erm_read_right(e, 0.025, 0.060);
}

TEST(CalibrationEstimate, FindsAnErmTurningAtHalfTheSamplingRateAlongOneAxisAt400Hz) {
    // At full speed 200 Hz sampled at 400 Hz, the energy of a force along one axis beats slowly
    // with the sampling: the estimate leans on the spin-up and the coast instead.
    SensorOptions sensor = at(400.0, 8);
    sensor.erm_full_speed_hz = 201.0;
    const Estimate e = measure(erm(0.030, 0.120), example_erm(), sensor);
    expect_erm_read_right(e, 0.030, 0.120);
}

TEST(CalibrationEstimate, FindsAnErmsTimeConstantsAt400HzWithSamplesTakenAtJitteredTimes) {
    // Readings taken at instants jittered by up to 1 ms fall at random places in a 200 Hz turn:
    // |vibration|^2 of a force along one axis is then noisy (bench/calibrate: up to 18 % off on
    // the spin-up); the phase-coherent envelope is not.
    expect_jittered_erm_read_right(feeling(400.0, 200.0), 0.0286, 0.129, {11u, 12u, 13u, 14u},
                                   0.15);
}

TEST(CalibrationEstimate, FindsAnLrasResonanceThroughTheSensorsOwnLowPassAt400Hz) {
    // A first-order low-pass at a quarter of the rate weakens 235 Hz 40 % more than 150 Hz: the
    // tones' strengths tilt, the ring-downs' frequency does not move.
    SensorOptions sensor = at(400.0, 21);
    sensor.low_pass_hz = 100.0;
    const Estimate e = measure(example_lra(226.0, 12.0), example_lra(210.0, 15.0), sensor);
    expect_lra_read_right(e, 226.0, 12.0);
}

TEST(CalibrationEstimate, FindsAnErmsTimeConstantsThroughTheSensorsOwnLowPassAt400Hz) {
    // A first-order low-pass at a quarter of the rate weakens a 180 Hz motor at full speed to
    // 0.49 of its strength and at half speed to 0.74: the energy grows slower than speed^4 and
    // a fit without the filter times it 20-30 % wrong (bench/calibrate).
    SensorOptions sensor = at(400.0, 31);
    sensor.low_pass_hz = 100.0;
    sensor.erm_full_speed_hz = 180.0;
    const Estimate e = measure(erm(0.040, 0.100), example_erm(), sensor);
    expect_erm_read_right(e, 0.040, 0.100);
}

TEST(VibrationSensor, TakesALowPassOfOrderOneOrTwoAndNoOther) {
    SensorOptions sensor = at(400.0);
    sensor.low_pass_hz = 100.0;
    sensor.low_pass_order = 2;
    EXPECT_NO_THROW(VibrationSensor(example_lra(), sensor));
    sensor.low_pass_order = 3;
    EXPECT_EQ(error_of([&] { VibrationSensor(example_lra(), sensor); }),
              "vibration sensor: the low-pass must be 0 or a frequency of order 1 or 2, not 100 "
              "Hz order 3");
    sensor.low_pass_order = 1;
    sensor.low_pass_hz = -1.0;
    EXPECT_NE(error_of([&] { VibrationSensor(example_lra(), sensor); }), "(no error)");
}

TEST(CalibrationEstimate, NoVibrationIsRefusedAndNothingIsMeasured) {
    SensorOptions sensor = at(1000.0);
    sensor.peak_accel = 0.0;  // the phone does not feel the actuator
    const Estimate e = measure(example_lra(), example_lra(), sensor);
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "no vibration felt")) << e.problems.front();
    EXPECT_FALSE(e.resonance_hz);
    EXPECT_TRUE(mentions(e.unmeasured, "resonance-hz"));
}

TEST(CalibrationEstimate, AVibrationLostInNoiseIsRefused) {
    SensorOptions sensor = at(1000.0);
    sensor.noise_rms = 4.0;
    sensor.bits = 0;
    const Estimate e = measure(erm(0.04, 0.08), example_erm(), sensor);
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "no vibration felt")) << e.problems.front();
}

TEST(CalibrationEstimate, ClippingIsRefused) {
    SensorOptions sensor = at(1000.0);
    sensor.range = 9.81;  // ±1 g: gravity and the vibration together go beyond it
    sensor.peak_accel = 12.0;
    const Estimate e = measure(example_lra(), example_lra(), sensor);
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "the accelerometer clipped")) << e.problems.front();
}

TEST(CalibrationEstimate, BelowTheLowestRateNothingIsGuessed) {
    // kMinSampleRateHz itself is measured; just below it, nothing.
    const Estimate at_edge =
        measure(example_lra(180.0, 12.0), example_lra(), at(kMinSampleRateHz + 0.5));
    EXPECT_TRUE(at_edge.unmeasured.empty());
    EXPECT_TRUE(at_edge.resonance_hz);
    for (const Kind kind : {Kind::lra, Kind::erm}) {
        const Declaration declared = kind == Kind::lra ? example_lra() : example_erm();
        const Estimate e = measure(declared, declared, at(kMinSampleRateHz - 4.0));
        EXPECT_FALSE(e.trusted);
        EXPECT_FALSE(e.resonance_hz || e.q || e.spin_up_s || e.spin_down_s);
        ASSERT_EQ(e.unmeasured.size(), 2u);
        EXPECT_NE(e.unmeasured[0].find("400 Hz or more"), std::string::npos) << e.unmeasured[0];
        EXPECT_TRUE(mentions(e.unmeasured, kind == Kind::lra ? "resonance-hz" : "spin-up-ms"));
    }
}

TEST(CalibrationEstimate, AResonanceBeyondWhatTheProbeCoversIsRefused) {
    // Declared 175 Hz: the probe covers up to 175 x 1.25 and the search a little beyond; a part
    // at 320 Hz is far outside, and the estimate says to declare a nearer nominal value.
    const Estimate e = measure(example_lra(320.0, 12.0), example_lra(175.0), at(1000.0));
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "at the edge of what the probe covers")) << e.problems.front();
}

TEST(CalibrationEstimate, AnErmTooSlowForTheProbeIsRefused) {
    const Estimate e = measure(erm(0.400, 0.150), example_erm(), at(1000.0));
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "beyond what the probe can time")) << e.problems.front();
}

TEST(CalibrationEstimate, TooFewReadingsAreRefused) {
    const Plan plan = make_plan(Kind::erm, std::nullopt);
    std::vector<Sample> samples = record(plan, example_erm(), at(1000.0));
    samples.resize(199);
    const Estimate e = estimate(plan, samples, std::nullopt);
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "199 readings"));
}

// An estimate whose numbers are all set and good, but for the uncertainties the test gives.
Estimate judged_erm(double up_doubt, double down_doubt, bool low_pass = false) {
    Estimate e;
    e.kind = Kind::erm;
    e.spin_up_s = 0.04;
    e.spin_down_s = 0.1;
    e.sample_rate_hz = 400.0;
    e.spin_up_uncertainty = up_doubt;
    e.spin_down_uncertainty = down_doubt;
    e.low_pass_doubt = low_pass;
    judge_confidence(e);
    return e;
}

Estimate judged_lra(double resonance_hz, double q, double rate_hz, double resonance_doubt = 0.001,
                    double q_doubt = 0.01) {
    Estimate e;
    e.kind = Kind::lra;
    e.resonance_hz = resonance_hz;
    e.q = q;
    e.sample_rate_hz = rate_hz;
    e.resonance_uncertainty = resonance_doubt;
    e.q_uncertainty = q_doubt;
    judge_confidence(e);
    return e;
}

TEST(CalibrationConfidence, AnErmTimeConstantUncertainByTheLimitIsTrustedAndNoMore) {
    EXPECT_TRUE(judged_erm(kMaxSpinUncertainty, 0.01).trusted);
    EXPECT_TRUE(judged_erm(0.01, kMaxSpinUncertainty).trusted);
    const Estimate up = judged_erm(std::nextafter(kMaxSpinUncertainty, 1.0), 0.01);
    EXPECT_FALSE(up.trusted);
    ASSERT_EQ(up.problems.size(), 1u);
    EXPECT_TRUE(mentions(up.problems, "uncertain by ±15 % (at most ±15 % trusted)"))
        << up.problems.front();
    EXPECT_TRUE(mentions(up.problems, "the probe's steps disagree")) << up.problems.front();
    EXPECT_FALSE(judged_erm(0.01, std::nextafter(kMaxSpinUncertainty, 1.0)).trusted);
}

TEST(CalibrationConfidence, AnErmDoubtedForTheSensorsLowPassSaysWhatToChange) {
    const Estimate e = judged_erm(0.2, 0.05, /*low_pass=*/true);
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "uncertain by ±40 %")) << e.problems.front();
    EXPECT_TRUE(mentions(e.problems,
                         "the accelerometer's own low-pass hides how fast the motor "
                         "turns (read at 1 kHz, or set the device's "
                         "filter_low_pass_3db_frequency"))
        << e.problems.front();
}

TEST(CalibrationConfidence, AnLrasResonanceAndQUncertainByTheLimitAreTrustedAndNoMore) {
    EXPECT_TRUE(
        judged_lra(170.0, 15.0, 1000.0, kMaxResonanceUncertainty, kMaxQUncertainty).trusted);
    const Estimate resonance =
        judged_lra(170.0, 15.0, 1000.0, std::nextafter(kMaxResonanceUncertainty, 1.0), 0.01);
    EXPECT_FALSE(resonance.trusted);
    EXPECT_TRUE(mentions(resonance.problems, "the probe's tones disagree: the resonance by ±1 %"))
        << resonance.problems.front();
    const Estimate q =
        judged_lra(170.0, 15.0, 1000.0, 0.001, std::nextafter(kMaxQUncertainty, 1.0));
    EXPECT_FALSE(q.trusted);
    EXPECT_TRUE(mentions(q.problems, "Q by ±15 % (at most ±1 % and ±15 % trusted)"))
        << q.problems.front();
}

TEST(CalibrationConfidence, AnLraRingingAtHalfTheSamplingRateHasNoMeasurableQ) {
    // 200 Hz, Q 10: a bandwidth of 20 Hz. Sampled at 403 Hz its mirror image is 3 Hz away,
    // 0.15 bandwidths: the last separation trusted.
    EXPECT_TRUE(judged_lra(200.0, 10.0, 403.0).trusted);
    EXPECT_TRUE(judged_lra(200.0, 10.0, 397.0).trusted);
    const Estimate e = judged_lra(200.0, 10.0, std::nextafter(403.0, 0.0));
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems,
                         "the resonance (200 Hz) lies at half the accelerometer's "
                         "sampling rate"))
        << e.problems.front();
    EXPECT_TRUE(mentions(e.problems, "1 kHz is best")) << e.problems.front();
    EXPECT_FALSE(judged_lra(200.0, 10.0, std::nextafter(397.0, 1000.0)).trusted);
}

TEST(CalibrationConfidence, EveryTrustedEstimateSaysHowSureItIs) {
    const Estimate lra = measure(example_lra(168.0, 22.0), example_lra(), at(1000.0));
    ASSERT_TRUE(lra.trusted) << (lra.problems.empty() ? "" : lra.problems.front());
    ASSERT_TRUE(lra.resonance_uncertainty && lra.q_uncertainty);
    EXPECT_LE(*lra.resonance_uncertainty, kMaxResonanceUncertainty);
    EXPECT_LE(*lra.q_uncertainty, kMaxQUncertainty);
    EXPECT_NE(declaration_lines(lra).find("# uncertainty: resonance-hz ±"), std::string::npos)
        << declaration_lines(lra);
    const Estimate erm_estimate = measure(erm(0.055, 0.150), example_erm(), at(1000.0, 5));
    ASSERT_TRUE(erm_estimate.trusted);
    ASSERT_TRUE(erm_estimate.spin_up_uncertainty && erm_estimate.spin_down_uncertainty);
    EXPECT_NE(declaration_lines(erm_estimate).find("# uncertainty: spin-up-ms ±"),
              std::string::npos)
        << declaration_lines(erm_estimate);
}

TEST(CalibrationConfidence, AnErmNearHalfTheRateBehindTheSensorsLowPassIsRefusedNotGuessed) {
    // bench/calibrate's worst before the trust rule: a motor at 208 Hz read at 400 Hz through a
    // second-order low-pass at 200 Hz, timed 72 % off and trusted. The fit with the filter and
    // the one without explain the recording nearly alike and disagree: neither is believed.
    SensorOptions sensor = at(400.0, 41);
    sensor.low_pass_hz = 200.0;
    sensor.low_pass_order = 2;
    sensor.erm_full_speed_hz = 208.0;
    const Estimate e = measure(erm(0.0541, 0.0473), example_erm(), sensor);
    EXPECT_FALSE(e.trusted) << *e.spin_up_s << " " << *e.spin_down_s;
    EXPECT_TRUE(mentions(e.problems,
                         "the accelerometer's own low-pass hides how fast the motor "
                         "turns"))
        << (e.problems.empty() ? "" : e.problems.front());
    // What the refusal says to do: the same motor and filter (at half the rate) read at 1 kHz.
    SensorOptions faster = at(1000.0, 41);
    faster.low_pass_hz = 500.0;
    faster.low_pass_order = 2;
    faster.erm_full_speed_hz = 208.0;
    const Estimate again = measure(erm(0.0541, 0.0473), example_erm(), faster);
    ASSERT_TRUE(again.trusted) << again.problems.front();
    EXPECT_NEAR(*again.spin_up_s, 0.0541, 0.0541 * 0.15);
    EXPECT_NEAR(*again.spin_down_s, 0.0473, 0.0473 * 0.15);
}

TEST(CalibrationConfidence, AnLraAtHalfTheRateBehindTheSensorsLowPassIsRefused) {
    // bench/calibrate: 200.8 Hz, Q 8.3 read at 401.6 Hz through a first-order low-pass at a
    // quarter of the rate came out at Q 7.32 (12 % off), trusted before the rule.
    SensorOptions sensor = at(401.6, 42);
    sensor.low_pass_hz = 100.4;
    const Estimate e = measure(example_lra(200.8, 8.3), example_lra(210.0, 10.0), sensor);
    EXPECT_FALSE(e.trusted);
    EXPECT_TRUE(mentions(e.problems, "lies at half the accelerometer's sampling rate"))
        << (e.problems.empty() ? "" : e.problems.front());
}

Estimate judged_with_mirror(double resonance_doubt) {
    // 197 Hz, Q 10, read at 400 Hz: its mirror image at 203 Hz is 0.3 bandwidths away, so its
    // decay is measurable; which of the two it is, only the tones could tell.
    Estimate e;
    e.kind = Kind::lra;
    e.resonance_hz = 197.0;
    e.q = 10.0;
    e.sample_rate_hz = 400.0;
    e.resonance_uncertainty = resonance_doubt;
    e.q_uncertainty = 0.01;
    e.mirror_hz = 203.0;
    judge_confidence(e);
    return e;
}

TEST(CalibrationConfidence, AnLraWhoseMirrorImageIsNotRuledOutIsTrustedOnlyWithinTheLimit) {
    EXPECT_TRUE(judged_with_mirror(kMaxResonanceUncertainty).trusted);
    const Estimate e = judged_with_mirror(std::nextafter(kMaxResonanceUncertainty, 1.0));
    EXPECT_FALSE(e.trusted);
    ASSERT_EQ(e.problems.size(), 1u);
    EXPECT_TRUE(mentions(e.problems,
                         "the resonance may be 197 Hz or its mirror image 203 Hz about half the "
                         "accelerometer's sampling rate (400 Hz)"))
        << e.problems.front();
    EXPECT_TRUE(mentions(e.problems, "1 kHz is best")) << e.problems.front();
}

TEST(CalibrationEstimate, AnLraJustBelowHalfTheRateIsTimedOnItsOwnSideNotAtItsMirror) {
    // bench/calibrate seed 7: 195.9 Hz, Q 11.7 read at 398.4 Hz came out at its mirror image,
    // 202.6 Hz (3.4 % off), trusted: the search had settled between the two and slid to the
    // mirror. Each side of half the rate now gets its own search, and the tones choose.
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE(seed);
        const Estimate e =
            measure(example_lra(195.9, 11.7), example_lra(190.0, 14.0), at(398.4, seed));
        expect_lra_read_right(e, 195.9, 11.7);
    }
}

TEST(CalibrationConfidence, AnErmBehindAWeakLowPassIsNeverTrustedBeyondTheTarget) {
    // bench/calibrate seed 7: motors turning at 103-110 Hz read at 400 Hz through a two-stage
    // low-pass at 200 Hz. The fit with the filter explains under 5 % more than the plain one, so
    // the plain one was kept, 15.5-15.8 % short on the spin-up, and trusted (±11-14 %).
    SensorOptions sensor = at(400.0, 51);
    sensor.low_pass_hz = 200.0;
    sensor.low_pass_order = 2;
    sensor.erm_full_speed_hz = 105.0;
    // Since the energy's high-pass no longer takes the end of each coast out
    // (erm_energy_high_pass_half), the plain fit reads the spin-up 11 % short and the spin-down
    // 11 % long, and says ±6.6 %: trusted, within the issue's ±15 %, and twice its doubt reaches
    // the truth. Either way never trusted beyond the target.
    const Estimate weak = measure(erm(0.0272, 0.0617), example_erm(), sensor);
    ASSERT_NO_FATAL_FAILURE(expect_erm_read_right(weak, 0.0272, 0.0617));
    EXPECT_LE(std::abs(std::log(*weak.spin_up_s / 0.0272)), 2.0 * *weak.spin_up_uncertainty);
    EXPECT_LE(std::abs(std::log(*weak.spin_down_s / 0.0617)), 2.0 * *weak.spin_down_uncertainty);
    // The neighbouring motor turning at 124 Hz: the filter shows, and the estimate is trusted.
    sensor.erm_full_speed_hz = 124.0;
    const Estimate shown = measure(erm(0.0506, 0.1957), example_erm(), sensor);
    expect_erm_read_right(shown, 0.0506, 0.1957);
}

TEST(CalibrationEstimate, AnErmFarAboveATwoStageLowPassIsTimedWithThatFiltersForm) {
    // bench/calibrate seed 11: a motor at 243 Hz read at 400 Hz through two first-order stages
    // at 200 Hz (its vibration at full speed 0.16 of its strength), timed 17 % short by a
    // first-order gain and trusted. The two-stage form explains more and times it right.
    SensorOptions sensor = at(400.0, 52);
    sensor.low_pass_hz = 200.0;
    sensor.low_pass_order = 2;
    sensor.erm_full_speed_hz = 243.0;
    const Estimate e = measure(erm(0.0759, 0.0810), example_erm(), sensor);
    ASSERT_TRUE(e.spin_up_s && e.spin_down_s);
    EXPECT_NEAR(*e.spin_up_s, 0.0759, 0.0759 * 0.15);
    EXPECT_NEAR(*e.spin_down_s, 0.0810, 0.0810 * 0.15);
}

TEST(CalibrationEstimate, AnErmCrossingHalfTheRateInAFastSpinUpIsTimedWithoutWhatItCannotSee) {
    // bench/calibrate seed 101: one-axis motors at 230-243 Hz spinning up in 22 ms, read at
    // 400 Hz, were timed 16-28 % slow and trusted: while the rotation passes 200 Hz the energy's
    // ripple aliases to zero and stays in the average. Those readings are now left out.
    // Timed within the issue's ±15 % each time (within 3 % here), and trusted mostly: one of
    // the four recordings is refused for the doubt what was left out leaves.
    int trusted = 0;
    for (const std::uint64_t seed : {61u, 62u, 64u, 65u}) {
        SensorOptions sensor = at(400.0, seed);
        sensor.erm_full_speed_hz = 243.0;
        const Estimate e = measure(erm(0.0228, 0.138), example_erm(), sensor);
        ASSERT_TRUE(e.spin_up_s && e.spin_down_s) << seed;
        EXPECT_NEAR(*e.spin_up_s, 0.0228, 0.0228 * 0.15) << seed;
        EXPECT_NEAR(*e.spin_down_s, 0.138, 0.138 * 0.15) << seed;
        trusted += e.trusted ? 1 : 0;
    }
    EXPECT_GE(trusted, 3);
    // A motor that never reaches half the rate (150 Hz) loses nothing.
    SensorOptions slower = at(400.0, 63);
    slower.erm_full_speed_hz = 150.0;
    const Estimate e = measure(erm(0.0228, 0.138), example_erm(), slower);
    ASSERT_TRUE(e.trusted) << (e.problems.empty() ? "" : e.problems.front());
    EXPECT_NEAR(*e.spin_up_s, 0.0228, 0.0228 * 0.15);
}

TEST(CalibrationEstimate, AnErmReadAtJitteredInstantsIsTimedOnItsOwnEnvelopesPhase) {
    // bench/calibrate seed 7: a motor at 174 Hz read at jittered instants; the envelope's phase
    // came from the energy fit (89.5 ms for a true 72.2) and the answer leaned on it: 83.8 ms,
    // 16 % off, trusted. Fitted again on the envelope its own answer predicts, it is right.
    expect_jittered_erm_read_right(feeling(400.0, 174.0), 0.0722, 0.186, {53u, 54u}, 0.15);
}

TEST(CalibrationEstimate, AnErmNearHalfTheRateReadAtJitteredInstantsIsNotTimedShort) {
    // bench/calibrated_feel seed 33: a motor at 200 Hz read at 405.8 Hz at jittered instants,
    // spinning up in 79.3 ms, was timed 71.6 ms and trusted at ±0.6 % (these seeds: 7.3 and 7.5 %
    // short at ±1 %). The high-pass that takes gravity out takes 1/9 of each reading out of itself;
    // jittered instants scatter the neighbours' phases that give it back, the more the faster
    // the mass turns, so the vibration looked weaker at full speed than on the way there.
    // Within 5 % now, and trusted.
    expect_jittered_erm_read_right(feeling(405.8, 200.0), 0.0793, 0.110, {73u, 74u}, 0.05);
}

TEST(CalibrationEstimate, AnErmsCoastReadAtJitteredInstantsIsNotTimedShort) {
    // The phase-coherent envelope fitted sinusoids of one amplitude over a few milliseconds: a
    // window's mean amplitude, which a coast's falling force leaves below its mean energy, and
    // what the high-pass takes from a changing amplitude went unmodelled. Every coast read short:
    // this motor by 1.4-1.5 % at ±0.06 % (bench/calibrate seed 32 without noise or delay). With
    // sinusoids carrying the force the speed model predicts, within 0.3 % and its stated doubt.
    SensorOptions sensor = flawless(400.0);
    sensor.jitter_s = 0.001;
    sensor.erm_full_speed_hz = 173.0;
    expect_jittered_erm_read_right(sensor, 0.0298, 0.1093, {3u, 4u}, 0.003, 0.0);
}

TEST(CalibrationEstimate, AnErmReadAtJitteredInstantsThroughTheSensorsLowPassIsNotTrustedWrong) {
    // A sensor that low-passes the vibration weakens a fast motor more than a slow one: the
    // energy grows slower than speed^4. The phase-coherent envelope's fit did not try the filter:
    // this motor was trusted with its spin-up 17 % short and its spin-down 30 % long (bench/
    // calibrate seed 32, readings at jittered instants through a first-order filter at a
    // quarter of 400 Hz: 3-5 of 12 trusted 20-28 % off). It tries it as the energy's fit does,
    // with what the answer leans on it as doubt.
    SensorOptions sensor = feeling(400.0, 176.0);
    sensor.low_pass_hz = 100.0;
    sensor.low_pass_order = 1;
    expect_jittered_erm_read_right(sensor, 0.0209, 0.0779, {5u, 6u}, 0.15);
}

TEST(CalibrationApply, ATrustedEstimateReplacesOnlyItsOwnNumbers) {
    Estimate e;
    e.kind = Kind::lra;
    e.resonance_hz = 181.5;
    e.q = 12.25;
    e.full_scale_accel = 9.0;
    e.trusted = true;
    const Declaration out = apply(example_lra(), e);
    EXPECT_EQ(out.resonance_hz, 181.5);
    EXPECT_EQ(out.q, 12.25);
    EXPECT_EQ(out.rated_drive, example_lra().rated_drive);
    EXPECT_EQ(out.brake, example_lra().brake);
    const std::string lines = declaration_lines(e);
    EXPECT_NE(lines.find("resonance-hz = 181.5\n"), std::string::npos) << lines;
    EXPECT_NE(lines.find("q = 12.2"), std::string::npos) << lines;
    EXPECT_NE(lines.find("# strength: full scale shakes the phone with 9 m/s²"), std::string::npos)
        << lines;
}

TEST(CalibrationApply, AnUntrustedEstimateOrOneOfAnotherKindChangesNothing) {
    Estimate e;
    e.kind = Kind::erm;
    e.spin_up_s = 0.05;
    e.spin_down_s = 0.1;
    e.problems = {"no vibration felt: ..."};
    EXPECT_EQ(error_of([&] { apply(example_erm(), e); }),
              "calibration: the estimate is not trusted: no vibration felt: ...");
    e.trusted = true;
    e.problems.clear();
    EXPECT_EQ(error_of([&] { apply(example_lra(), e); }),
              "calibration: the estimate is of an erm but the actuator is declared an lra");
    const Declaration out = apply(example_erm(), e);
    EXPECT_EQ(out.spin_up_s, 0.05);
    EXPECT_EQ(out.spin_down_s, 0.1);
    EXPECT_NE(declaration_lines(e).find("spin-up-ms = 50\nspin-down-ms = 100\n"),
              std::string::npos);
}

TEST(CalibrationPictures, TheMeasuredMagnitudeFollowsThePrediction) {
    const Declaration truth = erm(0.04, 0.1);
    const Plan plan = make_plan(Kind::erm, truth);
    SensorOptions sensor = at(1000.0);
    sensor.erm_rotating = true;
    const std::vector<Sample> samples = record(plan, truth, sensor);
    const Trace measured = measured_magnitude(samples, Kind::erm);
    const Trace predicted = predicted_magnitude(plan, truth, 10.0, measured.t_s);
    ASSERT_EQ(measured.magnitude.size(), predicted.magnitude.size());
    // At full speed (the end of the first step) both near the full-scale strength; at rest
    // before it both near nothing.
    const auto index_at = [&](double t) {
        return static_cast<std::size_t>(
            std::lower_bound(measured.t_s.begin(), measured.t_s.end(), t) - measured.t_s.begin());
    };
    EXPECT_NEAR(predicted.magnitude[index_at(0.45)], 10.0, 0.5);
    EXPECT_NEAR(measured.magnitude[index_at(0.45)], 10.0 * std::sqrt(2.0), 2.0);
    EXPECT_LT(measured.magnitude[index_at(0.05)], 0.5);
    EXPECT_LT(predicted.magnitude[index_at(0.05)], 0.01);
}

TEST(CalibrationPictures, ASlowMotorsCoastIsDrawnAsTheEstimateSawIt) {
    // A motor turning at 100 Hz at full speed turns at 20-32 Hz at 4-10 % of its full-scale
    // shaking, where the LRA's ±10 ms high-pass takes much of its vibration out: drawn through
    // it, that coast fell below 0.9 of the prediction (0.82 and less). The picture shows what
    // the estimate fitted (the ERM's ±40 ms), so its coasts end where the prediction does.
    const Declaration truth = erm(0.04, 0.1);
    const Plan plan = make_plan(Kind::erm, truth);
    SensorOptions sensor = flawless(1000.0);
    sensor.erm_rotating = true;
    sensor.erm_full_speed_hz = 100.0;
    const std::vector<Sample> samples = record(plan, truth, sensor);
    const Trace measured = measured_magnitude(samples, Kind::erm);
    const Trace predicted = predicted_magnitude(plan, truth, 10.0, measured.t_s);
    ASSERT_EQ(measured.magnitude.size(), predicted.magnitude.size());
    int looked = 0;
    for (std::size_t k = 1; k < predicted.magnitude.size(); ++k) {
        const double p = predicted.magnitude[k];
        if (p < predicted.magnitude[k - 1] && p >= 0.4 && p <= 1.0) {
            // (A force turning in a plane shakes along two axes: sqrt(2) of one's peak.)
            EXPECT_NEAR(measured.magnitude[k] / (std::sqrt(2.0) * p), 1.0, 0.1)
                << "at " << measured.t_s[k] << " s";
            ++looked;
        }
    }
    EXPECT_GT(looked, 20);
}

}  // namespace
}  // namespace vibscore::actuator::calibration
