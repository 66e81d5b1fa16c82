// The sim backend's accelerometer and its true actuator ([sim] true-*, accelerometer-*): what
// `vibscore calibrate` measures in the sim (docs/drivers.md, "Calibrating a board").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "common/monotonic_clock.hpp"
#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "daemon/drivers/sim_accelerometer.hpp"
#include "daemon/drivers/sim_actuator.hpp"
#include "daemon/sensors/accelerometer.hpp"

namespace vibscore {
namespace {

using ::testing::HasSubstr;

actuator::Declaration declared_lra() {
    actuator::Declaration declared;
    declared.kind = actuator::Kind::lra;
    declared.resonance_hz = 175.0;
    declared.q = 15.0;
    return declared;
}

// The vibration's largest deviation from the readings' mean along any axis.
double largest_swing(const std::vector<sensors::Reading>& readings) {
    double mean[3] = {0, 0, 0};
    for (const auto& r : readings) {
        mean[0] += r.x;
        mean[1] += r.y;
        mean[2] += r.z;
    }
    for (double& m : mean) {
        m /= static_cast<double>(readings.size());
    }
    double swing = 0.0;
    for (const auto& r : readings) {
        swing = std::max(
            {swing, std::abs(r.x - mean[0]), std::abs(r.y - mean[1]), std::abs(r.z - mean[2])});
    }
    return swing;
}

TEST(SimAccelerometer, RecordsTheDrivesItIsToldOfAtItsRateOnTheMonotonicClock) {
    actuator::SensorOptions options;
    options.rate_hz = 1000.0;
    drivers::SimAccelerometer sensor(declared_lra(), options);
    sensor.start();
    const std::int64_t started = monotonic_now_ns();
    sensor.command(started, {1.0, 0.0});
    // Readings up to now are taken when the recording stops; wait until 50 ms have passed.
    while (monotonic_now_ns() < started + 50'000'000) {
    }
    const auto readings = sensor.stop();
    ASSERT_GE(readings.size(), 45u);
    EXPECT_LE(readings.size(), 60u);
    EXPECT_GE(readings.front().t_ns, started - 2'000'000);
    EXPECT_LE(readings.back().t_ns, monotonic_now_ns() + 2'000'000);
    EXPECT_GT(largest_swing(readings), 1.0) << "full drive shakes the phone";
    EXPECT_THAT(sensor.describe(), HasSubstr("1000 Hz"));
    EXPECT_TRUE(sensor.stop().empty()) << "a stopped recording has nothing more";
}

TEST(SimAccelerometer, AtRestItFeelsOnlyGravityAndNoise) {
    actuator::SensorOptions options;
    options.noise_rms = 0.02;
    drivers::SimAccelerometer sensor(declared_lra(), options);
    sensor.start();
    const std::int64_t started = monotonic_now_ns();
    while (monotonic_now_ns() < started + 30'000'000) {
    }
    const auto readings = sensor.stop();
    ASSERT_FALSE(readings.empty());
    EXPECT_LT(largest_swing(readings), 0.2);
    const auto& first = readings.front();
    EXPECT_NEAR(std::sqrt(first.x * first.x + first.y * first.y + first.z * first.z), 9.81, 0.2);
}

TEST(SimTruth, TrueKeysSetTheSimulatedActuatorApartFromTheDeclaredOne) {
    const auto sim = drivers::make_sim_actuator(
        {{"true-resonance-hz", "168"}, {"true-q", "10"}, {"accelerometer-rate-hz", "400"}},
        declared_lra());
    const auto& model = static_cast<drivers::SimActuator&>(*sim).model();
    EXPECT_EQ(model.physics().declaration().resonance_hz, 168.0);
    EXPECT_EQ(model.physics().declaration().q, 10.0);
    ASSERT_NE(sim->accelerometer(), nullptr);
    EXPECT_THAT(sim->accelerometer()->describe(), HasSubstr("400 Hz"));
    EXPECT_THAT(sim->accelerometer()->describe(), HasSubstr("168 Hz"));
}

TEST(SimTruth, WithoutTrueKeysTheSimIsTheDeclaredActuatorAndRateZeroHasNoAccelerometer) {
    const auto sim = drivers::make_sim_actuator({{"accelerometer-rate-hz", "0"}}, declared_lra());
    const auto& model = static_cast<drivers::SimActuator&>(*sim).model();
    EXPECT_EQ(model.physics().declaration().resonance_hz, 175.0);
    EXPECT_EQ(sim->accelerometer(), nullptr);
    EXPECT_NE(drivers::make_sim_actuator({}, declared_lra())->accelerometer(), nullptr);
}

TEST(SimTruth, TrueNumbersAreHeldToTheDeclarationsLimitsAtTheirEdges) {
    EXPECT_NO_THROW(drivers::make_sim_actuator({{"true-q", "500"}}, declared_lra()));
    EXPECT_THROW(drivers::make_sim_actuator({{"true-q", "500.5"}}, declared_lra()),
                 drivers::SettingError);
    EXPECT_NO_THROW(drivers::make_sim_actuator({{"true-resonance-hz", "10"}}, declared_lra()));
    EXPECT_THROW(drivers::make_sim_actuator({{"true-resonance-hz", "9.9"}}, declared_lra()),
                 drivers::SettingError);
    EXPECT_THROW(drivers::make_sim_actuator({{"accelerometer-rate-hz", "-1"}}, declared_lra()),
                 drivers::SettingError);
}

TEST(SimTruth, TheSimsAccelerometerIsFoundThroughTheConfiguredWrapper) {
    // The host wraps every backend (common settings); calibration finds the sim's sensor through
    // it, and a backend without one has none.
    auto sim = drivers::make_sim_actuator({}, declared_lra());
    const auto sensor = sim->accelerometer();
    ASSERT_NE(sensor, nullptr);
    const drivers::ConfiguredActuator wrapped(std::move(sim), {});
    EXPECT_EQ(wrapped.accelerometer(), sensor);
}

}  // namespace
}  // namespace vibscore
