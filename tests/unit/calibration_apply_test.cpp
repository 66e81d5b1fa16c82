// The numbers `vibscore calibrate --apply` puts in use (actuator/calibration.hpp,
// with_measured_margins and apply_as_daemon): a measured LRA planned with the measurement's
// margins, not the datasheet's, a tolerance declared tighter kept, an ERM left as it is; and the
// daemon applies the same rule as the benchmark that judges it (bench/calibrated_feel).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "actuator/calibration.hpp"
#include "daemon/calibration_state.hpp"
#include "daemon/render/drive_planner.hpp"
#include "tests/support/example_actuators.hpp"

namespace vibscore {
namespace {

namespace cal = actuator::calibration;
using actuator::Declaration;
using testing::example_erm;
using testing::example_lra;

Declaration lra_with_tolerances(double resonance, double q) {
    Declaration d = example_lra();
    d.resonance_tolerance = resonance;
    d.q_tolerance = q;
    return d;
}

cal::Estimate trusted_lra(double hz, double q) {
    cal::Estimate e;
    e.kind = actuator::Kind::lra;
    e.resonance_hz = hz;
    e.q = q;
    e.trusted = true;
    return e;
}

TEST(MeasuredMargins, AreTwiceTheLargestUncertaintyAnEstimateIsTrustedWith) {
    EXPECT_DOUBLE_EQ(cal::kMeasuredResonanceTolerance, 0.01);
    EXPECT_DOUBLE_EQ(cal::kMeasuredQTolerance, 0.15);
}

TEST(MeasuredMargins, TheDatasheetsSpreadIsTightenedToTheMeasurements) {
    const Declaration out = cal::with_measured_margins(lra_with_tolerances(0.05, 0.40));
    EXPECT_EQ(out.resonance_tolerance, cal::kMeasuredResonanceTolerance);
    EXPECT_EQ(out.q_tolerance, cal::kMeasuredQTolerance);
    // And so the planner's margins (render::Uncertainty) are the measurement's.
    EXPECT_EQ(render::uncertainty_of(out),
              (render::Uncertainty{cal::kMeasuredResonanceTolerance, cal::kMeasuredQTolerance}));
}

TEST(MeasuredMargins, ATolerancePastTheMeasuredMarginIsTightenedAndOneAtItStays) {
    const double just_above_resonance = std::nextafter(cal::kMeasuredResonanceTolerance, 1.0);
    const double just_above_q = std::nextafter(cal::kMeasuredQTolerance, 1.0);
    const Declaration above =
        cal::with_measured_margins(lra_with_tolerances(just_above_resonance, just_above_q));
    EXPECT_EQ(above.resonance_tolerance, cal::kMeasuredResonanceTolerance);
    EXPECT_EQ(above.q_tolerance, cal::kMeasuredQTolerance);
    const Declaration at = cal::with_measured_margins(
        lra_with_tolerances(cal::kMeasuredResonanceTolerance, cal::kMeasuredQTolerance));
    EXPECT_EQ(at.resonance_tolerance, cal::kMeasuredResonanceTolerance);
    EXPECT_EQ(at.q_tolerance, cal::kMeasuredQTolerance);
}

TEST(MeasuredMargins, AToleranceDeclaredTighterStaysAndExactStaysExact) {
    const Declaration tighter = cal::with_measured_margins(lra_with_tolerances(0.005, 0.10));
    EXPECT_EQ(tighter.resonance_tolerance, 0.005);
    EXPECT_EQ(tighter.q_tolerance, 0.10);
    const Declaration exact = cal::with_measured_margins(lra_with_tolerances(0.0, 0.0));
    EXPECT_EQ(exact.resonance_tolerance, 0.0);
    EXPECT_EQ(exact.q_tolerance, 0.0);
    // Each independently: one tightened, the other kept.
    const Declaration mixed = cal::with_measured_margins(lra_with_tolerances(0.0, 0.40));
    EXPECT_EQ(mixed.resonance_tolerance, 0.0);
    EXPECT_EQ(mixed.q_tolerance, cal::kMeasuredQTolerance);
}

TEST(MeasuredMargins, AnErmIsLeftAsItIs) {
    Declaration erm = example_erm();
    erm.resonance_tolerance = 0.05;  // meaningless for an ERM, and not touched
    erm.q_tolerance = 0.40;
    EXPECT_EQ(cal::with_measured_margins(erm), erm);
}

TEST(MeasuredMargins, NothingButTheTolerancesChanges) {
    Declaration declared = lra_with_tolerances(0.05, 0.40);
    declared.rated_drive = 0.7;
    declared.brake = actuator::Brake::reverse;
    declared.compensation = false;
    Declaration expected = declared;
    expected.resonance_tolerance = cal::kMeasuredResonanceTolerance;
    expected.q_tolerance = cal::kMeasuredQTolerance;
    EXPECT_EQ(cal::with_measured_margins(declared), expected);
}

TEST(ApplyAsDaemon, PutsTheMeasuredNumbersInUseWithTheMeasuredMargins) {
    const Declaration out = cal::apply_as_daemon(example_lra(), trusted_lra(181.5, 12.25));
    EXPECT_EQ(out.resonance_hz, 181.5);
    EXPECT_EQ(out.q, 12.25);
    EXPECT_EQ(out.resonance_tolerance, cal::kMeasuredResonanceTolerance);
    EXPECT_EQ(out.q_tolerance, cal::kMeasuredQTolerance);

    cal::Estimate erm;
    erm.kind = actuator::Kind::erm;
    erm.spin_up_s = 0.05;
    erm.spin_down_s = 0.1;
    erm.trusted = true;
    EXPECT_EQ(cal::apply_as_daemon(example_erm(), erm), cal::apply(example_erm(), erm));
}

TEST(ApplyAsDaemon, RefusesWhatApplyRefuses) {
    cal::Estimate untrusted = trusted_lra(181.5, 12.25);
    untrusted.trusted = false;
    EXPECT_THROW(cal::apply_as_daemon(example_lra(), untrusted), std::invalid_argument);
    EXPECT_THROW(cal::apply_as_daemon(example_erm(), trusted_lra(181.5, 12.25)),
                 std::invalid_argument);
}

TEST(ApplyAsDaemon, IsWhatTheDaemonPlaysAfterApply) {
    // The daemon keeps the numbers (five significant digits) and puts them in with with_measured;
    // numbers already at five digits come out the same both ways.
    for (const Declaration& declared :
         {lra_with_tolerances(0.05, 0.40), lra_with_tolerances(0.005, 0.40),
          lra_with_tolerances(0.0, 0.0)}) {
        const cal::Estimate e = trusted_lra(168.25, 10.5);
        const auto measured = daemon::measured_from(e, "2026-11-29T01:00:00Z");
        EXPECT_EQ(daemon::with_measured(declared, measured), cal::apply_as_daemon(declared, e));
    }
}

}  // namespace
}  // namespace vibscore
