// The measured actuator kept in the daemon's store (daemon/calibration_state.hpp): its file round
// trip, its limits, a corrupt file ignored (and kept), and the numbers in use after a start.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "daemon/calibration_state.hpp"
#include "daemon/config.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using daemon::MeasuredActuator;
using ::testing::HasSubstr;

MeasuredActuator lra(double hz, double q) {
    MeasuredActuator measured;
    measured.kind = actuator::Kind::lra;
    measured.resonance_hz = hz;
    measured.q = q;
    measured.measured_at = "2026-11-28T18:40:12Z";
    return measured;
}

daemon::DaemonConfig declared_lra(const std::filesystem::path& store) {
    daemon::DaemonConfig config;
    config.store = store;
    actuator::Declaration declared;
    declared.kind = actuator::Kind::lra;
    declared.resonance_hz = 175.0;
    declared.q = 15.0;
    declared.rated_drive = 0.8;
    config.actuator = declared;
    return config;
}

TEST(CalibrationState, TheTextReadsBackAsTheSameMeasurement) {
    const auto measured = lra(168.25, 10.5);
    EXPECT_EQ(daemon::parse_measured(daemon::measured_text(measured), "f"), measured);
    MeasuredActuator erm;
    erm.kind = actuator::Kind::erm;
    erm.spin_up_s = 0.0375;
    erm.spin_down_s = 0.125;
    erm.measured_at = "2026-01-02T03:04:05Z";
    EXPECT_EQ(daemon::parse_measured(daemon::measured_text(erm), "f"), erm);
}

TEST(CalibrationState, NumbersAreHeldToTheDeclarationsLimitsAtTheirEdges) {
    const auto text = [](const std::string& line) {
        return "measured = 2026-11-28T18:40:12Z\nkind = lra\nresonance-hz = 170\n" + line + "\n";
    };
    EXPECT_NO_THROW(daemon::parse_measured(text("q = 500"), "f"));
    EXPECT_THROW(daemon::parse_measured(text("q = 500.01"), "f"), std::invalid_argument);
    EXPECT_NO_THROW(daemon::parse_measured(text("q = 1"), "f"));
    EXPECT_THROW(daemon::parse_measured(text("q = 0.99"), "f"), std::invalid_argument);
    try {
        daemon::parse_measured(text("q = lots"), "state");
        FAIL();
    } catch (const std::invalid_argument& error) {
        EXPECT_THAT(error.what(), HasSubstr("state:4: q = \"lots\" is not a number"));
    }
}

TEST(CalibrationState, AFileWithoutKindDateOrNumbersOrWithTheOtherKindsIsRefused) {
    EXPECT_THROW(daemon::parse_measured("measured = d\nq = 10\n", "f"), std::invalid_argument);
    EXPECT_THROW(daemon::parse_measured("kind = lra\nq = 10\n", "f"), std::invalid_argument);
    EXPECT_THROW(daemon::parse_measured("measured = d\nkind = lra\n", "f"), std::invalid_argument);
    EXPECT_THROW(daemon::parse_measured("measured = d\nkind = lra\nspin-up-ms = 40\n", "f"),
                 std::invalid_argument);
    EXPECT_THROW(daemon::parse_measured("measured = d\nkind = lra\nq 10\n", "f"),
                 std::invalid_argument);
    EXPECT_THROW(daemon::parse_measured("measured = d\nkind = lra\nbrake = none\n", "f"),
                 std::invalid_argument);
}

TEST(CalibrationState, SavedThenLoadedFromTheStore) {
    testing::TempDir dir;
    const auto file = dir.path() / daemon::kCalibrationStateFile;
    EXPECT_EQ(daemon::load_measured(file), std::nullopt);
    daemon::save_measured(file, lra(168.0, 10.0));
    EXPECT_EQ(daemon::load_measured(file), lra(168.0, 10.0));
    daemon::save_measured(file, lra(171.0, 12.0));  // replaced whole
    EXPECT_EQ(daemon::load_measured(file), lra(171.0, 12.0));
}

TEST(CalibrationState, ACorruptFileIsIgnoredWithALogLineAndKept) {
    testing::TempDir dir;
    const auto file =
        dir.write(daemon::kCalibrationStateFile, "measured = x\nkind = lra\nq = -3\n");
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(daemon::load_measured(file), std::nullopt);
    const std::string log = ::testing::internal::GetCapturedStderr();
    EXPECT_THAT(log, HasSubstr(file.string() + ":3: q = \"-3\" is outside 1..500"));
    EXPECT_THAT(log, HasSubstr("using the declared actuator"));
    EXPECT_TRUE(std::filesystem::exists(file));
    auto config = declared_lra(dir.path());
    ::testing::internal::CaptureStderr();
    daemon::use_measured_actuator(config);
    ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(config.actuator->resonance_hz, 175.0);
    EXPECT_EQ(config.actuator_source, "declared");
}

TEST(CalibrationState, AtStartTheMeasuredNumbersStandInForTheDeclaredOnesAndTheRestIsKept) {
    testing::TempDir dir;
    daemon::save_measured(dir.path() / daemon::kCalibrationStateFile, lra(168.0, 10.0));
    auto config = declared_lra(dir.path());
    config.device_clefs.fit_to = config.actuator;
    ::testing::internal::CaptureStderr();
    daemon::use_measured_actuator(config);
    ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(config.actuator->resonance_hz, 168.0);
    EXPECT_EQ(config.actuator->q, 10.0);
    EXPECT_EQ(config.actuator->rated_drive, 0.8);
    EXPECT_EQ(config.device_clefs.fit_to, config.actuator);  // clef fitting uses them too
    EXPECT_EQ(config.actuator_source, "measured 2026-11-28T18:40:12Z");
}

TEST(CalibrationState, MeasuredLraNumbersComeWithTheMeasurementsTolerancesNotTheDatasheets) {
    actuator::Declaration declared = *declared_lra("/nonexistent").actuator;
    const auto measured = daemon::with_measured(declared, lra(168.0, 10.0));
    EXPECT_EQ(measured.resonance_tolerance, 0.01);  // from the default 5 %
    EXPECT_EQ(measured.q_tolerance, 0.15);          // from the default 40 %
    declared.resonance_tolerance = 0.0;             // declared exact: stays exact
    declared.q_tolerance = 0.1;
    const auto exact = daemon::with_measured(declared, lra(168.0, 10.0));
    EXPECT_EQ(exact.resonance_tolerance, 0.0);
    EXPECT_EQ(exact.q_tolerance, 0.1);
}

TEST(CalibrationState, AMeasurementOfAnotherKindIsIgnoredAndNothingDeclaredNeedsNone) {
    testing::TempDir dir;
    MeasuredActuator erm;
    erm.kind = actuator::Kind::erm;
    erm.spin_up_s = 0.04;
    erm.measured_at = "2026-11-28T18:40:12Z";
    daemon::save_measured(dir.path() / daemon::kCalibrationStateFile, erm);
    auto config = declared_lra(dir.path());
    ::testing::internal::CaptureStderr();
    daemon::use_measured_actuator(config);
    EXPECT_THAT(::testing::internal::GetCapturedStderr(), HasSubstr("declares another kind"));
    EXPECT_EQ(config.actuator->resonance_hz, 175.0);
    EXPECT_EQ(config.actuator_source, "declared");

    daemon::DaemonConfig undeclared;
    undeclared.store = dir.path();
    daemon::use_measured_actuator(undeclared);
    EXPECT_FALSE(undeclared.actuator);
    EXPECT_EQ(undeclared.actuator_source, "");
}

}  // namespace
}  // namespace vibscore
