// [clefs] fit = auto through the real daemon on a private bus: every clef no line maps is fitted
// to the declared actuator as it is played, BarClefs and `vibscore info` say so, `vibscore get
// clef NAME --device` gives the fitted document, the log says what the fit changed, and a reload
// that declares another actuator refits (docs/clefs.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <signal.h>

#include <thread>

#include "daemon/render/fitting/clef_fit.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;

const char* const kLraSection =
    "[actuator]\nkind = lra\nresonance-hz = 175\nq = 15\nrated-drive = 0.7\nbrake = reverse\n";
const char* const kErmSection =
    "[actuator]\nkind = erm\nspin-up-ms = 40\nspin-down-ms = 80\nrated-drive = 0.7\n"
    "brake = reverse\n";
const char* const kClefs = "[clefs]\nfit = auto\nerm-rough = erm-phone\n";

actuator::Declaration declared(actuator::Kind kind) {
    actuator::Declaration d;
    d.kind = kind;
    d.rated_drive = 0.7;
    d.brake = actuator::Brake::reverse;
    return d;
}

Clef shipped_clef(const std::string& name) {
    return load_clef_file(testing::required_env("VIBSCORE_CLEFS") + "/" + name + ".clef.xml");
}

testing::CommandResult vibscore(const std::vector<std::string>& args) {
    std::vector<std::string> argv{testing::required_env("VIBSCORE")};
    argv.insert(argv.end(), args.begin(), args.end());
    return testing::run_command(argv);
}

bool wait_for_log(const DaemonFixture& daemon, const std::string& text) {
    return testing::wait_until([&] { return daemon.daemon_log().find(text) != std::string::npos; });
}

TEST(DaemonClefFit, FitsEachUnmappedClefToTheDeclaredActuatorAndSaysSoEverywhere) {
    DaemonFixture daemon{std::string(kLraSection) + kClefs};
    const auto bars = daemon.call({"BarClefs", "s", "success"});
    ASSERT_EQ(bars.exit_code, 0) << bars.err;
    EXPECT_EQ(bars.out, "a(ss) 1 \"lra-phone\" \"lra-phone (fitted)\"\n");
    const auto info = vibscore({"info", "success"});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_THAT(info.out, HasSubstr("  1  lra-phone -> lra-phone (fitted)\n"));

    // The LRA's band is too narrow for six pitches: the click plays as roughness at its own
    // frequency, never at lra-phone's 235 Hz.
    auto client = daemon.client();
    ASSERT_TRUE(client->wait_finished(client->Play("touch-click", {})));
    int driven = 0;
    for (const auto& row : daemon.trace_rows()) {
        if (row.amplitude != 0.0) {
            ++driven;
            EXPECT_NE(row.frequency_hz, 235.0);
        }
    }
    EXPECT_GT(driven, 0);

    const auto device = vibscore({"get", "clef", "lra-phone", "--device"});
    ASSERT_EQ(device.exit_code, 0) << device.err;
    EXPECT_THAT(device.out, HasSubstr("<!-- Fitted by vibscore clef fit from lra-phone to lra:"));
    EXPECT_EQ(read_clef(device.out, "device"),
              render::fit_clef(shipped_clef("lra-phone"), declared(actuator::Kind::lra)).clef);
    // An explicit map wins, and --device gives its clef.
    const auto mapped = vibscore({"get", "clef", "erm-rough", "--device"});
    ASSERT_EQ(mapped.exit_code, 0) << mapped.err;
    EXPECT_EQ(read_clef(mapped.out, "mapped"), shipped_clef("erm-phone"));
    EXPECT_EQ(vibscore({"get", "score", "success", "--device"}).exit_code, 2);

    EXPECT_THAT(
        daemon.daemon_log(),
        HasSubstr("clef \"lra-phone\" fitted to the actuator: strings: full strength only"));
    EXPECT_THAT(daemon.daemon_log(), HasSubstr("fit = auto (every other clef fitted"));

    // Another actuator on SIGHUP: the clefs are refitted to it.
    daemon.write_config(std::string(kErmSection) + kClefs, "trace = " + daemon.trace().string());
    daemon.signal_daemon(SIGHUP);
    ASSERT_TRUE(wait_for_log(daemon, "configuration reloaded")) << daemon.daemon_log();
    ASSERT_TRUE(wait_for_log(daemon, "an ERM has no pitch to play")) << daemon.daemon_log();
    const auto refitted = vibscore({"get", "clef", "lra-phone", "--device"});
    ASSERT_EQ(refitted.exit_code, 0) << refitted.err;
    EXPECT_EQ(read_clef(refitted.out, "refitted"),
              render::fit_clef(shipped_clef("lra-phone"), declared(actuator::Kind::erm)).clef);
}

TEST(DaemonClefFit, AStoredClefIsCheckedAgainstTheActuatorInTheLog) {
    DaemonFixture daemon{kLraSection};
    const auto text = testing::read_file(testing::required_env("VIBSCORE_CLEFS") +
                                         std::string("/lra-phone.clef.xml"));
    const auto composed = daemon.call({"Compose", "ss", "my-phone", text});
    ASSERT_EQ(composed.exit_code, 0) << composed.err;
    ASSERT_TRUE(wait_for_log(daemon, "clef \"my-phone\": string 6 (235 Hz): full drive gives"))
        << daemon.daemon_log();
}

}  // namespace
}  // namespace vibscore
