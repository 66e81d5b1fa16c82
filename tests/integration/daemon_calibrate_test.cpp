// `vibscore calibrate` end to end (issue 32; docs/drivers.md, "Calibrating"): the real daemon on
// a private bus with the sim backend, whose TRUE actuator ([sim] true-*) differs from the one
// declared, recorded by the sim's accelerometer; and the offline --plan / --estimate path with a
// recording made by the sensor model.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <future>
#include <regex>
#include <sstream>
#include <thread>

#include "actuator/calibration.hpp"
#include "actuator/vibration_sensor.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Declared LRA 175 Hz Q 15; the sim's true one 168 Hz Q 10.
constexpr const char* kDeclaredLra =
    "[actuator]\nkind = lra\nresonance-hz = 175\nq = 15\nbrake = reverse\n";
constexpr double kTrueHz = 168.0;
constexpr double kTrueQ = 10.0;

std::string sim_lines(const DaemonFixture& daemon, const std::string& accelerometer) {
    return "trace = " + daemon.trace().string() + "\ntrue-resonance-hz = 168\ntrue-q = 10\n" +
           accelerometer;
}

// The daemon with the declared LRA and the sim's true one, its accelerometer as given.
void configure(DaemonFixture& daemon, const std::string& accelerometer) {
    daemon.stop_daemon();
    daemon.write_config(kDeclaredLra, sim_lines(daemon, accelerometer));
    daemon.start_daemon();
}

testing::CommandResult vibscore(const std::vector<std::string>& args) {
    std::vector<std::string> argv{testing::required_env("VIBSCORE")};
    argv.insert(argv.end(), args.begin(), args.end());
    return testing::run_command(argv);
}

std::string property(const DaemonFixture& daemon, const std::string& name) {
    return daemon
        .busctl({"get-property", "org.vibscore.Haptics1", "/org/vibscore/Haptics1",
                 "org.vibscore.Haptics1", name})
        .out;
}

// "key = number" from the [actuator] lines calibrate prints.
std::optional<double> printed(const std::string& out, const std::string& key) {
    const std::regex line("(^|\\n)" + key + " = ([-0-9.eE+]+)");
    std::smatch found;
    if (!std::regex_search(out, found, line)) {
        return std::nullopt;
    }
    return std::stod(found[2]);
}

TEST(DaemonCalibrate, ApplyMeasuresTheTrueLraKeepsItAcrossARestartAndTheClientShowsIt) {
    DaemonFixture daemon;
    configure(daemon, "accelerometer-rate-hz = 1000\n");
    EXPECT_EQ(property(daemon, "ActuatorSource"), "s \"declared\"\n");

    testing::TempDir pictures;
    const auto svg = pictures.path() / "fit.svg";
    const auto calibrated = vibscore({"calibrate", "--apply", "--svg", svg.string()});
    ASSERT_EQ(calibrated.exit_code, 0) << calibrated.out << calibrated.err << daemon.daemon_log();
    EXPECT_THAT(testing::read_file(svg), HasSubstr("<svg"));
    const auto hz = printed(calibrated.out, "resonance-hz");
    const auto q = printed(calibrated.out, "q");
    ASSERT_TRUE(hz && q) << calibrated.out;
    EXPECT_NEAR(*hz, kTrueHz, kTrueHz * 0.01);
    EXPECT_NEAR(*q, kTrueQ, kTrueQ * 0.15);
    EXPECT_THAT(calibrated.out, HasSubstr("# resonance-hz: measured"));
    // How sure the daemon's estimate is arrives with it, as the offline estimate prints it.
    EXPECT_THAT(calibrated.out, HasSubstr("# uncertainty: resonance-hz ±"));
    EXPECT_THAT(calibrated.out, HasSubstr("declared 175"));

    EXPECT_THAT(property(daemon, "ActuatorSource"), StartsWith("s \"measured 20"));
    EXPECT_THAT(property(daemon, "Actuator"), HasSubstr("\"resonance-hz\" \"16"));
    EXPECT_TRUE(std::filesystem::exists(daemon.store() / ".actuator-calibration"));
    const auto driver = vibscore({"driver"});
    EXPECT_THAT(driver.out, HasSubstr("actuator numbers: measured 20")) << driver.out;
    // The administrator's file is left as it was.
    EXPECT_THAT(testing::read_file(daemon.config()), HasSubstr("resonance-hz = 175"));

    daemon.stop_daemon();
    daemon.start_daemon();
    EXPECT_THAT(property(daemon, "ActuatorSource"), StartsWith("s \"measured 20"));
    EXPECT_THAT(property(daemon, "Actuator"), HasSubstr("\"resonance-hz\" \"16"));
    EXPECT_THAT(daemon.daemon_log(), HasSubstr("actuator: using the numbers measured"));
}

// One quarter note at 0.4 at 170 Hz on the shipped phone clef (near both resonances, below full
// drive, so the drive that holds it depends on the numbers), played and waited for; the sim's
// drives for it.
std::vector<std::pair<double, double>> play_one_note(DaemonFixture& daemon) {
    const std::size_t before = daemon.trace_rows().size();
    auto client = daemon.client();
    const auto id = client->Play(
        "<VibScore><Title>one note</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>"
        "<Bar clef=\"l\"><Note length=\"quarter\" number=\"3\" string=\"2\"/></Bar></VibScore>",
        {});
    EXPECT_TRUE(client->wait_finished(id));
    std::vector<std::pair<double, double>> drives;
    const auto rows = daemon.trace_rows();
    for (std::size_t i = before; i < rows.size(); ++i) {
        drives.emplace_back(rows[i].amplitude, rows[i].frequency_hz);
    }
    return drives;
}

TEST(DaemonCalibrate, AppliedNumbersShapeTheNextPlaybackAsCompensationPlansForThem) {
    DaemonFixture daemon;
    configure(daemon, "accelerometer-rate-hz = 1000\n");
    const auto declared = play_one_note(daemon);
    ASSERT_FALSE(declared.empty());
    EXPECT_EQ(play_one_note(daemon), declared) << "the same numbers plan the same drives";
    const auto calibrated = vibscore({"calibrate", "--apply"});
    ASSERT_EQ(calibrated.exit_code, 0) << calibrated.err;
    const auto measured = play_one_note(daemon);
    ASSERT_FALSE(measured.empty());
    EXPECT_NE(measured, declared);
}

TEST(DaemonCalibrate, AnUnprivilegedCallerIsRefusedNamingTheActionAndNothingPlays) {
    DaemonFixture daemon;
    configure(daemon, "accelerometer-rate-hz = 1000\n");
    const auto refused = daemon.call({"Calibrate", "a{sv}", "1", "apply", "b", "true"}, 65534);
    EXPECT_THAT(refused.err, HasSubstr("Calibrating the actuator needs org.vibscore.manage"));
    // One copy of the rows: begin() and end() of two copies would walk past the first one.
    const auto rows = daemon.trace_rows();
    EXPECT_TRUE(std::all_of(rows.begin(), rows.end(), [](const DaemonFixture::TraceRow& row) {
        return row.amplitude == 0.0;
    })) << "no probe was played";
    EXPECT_EQ(property(daemon, "ActuatorSource"), "s \"declared\"\n");
}

TEST(DaemonCalibrate, OptionsOfTheWrongTypeOrNameAreInvalid) {
    DaemonFixture daemon;
    configure(daemon, "accelerometer-rate-hz = 1000\n");
    for (const auto& [key, value] : std::vector<std::pair<std::string, sdbus::Variant>>{
             {"apply", sdbus::Variant(std::string("yes"))}, {"aply", sdbus::Variant(true)}}) {
        try {
            daemon.client()->Calibrate({{key, value}});
            ADD_FAILURE() << key << " was taken";
        } catch (const sdbus::Error& error) {
            EXPECT_EQ(error.getName(), "org.vibscore.Haptics1.Error.InvalidDocument") << key;
            EXPECT_THAT(error.getMessage(), HasSubstr(key));
        }
    }
}

TEST(DaemonCalibrate, AnErmsTimeConstantsAreMeasuredWithoutBeingApplied) {
    DaemonFixture daemon;
    daemon.stop_daemon();
    daemon.write_config(
        "[actuator]\nkind = erm\nspin-up-ms = 40\nspin-down-ms = 80\n",
        "trace = " + daemon.trace().string() + "\ntrue-spin-up-ms = 55\ntrue-spin-down-ms = 120\n");
    daemon.start_daemon();
    const auto calibrated = vibscore({"calibrate"});
    ASSERT_EQ(calibrated.exit_code, 0) << calibrated.out << calibrated.err << daemon.daemon_log();
    const auto up = printed(calibrated.out, "spin-up-ms");
    const auto down = printed(calibrated.out, "spin-down-ms");
    ASSERT_TRUE(up && down) << calibrated.out;
    EXPECT_NEAR(*up, 55.0, 55.0 * 0.15);
    EXPECT_NEAR(*down, 120.0, 120.0 * 0.15);
    EXPECT_THAT(calibrated.err, HasSubstr("--apply makes these the numbers in use"));
    EXPECT_THAT(calibrated.out, HasSubstr("# uncertainty: spin-up-ms ±"));
    EXPECT_EQ(property(daemon, "ActuatorSource"), "s \"declared\"\n");
    EXPECT_THAT(property(daemon, "Actuator"), HasSubstr("\"spin-up-ms\" \"40\""));
}

TEST(DaemonCalibrate, WithoutAnAccelerometerItRefusesSayingWhatToConfigureAndChangesNothing) {
    DaemonFixture daemon;
    configure(daemon, "accelerometer-rate-hz = 0\n");
    const auto refused = vibscore({"calibrate", "--apply"});
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_THAT(refused.err, HasSubstr("no accelerometer"));
    EXPECT_THAT(refused.err, HasSubstr("[calibration] accelerometer = PATH"));
    EXPECT_EQ(property(daemon, "ActuatorSource"), "s \"declared\"\n");
    EXPECT_FALSE(std::filesystem::exists(daemon.store() / ".actuator-calibration"));

    try {
        daemon.client()->Calibrate({});
        ADD_FAILURE() << "Calibrate without an accelerometer answered";
    } catch (const sdbus::Error& error) {
        EXPECT_EQ(error.getName(), "org.vibscore.Haptics1.Error.NoAccelerometer");
    }
}

TEST(DaemonCalibrate, ANamedDeviceThatIsNotThereIsRefusedByName) {
    DaemonFixture daemon;
    daemon.stop_daemon();
    daemon.write_config(
        std::string(kDeclaredLra) + "[calibration]\naccelerometer = /dev/iio:device97\n",
        sim_lines(daemon, ""));
    daemon.start_daemon();
    const auto refused = vibscore({"calibrate"});
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_THAT(refused.err, HasSubstr("/dev/iio:device97: no such IIO device"));
}

TEST(DaemonCalibrate, AnUntrustedRecordingIsRefusedWithApplyAndNothingChanges) {
    DaemonFixture daemon;
    configure(daemon, "accelerometer-rate-hz = 1000\naccelerometer-noise = 80\n");
    const auto refused = vibscore({"calibrate", "--apply"});
    EXPECT_EQ(refused.exit_code, 1) << refused.out;
    EXPECT_THAT(refused.err, HasSubstr("not trusted")) << refused.err;
    EXPECT_EQ(property(daemon, "ActuatorSource"), "s \"declared\"\n");
    EXPECT_THAT(property(daemon, "Actuator"), HasSubstr("\"resonance-hz\" \"175\""));
    EXPECT_FALSE(std::filesystem::exists(daemon.store() / ".actuator-calibration"));

    // Without --apply the estimate is shown, and the exit status says it is not to be trusted.
    const auto shown = vibscore({"calibrate"});
    EXPECT_EQ(shown.exit_code, 1);
    EXPECT_THAT(shown.err, HasSubstr("the estimate is not trusted"));
}

TEST(DaemonCalibrate, AnUrgentPlaybackStopsTheProbeAtOnceAndNothingChanges) {
    DaemonFixture daemon;
    configure(daemon, "accelerometer-rate-hz = 1000\n");
    auto client = daemon.client();
    auto calibrating = std::async(std::launch::async, [] {
        return vibscore({"calibrate", "--apply"});
    });
    ASSERT_TRUE(client->wait_for([](const testing::SeenSignal& seen) {
        return seen.name == "PlaybackStarted" && seen.text == "<calibration>";
    })) << daemon.daemon_log();
    const auto rang = daemon.call({"Play", "sa{sv}", "ringtone", "1", "usage", "s", "ringtone"});
    EXPECT_EQ(rang.exit_code, 0) << rang.err;
    const auto refused = calibrating.get();
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_THAT(refused.err, HasSubstr("the probe was cut short (preempted)"));
    EXPECT_EQ(property(daemon, "ActuatorSource"), "s \"declared\"\n");
}

// The offline path: the probe as a file, recorded by a model of a phone's accelerometer (as any
// recorder would), estimated by the CLI.
class OfflineCalibrate : public ::testing::Test {
  protected:
    void SetUp() override {
        declared_ = dir_.write("actuator.conf", kDeclaredLra);
        plan_ = dir_.path() / "plan.csv";
    }

    // ACCEL.csv for the plan the CLI wrote, of the true actuator.
    std::filesystem::path record(double noise_rms) {
        const auto plan = actuator::calibration::parse_plan_csv(
            testing::read_file(plan_), plan_.string(), actuator::Kind::lra);
        actuator::Declaration truth;
        truth.kind = actuator::Kind::lra;
        truth.resonance_hz = kTrueHz;
        truth.q = kTrueQ;
        actuator::SensorOptions options;
        options.rate_hz = 1000.0;
        options.noise_rms = noise_rms;
        std::ostringstream csv;
        csv.precision(9);
        csv << "t,x,y,z\n";
        for (const auto& s : actuator::record(plan, truth, options, 0.002, 0.2)) {
            csv << s.t_s << "," << s.x << "," << s.y << "," << s.z << "\n";
        }
        return dir_.write("accel.csv", csv.str());
    }

    testing::TempDir dir_;
    std::filesystem::path declared_, plan_;
};

TEST_F(OfflineCalibrate, PlanThenEstimateGivesTheTrueNumbersBesideTheDeclaredOnesAndAPicture) {
    const auto planned =
        vibscore({"calibrate", "--plan", "--actuator", declared_.string(), "-o", plan_.string()});
    ASSERT_EQ(planned.exit_code, 0) << planned.err;
    EXPECT_THAT(testing::read_file(plan_), StartsWith("time_ns,amplitude,frequency_hz\n"));
    const auto accel = record(0.02);
    const auto png = dir_.path() / "fit.png";
    const auto estimated = vibscore({"calibrate", "--estimate", plan_.string(), accel.string(),
                                     "--actuator", declared_.string(), "--png", png.string()});
    ASSERT_EQ(estimated.exit_code, 0) << estimated.out << estimated.err;
    const auto hz = printed(estimated.out, "resonance-hz");
    ASSERT_TRUE(hz) << estimated.out;
    EXPECT_NEAR(*hz, kTrueHz, kTrueHz * 0.01);
    EXPECT_THAT(estimated.out, HasSubstr("declared 175"));
    EXPECT_GT(std::filesystem::file_size(png), 1000u);
}

TEST_F(OfflineCalibrate, ARecordingDrownedInNoiseIsRefusedWithItsReasonsOnStandardError) {
    ASSERT_EQ(vibscore({"calibrate", "--plan", "--kind", "lra", "-o", plan_.string()}).exit_code,
              0);
    const auto accel = record(80.0);
    const auto estimated =
        vibscore({"calibrate", "--estimate", plan_.string(), accel.string(), "--kind", "lra"});
    EXPECT_EQ(estimated.exit_code, 1);
    EXPECT_THAT(estimated.err, HasSubstr("the estimate is not trusted"));
}

TEST_F(OfflineCalibrate, WithoutAKindThePlanIsAUsageError) {
    const auto planned = vibscore({"calibrate", "--plan", "-o", plan_.string()});
    EXPECT_EQ(planned.exit_code, 2);
    EXPECT_THAT(planned.err, HasSubstr("--kind erm|lra"));
}

}  // namespace
}  // namespace vibscore
