// The declared actuator ([actuator]) through the real daemon on a private bus: read at start and
// on SIGHUP, simulated by the sim backend, and the drives the player sends for it as the sim's
// trace records them (docs/drivers.md, "Compensation").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <signal.h>

#include <thread>

#include "common/monotonic_clock.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;
using TraceRow = DaemonFixture::TraceRow;

// One quarter note (200 ms) at strength 1 on the shipped phone clef.
const char* const kOneNote =
    "<VibScore><Title>one note</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"l\"><Note length=\"quarter\" number=\"9\" string=\"6\"/></Bar></VibScore>";

std::string erm_section(const std::string& brake, const std::string& compensation) {
    return "[actuator]\nkind = erm\nrated-drive = 0.7\nspin-up-ms = 40\nspin-down-ms = 80\n"
           "brake = " +
           brake + "\ncompensation = " + compensation + "\n";
}

actuator::Declaration erm(bool compensation) {
    actuator::Declaration d;
    d.kind = actuator::Kind::erm;
    d.rated_drive = 0.7;
    d.brake = actuator::Brake::reverse;
    d.compensation = compensation;
    return d;
}

// The drives the renderer plans for kOneNote on that actuator, as the player would send them.
std::vector<render::Cue> planned(const actuator::Declaration& declared) {
    const Clef clef =
        load_clef_file(testing::required_env("VIBSCORE_CLEFS") + "/lra-phone.clef.xml");
    const ScoreBundle bundle =
        bind_clefs(read_score(kOneNote, "one"), "one",
                   [&](const ClefDeclaration&, const SourceLocation&) { return clef; });
    const render::Performance performance(bundle);
    render::CueAdaptation adaptation;
    adaptation.actuator = declared;
    adaptation.reverse = true;
    auto cues =
        render::adapt_cues(render::cue_schedule(performance), performance.duration(), adaptation);
    std::erase_if(cues, [](const render::Cue& c) { return c.kind != render::Cue::Kind::drive; });
    return cues;
}

// The trace rows of one playback of kOneNote, from its first drive on.
std::vector<TraceRow> play_one_note(DaemonFixture& daemon) {
    auto client = daemon.client();
    const std::int64_t before = monotonic_now_ns();
    const auto id = client->Play(kOneNote, {});
    EXPECT_TRUE(client->wait_finished(id));
    std::vector<TraceRow> rows;
    for (const auto& row : daemon.trace_rows()) {
        if (row.time_ns >= before && (!rows.empty() || row.amplitude != 0.0)) {
            rows.push_back(row);
        }
    }
    return rows;
}

bool wait_for_log(const DaemonFixture& daemon, const std::string& text) {
    return testing::wait_until([&] { return daemon.daemon_log().find(text) != std::string::npos; });
}

TEST(DaemonFeel, ADeclaredErmIsOverdrivenHeldAndBrakedAsTheModelSays) {
    DaemonFixture daemon(erm_section("reverse", "on"));
    EXPECT_THAT(daemon.daemon_log(), HasSubstr("actuator: erm: spin-up 40 ms, spin-down 80 ms, "
                                               "rated-drive 0.7, brake reverse, compensation on"));
    const auto plan = planned(erm(true));
    ASSERT_EQ(plan.size(), 4u);  // overdrive, hold, brake, off
    const auto rows = play_one_note(daemon);
    ASSERT_GE(rows.size(), plan.size()) << daemon.daemon_log();
    for (std::size_t i = 0; i < plan.size(); ++i) {
        EXPECT_DOUBLE_EQ(rows[i].amplitude, plan[i].amplitude) << "drive " << i;
        // Every drive at its planned time after the first, or later (the player is never early).
        const double at_ms = static_cast<double>(rows[i].time_ns - rows[0].time_ns) / 1e6;
        EXPECT_GE(at_ms, (plan[i].at - plan[0].at) * 1000.0 - 0.5) << "drive " << i;
    }
    // The sim's strength when the overdrive ends: the written 1 (more if the player was late), and
    // next to nothing once the brake is done.
    EXPECT_GT(rows[1].response, 0.99);
    EXPECT_LT(rows[1].response, 1.2);
    EXPECT_LT(rows[3].response, 0.15);
}

TEST(DaemonFeel, SighupReloadsTheDeclarationAndABadOneChangesNothing) {
    DaemonFixture daemon(erm_section("reverse", "off"));
    auto rows = play_one_note(daemon);
    ASSERT_FALSE(rows.empty());
    EXPECT_DOUBLE_EQ(rows[0].amplitude, 0.7);  // strength 1 is the rated drive, unshaped

    daemon.write_config(erm_section("none", "on"), "trace = " + daemon.trace().string());
    daemon.signal_daemon(SIGHUP);
    ASSERT_TRUE(wait_for_log(daemon, "compensation on")) << daemon.daemon_log();
    ASSERT_TRUE(wait_for_log(daemon, "configuration reloaded"));
    rows = play_one_note(daemon);
    ASSERT_FALSE(rows.empty());
    EXPECT_DOUBLE_EQ(rows[0].amplitude, 1.0);  // overdrive
    for (const auto& row : rows) {
        EXPECT_GE(row.amplitude, 0.0) << "no brake without one declared";
    }

    daemon.write_config("[actuator]\nkind = erm\nq = 15\n", "trace = " + daemon.trace().string());
    daemon.signal_daemon(SIGHUP);
    ASSERT_TRUE(wait_for_log(daemon, "reload failed")) << daemon.daemon_log();
    EXPECT_THAT(daemon.daemon_log(),
                HasSubstr("vibscored.conf:7: [actuator] q = \"15\" is for kind = lra"));
    rows = play_one_note(daemon);
    ASSERT_FALSE(rows.empty());
    EXPECT_DOUBLE_EQ(rows[0].amplitude, 1.0);  // the running declaration plays on
}

std::string property(const DaemonFixture& daemon, const std::string& name) {
    return daemon
        .busctl({"get-property", "org.vibscore.Haptics1", "/org/vibscore/Haptics1",
                 "org.vibscore.Haptics1", name})
        .out;
}

testing::CommandResult vibscore(const std::vector<std::string>& args) {
    std::vector<std::string> argv{testing::required_env("VIBSCORE")};
    argv.insert(argv.end(), args.begin(), args.end());
    return testing::run_command(argv);
}

// A reload that changes only the declared numbers (the same kind and brake) does not end what
// plays with "driver-switch": the sim takes them in place. Another kind reopens it, as a new
// backend, and that ends the playback as before.
TEST(DaemonFeel, ANewDeclarationOfTheSameKindKeepsWhatPlaysAndAnotherKindEndsIt) {
    DaemonFixture daemon(erm_section("reverse", "on"));
    auto client = daemon.client();
    const auto id = client->Play(
        "ringtone", std::map<std::string, sdbus::Variant>{{"repeat", sdbus::Variant(-1)}});
    const auto trace = "trace = " + daemon.trace().string();
    daemon.write_config(
        "[actuator]\nkind = erm\nrated-drive = 0.7\nspin-up-ms = 60\nspin-down-ms = 80\n"
        "brake = reverse\n",
        trace);
    daemon.signal_daemon(SIGHUP);
    ASSERT_TRUE(wait_for_log(daemon, "configuration reloaded")) << daemon.daemon_log();
    // Still playing: a position of it arrives after the reload, and it did not finish.
    const std::size_t seen_at_reload = client->signals().size();
    EXPECT_TRUE(testing::wait_until([&] {
        const auto seen = client->signals();
        for (std::size_t i = seen_at_reload + 1; i < seen.size(); ++i) {
            if (seen[i].name == "PlaybackPosition" && seen[i].id == id) {
                return true;
            }
        }
        return false;
    })) << daemon.daemon_log();
    for (const auto& seen : client->signals()) {
        EXPECT_FALSE(seen.name == "PlaybackFinished" && seen.id == id) << seen.text;
    }
    EXPECT_THAT(daemon.daemon_log(), ::testing::Not(HasSubstr("driver is now")));

    daemon.write_config("[actuator]\nkind = lra\nbrake = reverse\n", trace);
    daemon.signal_daemon(SIGHUP);
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason)) << daemon.daemon_log();
    EXPECT_EQ(reason, "driver-switch");
}

TEST(DaemonFeel, TheDeclarationIsPublishedOnTheBusAndShownByTheClient) {
    DaemonFixture daemon(erm_section("reverse", "on"));
    EXPECT_EQ(property(daemon, "Actuator"),
              "a{ss} 6 \"brake\" \"reverse\" \"compensation\" \"on\" \"kind\" \"erm\" "
              "\"rated-drive\" \"0.7\" \"spin-down-ms\" \"80\" \"spin-up-ms\" \"40\"\n");
    EXPECT_THAT(property(daemon, "Capabilities"), HasSubstr("\"reverse-drive\""));
    const std::string declared =
        "actuator: erm: spin-up 40 ms, spin-down 80 ms, rated-drive 0.7, brake reverse, "
        "compensation on\n";
    const auto driver = vibscore({"driver"});
    EXPECT_EQ(driver.exit_code, 0) << driver.err;
    EXPECT_THAT(driver.out, HasSubstr(declared));
    EXPECT_THAT(vibscore({"info", "ringtone"}).out, HasSubstr(declared));
    // --actuator without a file asks the daemon.
    const auto check =
        vibscore({"check", testing::required_env("VIBSCORE_CLEFS") + "/touch-click.score.xml",
                  "--actuator"});
    EXPECT_EQ(check.exit_code, 0) << check.err;
    EXPECT_THAT(check.err, HasSubstr("touch-click.score.xml: warning: bar 1, note 1: too short"));
    EXPECT_THAT(check.out, HasSubstr("for the actuator (erm: spin-up 40 ms"));

    // A reload that declares another actuator changes the property.
    daemon.write_config("[actuator]\nkind = lra\nq = 20\n", "trace = " + daemon.trace().string());
    daemon.signal_daemon(SIGHUP);
    ASSERT_TRUE(wait_for_log(daemon, "configuration reloaded")) << daemon.daemon_log();
    EXPECT_THAT(property(daemon, "Actuator"), HasSubstr("\"kind\" \"lra\""));
    EXPECT_THAT(property(daemon, "Actuator"), HasSubstr("\"q\" \"20\""));
}

TEST(DaemonFeel, WithoutADeclarationThePropertyIsEmptyAndTheClientSaysSo) {
    DaemonFixture daemon;
    EXPECT_EQ(property(daemon, "Actuator"), "a{ss} 0\n");
    EXPECT_THAT(vibscore({"driver"}).out, HasSubstr("actuator: none declared"));
    const auto check = vibscore(
        {"check", testing::required_env("VIBSCORE_CLEFS") + "/touch-tick.score.xml", "--actuator"});
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_THAT(check.err, HasSubstr("vibscored declares no actuator"));
}

TEST(DaemonFeel, ABadDeclarationStopsStartUpNamingTheFileLineKeyAndValue) {
    DaemonFixture daemon;
    daemon.stop_daemon();
    daemon.write_config("[actuator]\nkind = lra\nrated-drive = 1.5\n", "");
    try {
        daemon.start_daemon();
        FAIL() << "vibscored started";
    } catch (const std::runtime_error& error) {
        EXPECT_THAT(error.what(),
                    HasSubstr("vibscored.conf:7: [actuator] rated-drive = \"1.5\": expected a "
                              "number above 0 and at most 1"));
    }
}

}  // namespace
}  // namespace vibscore
