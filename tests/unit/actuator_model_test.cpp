#include "daemon/drivers/actuator_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace vibscore::drivers {
namespace {

const double kOneOverE = std::exp(-1.0);

ModelSettings erm() {
    ModelSettings settings;
    settings.kind = ActuatorKind::erm;
    return settings;
}

TEST(ActuatorModel, StillBeforeTheFirstCommand) {
    const ActuatorModel model(erm());
    EXPECT_EQ(model.response_at(0.0), 0.0);
    EXPECT_EQ(model.response_at(100.0), 0.0);
}

TEST(ActuatorModel, ErmReaches63PercentAfterOneSpinUpTimeConstant) {
    ActuatorModel model(erm());
    model.command(10.0, 1.0, 0.0);
    EXPECT_EQ(model.response_at(10.0), 0.0);
    EXPECT_NEAR(model.response_at(10.050), 1.0 - kOneOverE, 1e-9);
    EXPECT_NEAR(model.response_at(10.100), 1.0 - kOneOverE * kOneOverE, 1e-9);
    EXPECT_NEAR(model.response_at(20.0), 1.0, 1e-9);
}

TEST(ActuatorModel, ErmSpinsDownSlowerThanUp) {
    ActuatorModel model(erm());
    model.command(0.0, 1.0, 0.0);
    model.command(10.0, 0.0, 0.0);  // fully spun up by now
    EXPECT_DOUBLE_EQ(model.time_constant_s(), 0.080);
    EXPECT_NEAR(model.response_at(10.080), kOneOverE, 1e-9);

    // After the same 50 ms, spinning up covers more of the way than spinning down.
    const double down_fraction = 1.0 - model.response_at(10.050);
    ActuatorModel up(erm());
    up.command(0.0, 1.0, 0.0);
    EXPECT_GT(up.response_at(0.050), down_fraction);
}

TEST(ActuatorModel, ErmIgnoresFrequency) {
    ActuatorModel model(erm());
    model.command(0.0, 0.5, 400.0);
    EXPECT_DOUBLE_EQ(model.target(), 0.5);
    EXPECT_DOUBLE_EQ(model.steady_gain(17.0), 1.0);
}

TEST(ActuatorModel, NewCommandStartsFromTheCurrentStrength) {
    ActuatorModel model(erm());
    model.command(0.0, 1.0, 0.0);
    const double halfway = model.response_at(0.020);
    model.command(0.020, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(model.response_at(0.020), halfway);
    EXPECT_NEAR(model.response_at(0.100), halfway * std::exp(-0.080 / 0.080), 1e-12);
}

TEST(ActuatorModel, EarlierCommandTimeCountsAsTheLastOne) {
    ActuatorModel model(erm());
    model.command(1.0, 1.0, 0.0);
    model.command(0.5, 0.0, 0.0);
    EXPECT_EQ(model.response_at(1.0), 0.0);
    EXPECT_NEAR(model.response_at(1.080), 0.0, 1e-12);
}

TEST(ActuatorModel, LraGainIsOneAtResonanceAndFallsAway) {
    EXPECT_DOUBLE_EQ(ActuatorModel::lra_gain(175.0, 175.0, 8.0), 1.0);
    const double at_double = ActuatorModel::lra_gain(350.0, 175.0, 8.0);
    EXPECT_LT(at_double, 0.1);
    EXPECT_NEAR(at_double, (1.0 / 8.0) / std::sqrt(9.0 + 0.0625), 1e-12);
    EXPECT_LT(ActuatorModel::lra_gain(175.0 / 2.0, 175.0, 8.0), 0.2);
    // Within the half-power bandwidth f0/Q the gain stays above 1/√2.
    EXPECT_GT(ActuatorModel::lra_gain(175.0 * (1.0 + 0.4 / 8.0), 175.0, 8.0), 1.0 / std::sqrt(2.0));
}

TEST(ActuatorModel, LraSteadyStrengthFollowsTheGain) {
    ActuatorModel model;
    model.command(0.0, 0.8, 350.0);
    EXPECT_NEAR(model.target(), 0.8 * ActuatorModel::lra_gain(350.0, 175.0, 8.0), 1e-12);
    EXPECT_NEAR(model.response_at(1.0), model.target(), 1e-12);

    ActuatorModel tuned;
    tuned.command(0.0, 0.8, 175.0);
    EXPECT_GT(tuned.response_at(1.0), 10 * model.response_at(1.0));
}

TEST(ActuatorModel, LraFrequencyZeroMeansResonance) {
    ModelSettings settings;
    settings.resonance_hz = 235.0;
    ActuatorModel model(settings);
    model.command(0.0, 0.6, 0.0);
    EXPECT_DOUBLE_EQ(model.target(), 0.6);
    EXPECT_DOUBLE_EQ(model.steady_gain(0.0), model.steady_gain(235.0));
}

TEST(ActuatorModel, LraEnvelopeTimeConstantIsQOverPiF0) {
    ModelSettings settings;
    settings.resonance_hz = 200.0;
    settings.q = 10.0;
    const double tau = 10.0 / (std::numbers::pi * 200.0);
    ActuatorModel model(settings);
    model.command(0.0, 1.0, 0.0);
    EXPECT_DOUBLE_EQ(model.time_constant_s(), tau);
    EXPECT_NEAR(model.response_at(tau), 1.0 - kOneOverE, 1e-9);

    // The same constant governs the ring-down.
    model.command(1.0, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(model.time_constant_s(), tau);
    EXPECT_NEAR(model.response_at(1.0 + tau), kOneOverE, 1e-9);
}

TEST(ActuatorModel, RejectsImpossibleConstantsAndCommands) {
    ModelSettings settings;
    settings.q = 0.0;
    EXPECT_THROW(ActuatorModel{settings}, std::invalid_argument);
    settings = erm();
    settings.spin_down_s = -1.0;
    EXPECT_THROW(ActuatorModel{settings}, std::invalid_argument);

    ActuatorModel model;
    EXPECT_THROW(model.command(0.0, 1.5, 0.0), std::invalid_argument);
    EXPECT_THROW(model.command(0.0, NAN, 0.0), std::invalid_argument);
    EXPECT_THROW(model.command(0.0, 0.5, -1.0), std::invalid_argument);
    EXPECT_THROW(model.command(INFINITY, 0.5, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace vibscore::drivers
