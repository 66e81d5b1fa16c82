// The real vibscored on a private bus with the real policy: driven with busctl (systemd's own
// client) and with a typed sdbus-c++ client that watches the signals.
#include <gtest/gtest.h>

#include <pwd.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <thread>

#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "dbus/sdbus_compat.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using testing::SeenSignal;

constexpr uid_t kNobody = 65534;

std::map<std::string, sdbus::Variant> options(
    std::initializer_list<std::pair<const std::string, sdbus::Variant>> list = {}) {
    return std::map<std::string, sdbus::Variant>(list);
}

std::string error_name_of(const std::function<void()>& call) {
    try {
        call();
    } catch (const sdbus::Error& error) {
        return error.getName() + ": " + error.getMessage();
    }
    return "<no error>";
}

const char* const kShortScore =
    "<VibScore><Title>two notes</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"l\"><Note length=\"8th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"5\" string=\"1\"/></Bar></VibScore>";

class DaemonBus : public ::testing::Test {
  protected:
    DaemonFixture daemon;
};

TEST_F(DaemonBus, BusctlListsAndGetsShippedDocuments) {
    const auto scores = daemon.call({"List", "s", "score"});
    ASSERT_EQ(scores.exit_code, 0) << scores.err;
    EXPECT_NE(scores.out.find("\"ringtone\""), std::string::npos) << scores.out;
    const auto clef = daemon.call({"Get", "ss", "clef", "lra-phone"});
    ASSERT_EQ(clef.exit_code, 0) << clef.err;
    EXPECT_NE(clef.out.find("VibClef"), std::string::npos);
    const auto properties =
        daemon.busctl({"get-property", "org.vibscore.Haptics1", "/org/vibscore/Haptics1",
                       "org.vibscore.Haptics1", "Driver", "Capabilities", "Version"});
    EXPECT_EQ(properties.out,
              "s \"sim\"\nas 2 \"amplitude-control\" \"frequency-control\"\n"
              "s \"0.1.0\"\n");
}

TEST_F(DaemonBus, BusctlComposesAndDeletesWithRegistryChangedSignals) {
    auto client = daemon.client();
    const auto composed = daemon.call({"Compose", "ss", "my-buzz", kShortScore});
    ASSERT_EQ(composed.exit_code, 0) << composed.err;
    EXPECT_TRUE(client->wait_for([](const SeenSignal& s) { return s.text == "score/my-buzz"; }));
    EXPECT_NE(daemon.call({"List", "s", "score"}).out.find("\"my-buzz\" \"two notes\""),
              std::string::npos);
    EXPECT_EQ(client->Get("score", "my-buzz").find("<Title>two notes</Title>") != std::string::npos,
              true);
    EXPECT_EQ(daemon.call({"Delete", "ss", "score", "my-buzz"}).exit_code, 0);
    EXPECT_NE(daemon.call({"Get", "ss", "score", "my-buzz"}).err.find("no score \"my-buzz\""),
              std::string::npos);
}

TEST_F(DaemonBus, OriginTellsAShippedScoreFromAStoredOneAndOneShadowingIt) {
    EXPECT_EQ(daemon.call({"Origin", "ss", "score", "ringtone"}).out, "s \"shipped\"\n");
    ASSERT_EQ(daemon.call({"Compose", "ss", "my-buzz", kShortScore}).exit_code, 0);
    EXPECT_EQ(daemon.call({"Origin", "ss", "score", "my-buzz"}).out, "s \"stored\"\n");
    ASSERT_EQ(daemon.call({"Compose", "ss", "ringtone", kShortScore}).exit_code, 0);
    EXPECT_EQ(daemon.call({"Origin", "ss", "score", "ringtone"}).out,
              "s \"stored-over-shipped\"\n");
    EXPECT_EQ(daemon.call({"Origin", "ss", "clef", "lra-phone"}).out, "s \"shipped\"\n");
    const auto missing = daemon.call({"Origin", "ss", "score", "no-such-score"});
    EXPECT_NE(missing.exit_code, 0);
    EXPECT_NE(missing.err.find("no score \"no-such-score\""), std::string::npos) << missing.err;
    EXPECT_NE(daemon.call({"Origin", "ss", "tune", "x"}).err.find("tune"), std::string::npos);
    const auto info = vibscore::testing::run_command(
        {vibscore::testing::required_env("VIBSCORE"), "info", "ringtone"});
    EXPECT_NE(
        info.out.find("registry: stored, shadowing a shipped one (deleting it brings that back)\n"),
        std::string::npos)
        << info.out << info.err;
}

TEST_F(DaemonBus, PlaysAScoreWithSignalsInOrderAndTheActuatorEndsOff) {
    auto client = daemon.client();
    const auto id = client->Play(kShortScore, options());
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason));
    EXPECT_EQ(reason, "completed");
    std::vector<std::string> seen;
    for (const auto& s : client->signals()) {
        if (s.id == id)
            seen.push_back(s.name + " " + s.text);
    }
    EXPECT_EQ(seen, (std::vector<std::string>{"PlaybackStarted <inline>", "PlaybackPosition 0.0",
                                              "PlaybackPosition 0.1", "PlaybackPosition 0.2",
                                              "PlaybackFinished completed"}));
    const auto rows = daemon.trace_rows();
    ASSERT_GE(rows.size(), 4u);
    // off at start, 235 Hz at full strength, off for the rest, 155 Hz at number 5, off.
    EXPECT_EQ(rows[1].amplitude, 1.0);
    EXPECT_EQ(rows[1].frequency_hz, 235.0);
    EXPECT_EQ(rows[2].amplitude, 0.0);
    EXPECT_NEAR((rows[2].time_ns - rows[1].time_ns) / 1e6, 100.0, 20.0);  // an 8th at tempo 0.2
    EXPECT_DOUBLE_EQ(rows[3].amplitude, 0.6);
    EXPECT_EQ(rows[3].frequency_hz, 155.0);
    EXPECT_EQ(rows.back().amplitude, 0.0);
}

TEST_F(DaemonBus, BusctlMonitorSeesThePlaybackSignals) {
    const auto log = daemon.store().parent_path() / "monitor.log";
    testing::Process monitor(
        {"/usr/bin/env", "DBUS_SYSTEM_BUS_ADDRESS=" + daemon.bus_address(), "/usr/bin/busctl",
         "--system", "monitor", "--match=type='signal',interface='org.vibscore.Haptics1'"},
        log);
    // busctl says so once the bus has made it a monitor.
    ASSERT_TRUE(testing::wait_until_file_contains(log, "Monitoring bus message stream."))
        << testing::read_file(log);
    auto client = daemon.client();
    const auto id = client->Play("touch-click", options());
    ASSERT_TRUE(client->wait_finished(id));
    EXPECT_TRUE(testing::wait_until_file_contains(log, "STRING \"completed\""))
        << testing::read_file(log);
    monitor.signal(SIGTERM);
    monitor.wait();
    std::ifstream in(log);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    const auto started = text.find("Member=PlaybackStarted");
    const auto position = text.find("Member=PlaybackPosition");
    const auto finished = text.find("Member=PlaybackFinished");
    ASSERT_NE(started, std::string::npos) << text;
    ASSERT_NE(position, std::string::npos) << text;
    ASSERT_NE(finished, std::string::npos) << text;
    EXPECT_LT(started, position);
    EXPECT_LT(position, finished);
    EXPECT_NE(text.find("STRING \"completed\""), std::string::npos) << text;
}

TEST_F(DaemonBus, BusctlStopSilencesARepeatingPlaybackAtOnce) {
    auto client = daemon.client();
    const auto id =
        client->Play("ringtone", options({{"repeat", sdbus::Variant(std::int32_t{-1})},
                                          {"usage", sdbus::Variant(std::string("ringtone"))}}));
    ASSERT_TRUE(client->wait_for([&](const testing::SeenSignal& seen) {
        return seen.name == "PlaybackStarted" && seen.id == id;
    }));
    const auto stopped = daemon.call({"Stop", "t", std::to_string(id)});
    ASSERT_EQ(stopped.exit_code, 0) << stopped.err;
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason));
    EXPECT_EQ(reason, "stopped");
    EXPECT_EQ(daemon.trace_rows().back().amplitude, 0.0);
}

TEST_F(DaemonBus, APlaybackEndsWhenItsCallerLeavesTheBus) {
    auto watcher = daemon.client();
    {
        auto caller = daemon.client();
        caller->Play("ringtone", options({{"repeat", sdbus::Variant(std::int32_t{-1})}}));
    }
    std::string reason;
    ASSERT_TRUE(watcher->wait_for([&](const SeenSignal& s) {
        reason = s.text;
        return s.name == "PlaybackFinished";
    }));
    EXPECT_EQ(reason, "client-vanished");
    EXPECT_EQ(daemon.trace_rows().back().amplitude, 0.0);
}

// The README's example: busctl leaves the bus as soon as Play returns, and the click still plays
// whole, every drive of its schedule in the sim's trace.
TEST_F(DaemonBus, TheReadmesBusctlPlayVibratesForTheWholeClickAfterBusctlLeaves) {
    const auto click = load_score_file(std::filesystem::path(std::getenv("VIBSCORE_CLEFS")) /
                                       "touch-click.score.xml");
    std::vector<render::Cue> expected;
    for (const auto& cue : render::cue_schedule(render::Performance(click))) {
        // The decrescendo's last step is a rounding residue (1e-16): the actuator is off there.
        if (cue.kind == render::Cue::Kind::drive && cue.amplitude > 1e-9) {
            expected.push_back(cue);
        }
    }
    ASSERT_GT(expected.size(), 2u);
    auto watcher = daemon.client();
    const auto played = daemon.call({"Play", "sa{sv}", "touch-click", "1", "usage", "s", "touch"});
    ASSERT_EQ(played.exit_code, 0) << played.err;
    std::string reason;
    ASSERT_TRUE(watcher->wait_for([&](const SeenSignal& s) {
        reason = s.text;
        return s.name == "PlaybackFinished";
    }));
    EXPECT_EQ(reason, "completed");

    std::vector<DaemonFixture::TraceRow> on;
    const auto rows = daemon.trace_rows();
    for (const auto& row : rows) {
        if (row.amplitude > 0.0) {
            on.push_back(row);
        }
    }
    ASSERT_EQ(on.size(), expected.size());
    for (std::size_t i = 0; i < on.size(); ++i) {
        EXPECT_NEAR(on[i].amplitude, expected[i].amplitude, 1e-6) << "drive " << i;
        EXPECT_NEAR(static_cast<double>(on[i].time_ns - on[0].time_ns) / 1e9,
                    expected[i].at - expected[0].at, 0.02)
            << "drive " << i;
    }
    EXPECT_EQ(rows.back().amplitude, 0.0);
    // The last drive lasts until the click's end (50 ms), not cut off when busctl left.
    const auto off = std::find_if(rows.begin(), rows.end(), [&](const auto& row) {
        return row.time_ns > on.back().time_ns && row.amplitude == 0.0;
    });
    ASSERT_NE(off, rows.end());
    EXPECT_NEAR(static_cast<double>(off->time_ns - on.front().time_ns) / 1e9,
                render::Performance(click).duration(), 0.02);
}

TEST_F(DaemonBus, UsageDecidesWhichPlaybackWins) {
    auto client = daemon.client();
    const auto touch =
        client->Play("ringtone", options({{"usage", sdbus::Variant(std::string("touch"))}}));
    const auto alarm =
        client->Play("alarm", options({{"usage", sdbus::Variant(std::string("alarm"))}}));
    std::string reason;
    ASSERT_TRUE(client->wait_finished(touch, &reason));
    EXPECT_EQ(reason, "preempted");
    EXPECT_EQ(
        error_name_of([&] {
            client->Play("touch-tick", options({{"usage", sdbus::Variant(std::string("touch"))}}));
        }).substr(0, 36),
        "org.vibscore.Haptics1.Error.Busy: a ");
    client->Stop(alarm);
}

TEST_F(DaemonBus, ARequestThatWouldBeRefusedIsRefusedBeforeItsScoreIsRead) {
    auto client = daemon.client();
    const auto alarm =
        client->Play("alarm", options({{"usage", sdbus::Variant(std::string("alarm"))},
                                       {"repeat", sdbus::Variant(std::int32_t{-1})}}));
    const auto touch = options({{"usage", sdbus::Variant(std::string("touch"))}});
    // Neither a broken document nor a missing one is looked at: the answer is Busy.
    EXPECT_EQ(error_name_of([&] { client->Play("<VibScore><Bar", touch); }).substr(0, 32),
              "org.vibscore.Haptics1.Error.Busy");
    EXPECT_EQ(error_name_of([&] { client->Play("no-such-score", touch); }).substr(0, 32),
              "org.vibscore.Haptics1.Error.Busy");
    client->Stop(alarm);
    EXPECT_EQ(error_name_of([&] { client->Play("<VibScore><Bar", touch); }).substr(0, 43),
              "org.vibscore.Haptics1.Error.InvalidDocument");
}

TEST_F(DaemonBus, OptionsChangeWhatPlays) {
    auto client = daemon.client();
    // The same score through the plain ERM clef: no frequency, strength from the line levels.
    const auto id =
        client->Play("touch-click", options({{"clef", sdbus::Variant(std::string("erm-phone"))},
                                             {"intensity", sdbus::Variant(0.5)}}));
    ASSERT_TRUE(client->wait_finished(id));
    const auto rows = daemon.trace_rows();
    ASSERT_GE(rows.size(), 2u);
    EXPECT_EQ(rows[1].frequency_hz, 0.0);
    EXPECT_GT(rows[1].amplitude, 0.0);
    EXPECT_LE(rows[1].amplitude, 0.5);
    const auto second = client->Play("alarm", options({{"start-bar", sdbus::Variant(1u)}}));
    ASSERT_TRUE(client->wait_for(
        [&](const SeenSignal& s) { return s.id == second && s.name == "PlaybackPosition"; }));
    for (const auto& s : client->signals()) {
        if (s.id == second && s.name == "PlaybackPosition") {
            EXPECT_EQ(s.text.substr(0, 2), "1.");
        }
    }
}

TEST_F(DaemonBus, BadInputGetsANamedErrorAndTheDaemonKeepsServing) {
    auto client = daemon.client();
    const std::pair<std::function<void()>, std::string> cases[] = {
        {[&] { client->Play("<VibScore>\n<Bar clef=\"x\">", options()); },
         "InvalidDocument: <inline score>:2:"},
        {[&] { client->Play("no-such-score", options()); }, "NotFound: no score \"no-such-score\""},
        {[&] {
             client->Play("touch-tick", options({{"repeat", sdbus::Variant(std::string("x"))}}));
         },
         "InvalidDocument: option \"repeat\" must be an int32"},
        {[&] {
             client->Play("touch-tick", options({{"volume", sdbus::Variant(1.0)}}));
         },
         "InvalidDocument: unknown option \"volume\""},
        {[&] {
             client->Play("touch-tick", options({{"usage", sdbus::Variant(std::string("loud"))}}));
         },
         "InvalidDocument: unknown usage \"loud\""},
        {[&] {
             client->Play("touch-tick", options({{"intensity", sdbus::Variant(1.5)}}));
         },
         "OutOfRange: intensity 1.5 is outside 0..1"},
        {[&] {
             client->Play("touch-tick", options({{"clef", sdbus::Variant(std::string("nope"))}}));
         },
         "NotFound"},
        {[&] {
             client->Play("touch-tick", options({{"start-bar", sdbus::Variant(7u)}}));
         },
         "OutOfRange: start-bar 7 is past the last bar"},
        {[&] { client->Play(std::string(2 << 20, '<'), options()); }, "LimitExceeded"},
        {[&] {
             client->Play(
                 "<VibScore><Clef id=\"c\" href=\"/etc/passwd\"/><Bar clef=\"c\"/>"
                 "</VibScore>",
                 options());
         },
         "InvalidDocument"},
        {[&] { client->Get("score", "../../etc/passwd"); }, "InvalidDocument"},
        {[&] { client->List("songs"); }, "InvalidDocument: unknown kind \"songs\""},
        {[&] { client->Compose("x", "<html/>"); }, "InvalidDocument"},
        {[&] { client->Compose("Bad/Name", kShortScore); }, "InvalidDocument"},
        {[&] { client->Delete("clef", "lra-phone"); }, "PermissionDenied"},
        {[&] { client->Stop(424242); }, "NotFound"},
    };
    for (const auto& [call, expected] : cases) {
        const auto error = error_name_of(call);
        EXPECT_NE(error.find("org.vibscore.Haptics1.Error." + expected), std::string::npos)
            << "expected " << expected << ", got " << error;
    }
    // Wrong argument types are refused by the bus layer itself.
    EXPECT_NE(daemon.call({"Stop", "s", "x"}).exit_code, 0);
    EXPECT_EQ(daemon.call({"List", "s", "clef"}).exit_code, 0);
    const auto id = client->Play("touch-tick", options());
    EXPECT_TRUE(client->wait_finished(id));
}

// No polkit on the private bus: the rule before polkit holds (root or group vibscore), and each
// refusal names the polkit action.
TEST_F(DaemonBus, AnUnprivilegedCallerMayPlayButNotComposeDeleteOrStopOthers) {
    auto client = daemon.client();  // root
    const auto played = daemon.call({"Play", "sa{sv}", "touch-tick", "0"}, kNobody);
    EXPECT_EQ(played.exit_code, 0) << played.err;
    const auto compose = daemon.call({"Compose", "ss", "mine", kShortScore}, kNobody);
    EXPECT_NE(compose.err.find("Compose needs org.vibscore.compose; polkit is not running, so "
                               "only root and group vibscore have it, and uid 65534 is neither"),
              std::string::npos)
        << compose.err;
    EXPECT_NE(daemon.call({"Delete", "ss", "score", "ringtone"}, kNobody)
                  .err.find("Delete needs org.vibscore.compose"),
              std::string::npos);
    const auto ringing =
        daemon.call({"Play", "sa{sv}", "touch-tick", "1", "usage", "s", "ringtone"}, kNobody);
    EXPECT_NE(ringing.err.find("Playing with usage ringtone needs org.vibscore.urgent-usage"),
              std::string::npos)
        << ringing.err;
    const auto id =
        client->Play("ringtone", options({{"repeat", sdbus::Variant(std::int32_t{-1})}}));
    const auto stop = daemon.call({"Stop", "t", std::to_string(id)}, kNobody);
    EXPECT_NE(stop.err.find("belongs to another user"), std::string::npos) << stop.err;
    EXPECT_FALSE(client->wait_finished(id, nullptr, std::chrono::milliseconds(100)));
    EXPECT_EQ(daemon.call({"Stop", "t", "0"}, kNobody).exit_code, 0);  // "mine": nothing
    EXPECT_FALSE(client->wait_finished(id, nullptr, std::chrono::milliseconds(50)));
    client->SetIntensity(0.25);  // root may
    EXPECT_EQ(client->Intensity(), 0.25);
    client->Stop(id);
}

TEST_F(DaemonBus, SigtermSwitchesTheActuatorOffAndExitsCleanly) {
    auto client = daemon.client();
    const auto id =
        client->Play("ringtone", options({{"repeat", sdbus::Variant(std::int32_t{-1})}}));
    ASSERT_TRUE(testing::wait_until([&] {
        const auto rows = daemon.trace_rows();
        return !rows.empty() && rows.back().amplitude > 0.0;
    }));  // playing: the actuator is on
    EXPECT_EQ(daemon.stop_daemon(), 0);
    EXPECT_EQ(daemon.trace_rows().back().amplitude, 0.0);
    EXPECT_NE(daemon.daemon_log().find("stopping"), std::string::npos);
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason));
    EXPECT_EQ(reason, "service-stopped") << "not a caller's Stop";
}

TEST_F(DaemonBus, SafeOffSwitchesTheActuatorOffAfterTheDaemonWasKilledMidNote) {
    const char* const kLongNote =
        "<VibScore><Title>long</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>"
        "<Bar clef=\"l\"><Note length=\"whole\" number=\"9\" string=\"6\"/></Bar></VibScore>";
    auto client = daemon.client();
    client->Play(kLongNote, options());
    testing::wait_until([&] {
        const auto rows = daemon.trace_rows();
        return !rows.empty() && rows.back().amplitude > 0.0;
    });  // the assertions below say what it found
    daemon.kill_daemon();
    const auto killed = daemon.trace_rows();
    ASSERT_FALSE(killed.empty());
    ASSERT_GT(killed.back().amplitude, 0.0) << "killed mid-note, left on";
    const auto safe_off = testing::run_command(
        {testing::required_env("VIBSCORED"), "--config", daemon.config().string(), "--safe-off"});
    EXPECT_EQ(safe_off.exit_code, 0) << safe_off.err;
    const auto after = daemon.trace_rows();
    ASSERT_GT(after.size(), killed.size()) << "the killed run's record is kept, not truncated";
    EXPECT_EQ(after[killed.size() - 1].time_ns, killed.back().time_ns);
    EXPECT_EQ(after.back().amplitude, 0.0);
}

TEST_F(DaemonBus, PlaybackIdsOfARestartedDaemonAreNewAndOldOnesAreNotFound) {
    auto client = daemon.client();
    const auto first = client->Play("touch-tick", options());
    const auto second = client->Play("touch-tick", options());
    EXPECT_EQ(second, first + 1);
    client.reset();
    daemon.kill_daemon();
    daemon.start_daemon();
    client = daemon.client();
    const auto after_restart =
        client->Play("ringtone", options({{"repeat", sdbus::Variant(std::int32_t{-1})}}));
    EXPECT_GT(after_restart, second);
    EXPECT_NE(after_restart & 0xffffffffu, 0u);
    EXPECT_EQ(error_name_of([&] { client->Stop(first); }).substr(0, 36),
              "org.vibscore.Haptics1.Error.NotFound");
    EXPECT_FALSE(client->wait_finished(after_restart, nullptr, std::chrono::milliseconds(100)))
        << "an earlier run's id stopped this playback";
    client->Stop(after_restart);
}

TEST_F(DaemonBus, ComposedDocumentsSurviveARestart) {
    auto client = daemon.client();
    client->Compose("kept", kShortScore);
    client.reset();
    EXPECT_EQ(daemon.stop_daemon(), 0);
    daemon.start_daemon();
    EXPECT_NE(daemon.call({"Get", "ss", "score", "kept"}).out.find("two notes"), std::string::npos);
}

TEST_F(DaemonBus, AcknowledgedComposesSurviveSigkillMidStream) {
    auto client = daemon.client();
    std::atomic<int> acknowledged{0};
    std::atomic<bool> stop{false};
    std::thread writer([&] {
        for (int i = 0; !stop; ++i) {
            const std::string title = "take " + std::to_string(i);
            std::string document = kShortScore;
            document.replace(document.find("two notes"), 9, title);
            try {
                client->Compose("stream-" + std::to_string(i % 7), document);
                acknowledged = i + 1;
            } catch (const sdbus::Error&) {
                break;  // the daemon died under us
            }
        }
    });
    // Killed mid-stream, once each of the seven names has been rewritten at least once.
    testing::wait_until([&] { return acknowledged.load() > 14; });
    daemon.kill_daemon();
    stop = true;
    writer.join();
    client.reset();
    ASSERT_GT(acknowledged.load(), 7);
    daemon.start_daemon();
    for (int stream = 0; stream < 7; ++stream) {
        // The newest acknowledged take of each name is stored whole (or a newer one whose reply
        // was lost in the kill); never a partial document.
        const auto got = daemon.call({"Get", "ss", "score", "stream-" + std::to_string(stream)});
        ASSERT_EQ(got.exit_code, 0) << got.err;
        const auto at = got.out.find("take ");
        ASSERT_NE(at, std::string::npos) << got.out;
        const int take = std::stoi(got.out.substr(at + 5));
        EXPECT_EQ(take % 7, stream);
        int newest_acknowledged = -1;
        for (int i = 0; i < acknowledged; ++i) {
            if (i % 7 == stream)
                newest_acknowledged = i;
        }
        EXPECT_GE(take, newest_acknowledged);
        EXPECT_NE(got.out.find("</VibScore>"), std::string::npos);
    }
    for (const auto& entry : std::filesystem::directory_iterator(daemon.store())) {
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
            << "temporary file left: " << entry.path();
    }
}

TEST_F(DaemonBus, SighupReloadsTheDriverAndKeepsServingOnABadFile) {
    auto client = daemon.client();
    const auto erm_trace = daemon.store().parent_path() / "erm-trace.csv";
    daemon.write_config("", "model = erm\ntrace = " + erm_trace.string());
    daemon.signal_daemon(SIGHUP);
    testing::wait_until([&] { return std::filesystem::exists(erm_trace); });
    ASSERT_TRUE(std::filesystem::exists(erm_trace)) << daemon.daemon_log();
    EXPECT_NE(daemon.daemon_log().find("configuration reloaded"), std::string::npos);
    const auto id = client->Play("touch-click", options());
    ASSERT_TRUE(client->wait_finished(id));
    std::ifstream trace(erm_trace);
    const std::string text{std::istreambuf_iterator<char>(trace), {}};
    EXPECT_NE(text.find(",1,235,"), std::string::npos) << text;

    daemon.write_config("separation-ms = lots", "");
    daemon.signal_daemon(SIGHUP);
    testing::wait_until(
        [&] { return daemon.daemon_log().find("reload failed") != std::string::npos; });
    EXPECT_NE(daemon.daemon_log().find("reload failed, keeping the running configuration: "),
              std::string::npos);
    EXPECT_NE(daemon.daemon_log().find("separation-ms = \"lots\""), std::string::npos);
    EXPECT_EQ(daemon.call({"List", "s", "clef"}).exit_code, 0);
}

// vibscored.conf's [clefs]: the device's own clef for the one a score names (thesis §4.4),
// shown by BarClefs and `vibscore info`, played, and reloaded with SIGHUP.
class DaemonDeviceClefs : public ::testing::Test {
  protected:
    DaemonFixture daemon{"[clefs]\nlra-phone = erm-phone\n"};
};

TEST_F(DaemonDeviceClefs, EachBarPlaysThroughTheMappedClefAsBarClefsAndInfoShow) {
    const auto bars = daemon.call({"BarClefs", "s", "success"});
    ASSERT_EQ(bars.exit_code, 0) << bars.err;
    EXPECT_EQ(bars.out, "a(ss) 1 \"lra-phone\" \"erm-phone\"\n");
    const auto info = vibscore::testing::run_command(
        {vibscore::testing::required_env("VIBSCORE"), "info", "success"});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("registry: shipped\non this device:\n  1  lra-phone -> erm-phone\n"),
              std::string::npos)
        << info.out;

    // lra-phone plays the click at 235 Hz; erm-phone is a line clef: drive levels, no frequency.
    auto client = daemon.client();
    ASSERT_TRUE(client->wait_finished(client->Play("touch-click", options())));
    int driven = 0;
    for (const auto& row : daemon.trace_rows()) {
        if (row.amplitude > 0.0) {
            ++driven;
            EXPECT_NE(row.frequency_hz, 235.0);
        }
    }
    EXPECT_GT(driven, 0);

    daemon.write_config("", "");
    daemon.signal_daemon(SIGHUP);
    std::string shown;
    testing::wait_until([&] {
        shown = daemon.call({"BarClefs", "s", "success"}).out;
        return shown.find("\"lra-phone\" \"lra-phone\"") != std::string::npos;
    });
    EXPECT_EQ(shown, "a(ss) 1 \"lra-phone\" \"lra-phone\"\n") << daemon.daemon_log();
    EXPECT_NE(daemon.daemon_log().find("device clefs: none"), std::string::npos);
}

TEST_F(DaemonBus, TellsTheServiceManagerItIsReadyAndAlive) {
    const auto socket_path = daemon.store().parent_path() / "notify";
    const int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    ASSERT_GE(fd, 0);
    const sockaddr_un address = testing::unix_socket_address(socket_path);
    ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    const timeval timeout{2, 0};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    daemon.kill_daemon();
    setenv("NOTIFY_SOCKET", socket_path.c_str(), 1);
    setenv("WATCHDOG_USEC", "200000", 1);
    daemon.start_daemon();
    unsetenv("NOTIFY_SOCKET");
    unsetenv("WATCHDOG_USEC");
    std::string received;
    char buffer[512];
    // The first ping comes as the loop is made, READY=1 once serving, then more pings.
    const auto seen_all = [&] {
        const auto ready = received.find("READY=1");
        const auto last_ping = received.rfind("WATCHDOG=1");
        return ready != std::string::npos && last_ping != std::string::npos && last_ping > ready;
    };
    for (int i = 0; i < 20 && !seen_all(); ++i) {
        const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
        if (n > 0)
            received.append(buffer, static_cast<std::size_t>(n)).append("|");
    }
    close(fd);
    EXPECT_TRUE(seen_all()) << received;
}

std::vector<std::string> vibscore_command(std::initializer_list<std::string> args) {
    std::vector<std::string> argv{testing::required_env("VIBSCORE")};
    argv.insert(argv.end(), args);
    return argv;
}

TEST_F(DaemonBus, TheClientPlaysAndWaitsListsComposesAndExplainsErrors) {
    const auto played =
        testing::run_command(vibscore_command({"play", "notification-message", "--wait"}));
    EXPECT_EQ(played.exit_code, 0) << played.err;
    // "playback N: bar 1"
    const auto id = played.out.substr(9, played.out.find_first_not_of("0123456789", 9) - 9);
    EXPECT_NE(played.out.find("playback " + id + ": bar 1"), std::string::npos) << played.out;
    EXPECT_NE(played.out.find("playback " + id + " completed"), std::string::npos) << played.out;
    const auto listed = testing::run_command(vibscore_command({"list", "clefs"}));
    EXPECT_NE(listed.out.find("lra-phone\tsine, tempo 0.2 s, 6 strings"), std::string::npos);
    const auto file = daemon.store().parent_path() / "mine.score.xml";
    std::ofstream(file) << kShortScore;
    EXPECT_EQ(testing::run_command(vibscore_command({"compose", "mine", file.string()})).exit_code,
              0);
    const auto from_file =
        testing::run_command(vibscore_command({"play", file.string(), "--wait"}));
    EXPECT_NE(from_file.out.find("completed"), std::string::npos) << from_file.err;
    const auto missing = testing::run_command(vibscore_command({"play", "nope"}));
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_EQ(missing.err, "vibscore: not found: no score \"nope\"\n");
    const auto not_root = testing::run_command(
        {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--",
         "/usr/bin/env", "DBUS_SYSTEM_BUS_ADDRESS=" + daemon.bus_address(),
         testing::required_env("VIBSCORE"), "delete", "score", "mine"});
    EXPECT_EQ(not_root.exit_code, 1);
    EXPECT_NE(not_root.err.find("vibscore: not permitted: Delete needs org.vibscore.compose"),
              std::string::npos)
        << not_root.err;
}

// `vibscore play --wait` on a ringtone that never ends, in the background; returns once the
// first bar has been shown.
std::unique_ptr<testing::Process> waiting_client(const std::filesystem::path& output) {
    auto waiting = std::make_unique<testing::Process>(
        vibscore_command({"play", "ringtone", "--usage", "ringtone", "--repeat", "-1", "--wait"}),
        output);
    testing::wait_until_file_contains(output, ": bar 1");
    EXPECT_NE(testing::read_file(output).find(": bar 1"), std::string::npos)
        << testing::read_file(output);
    return waiting;
}

TEST_F(DaemonBus, PlayWaitSaysTheDaemonLeftAndFailsWhenItIsKilled) {
    const auto output = daemon.store().parent_path() / "play-wait.out";
    auto waiting = waiting_client(output);
    daemon.kill_daemon();
    EXPECT_EQ(waiting->wait(), 1) << testing::read_file(output);
    EXPECT_NE(testing::read_file(output).find("vibscore: vibscored left the bus during playback "),
              std::string::npos)
        << testing::read_file(output);
}

TEST_F(DaemonBus, PlayWaitSaysTheServiceStoppedThePlaybackOnSigterm) {
    const auto output = daemon.store().parent_path() / "play-wait.out";
    auto waiting = waiting_client(output);
    EXPECT_EQ(daemon.stop_daemon(), 0);
    EXPECT_EQ(waiting->wait(), 1) << testing::read_file(output);
    EXPECT_NE(testing::read_file(output).find(" service-stopped\n"), std::string::npos)
        << testing::read_file(output);
}

TEST(ClientWithoutDaemon, SaysTheBusCannotBeReached) {
    setenv("DBUS_SYSTEM_BUS_ADDRESS", "unix:path=/nonexistent/bus", 1);
    const auto result = testing::run_command(vibscore_command({"list"}));
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.err.find("vibscore: cannot connect to the system bus"), std::string::npos)
        << result.err;
}

class RateLimitedDaemon : public ::testing::Test {
  protected:
    DaemonFixture daemon{"requests-per-second = 5\nrequest-burst = 5"};
};

// Twenty connections of one user are one caller: each busctl below is a connection of its own,
// and together they get one burst. Another user, and root, are not affected.
TEST_F(RateLimitedDaemon, AUsersConnectionsShareOneRateAndOtherUsersAreNotAffected) {
    int refused = 0;
    for (int i = 0; i < 20; ++i) {
        const auto listed = daemon.call({"List", "s", "clef"}, kNobody);
        if (listed.exit_code != 0) {
            EXPECT_NE(listed.err.find("too many requests from uid 65534"), std::string::npos)
                << listed.err;
            ++refused;
        }
    }
    EXPECT_GE(refused, 12);
    // A user the bus knows (dbus-daemon refuses a uid with no account).
    const passwd* other_user = getpwnam("daemon");
    ASSERT_NE(other_user, nullptr);
    const auto other = daemon.call({"List", "s", "clef"}, other_user->pw_uid);
    EXPECT_EQ(other.exit_code, 0) << other.err;
    auto root = daemon.client();
    for (int i = 0; i < 20; ++i) {
        EXPECT_NO_THROW(root->List("clef"));
    }
}

// A privileged "stop everyone's": a stranger's fire-and-forget ringtone that pins the actuator
// is ended by root; the stranger itself may not stop everyone's.
TEST_F(DaemonBus, StopAllEndsEveryonesPlaybackAndNeedsManage) {
    auto root = daemon.client();
    // Two more times: it ends by itself, so it plays on after busctl left.
    const auto started =
        daemon.call({"Play", "sa{sv}", "ringtone", "1", "repeat", "i", "2"}, kNobody);
    ASSERT_EQ(started.exit_code, 0) << started.err;
    ASSERT_TRUE(
        root->wait_for([](const SeenSignal& seen) { return seen.name == "PlaybackStarted"; }));
    const auto refused = daemon.call({"StopAll"}, kNobody);
    EXPECT_NE(refused.err.find("Stopping every user's playback needs org.vibscore.manage"),
              std::string::npos)
        << refused.err;
    const auto stopped = testing::run_command(vibscore_command({"stop", "--all"}));
    EXPECT_EQ(stopped.exit_code, 0) << stopped.err;
    EXPECT_EQ(stopped.out, "stopped every playback\n");
    EXPECT_TRUE(root->wait_for([](const SeenSignal& seen) {
        return seen.name == "PlaybackFinished" && seen.text == "stopped";
    }));
    const auto nothing = testing::run_command(vibscore_command({"stop", "--all"}));
    EXPECT_EQ(nothing.out, "nothing was playing\n");
    const auto both = testing::run_command(vibscore_command({"stop", "--all", "7"}));
    EXPECT_EQ(both.exit_code, 2) << both.err;
}

// A property set cannot wait for polkit, so Intensity is read-only and set through SetIntensity,
// which waits. The bus refuses a property set, root's too, without the daemon's code running.
TEST_F(DaemonBus, IntensityIsReadOnlyAndSetThroughSetIntensity) {
    for (const uid_t uid : {kNobody, uid_t{0}}) {
        const auto property =
            daemon.busctl({"set-property", "org.vibscore.Haptics1", "/org/vibscore/Haptics1",
                           "org.vibscore.Haptics1", "Intensity", "d", "0.2"},
                          uid);
        EXPECT_NE(property.exit_code, 0) << uid;
        EXPECT_NE(property.err.find("Property 'Intensity' is not writable"), std::string::npos)
            << property.err;
    }
    const auto connection = sdbus::createSystemBusConnection();
    const auto proxy =
        dbus::create_proxy(*connection, "org.vibscore.Haptics1", "/org/vibscore/Haptics1");
    try {
        proxy->setProperty("Intensity").onInterface("org.vibscore.Haptics1").toValue(0.2);
        ADD_FAILURE() << "setting the Intensity property was not refused";
    } catch (const sdbus::Error& error) {
        EXPECT_EQ(dbus::error_name(error), "org.freedesktop.DBus.Error.PropertyReadOnly")
            << error.getMessage();
    }
    auto root = daemon.client();
    EXPECT_EQ(root->Intensity(), 1.0);
    const auto method = daemon.call({"SetIntensity", "d", "0.2"}, kNobody);
    EXPECT_NE(method.err.find("Setting Intensity needs org.vibscore.manage; polkit is not "
                              "running"),
              std::string::npos)
        << method.err;
    EXPECT_EQ(daemon.call({"SetIntensity", "d", "0.3"}).exit_code, 0);
    EXPECT_EQ(root->Intensity(), 0.3);
}

// A number outside its range is OutOfRange, not InvalidDocument, at both edges of 0..1.
TEST_F(DaemonBus, SetIntensityTakesZeroToOneAndRefusesBeyondAsOutOfRange) {
    auto root = daemon.client();
    root->SetIntensity(1.0);
    EXPECT_EQ(root->Intensity(), 1.0);
    root->SetIntensity(0.0);
    EXPECT_EQ(root->Intensity(), 0.0);
    for (const double bad : {1.0000001, std::nextafter(1.0, 2.0), -1e-300, -0.5, 1.5}) {
        try {
            root->SetIntensity(bad);
            ADD_FAILURE() << "SetIntensity " << bad << " was not refused";
        } catch (const sdbus::Error& error) {
            EXPECT_EQ(dbus::error_name(error), "org.vibscore.Haptics1.Error.OutOfRange") << bad;
            EXPECT_NE(error.getMessage().find("is outside 0..1"), std::string::npos)
                << error.getMessage();
        }
    }
    EXPECT_EQ(root->Intensity(), 0.0);
    const auto outside = daemon.call({"SetIntensity", "d", "1.5"});
    EXPECT_NE(outside.err.find("Intensity 1.5 is outside 0..1"), std::string::npos) << outside.err;
}

// Debian's polkitd on the private bus. vibscore's actions are not installed on the test
// machine, so polkit answers each check with an error, which refuses, naming it.
class DaemonWithPolkit : public ::testing::Test {
  protected:
    DaemonFixture daemon{"", true};
};

TEST_F(DaemonWithPolkit, APolkitCheckIsAnsweredWithoutHoldingTheBus) {
    const auto ringing =
        daemon.call({"Play", "sa{sv}", "touch-tick", "1", "usage", "s", "ringtone"}, kNobody);
    EXPECT_NE(ringing.exit_code, 0);
    EXPECT_NE(ringing.err.find("Playing with usage ringtone needs org.vibscore.urgent-usage, and "
                               "polkit could not check it for uid 65534"),
              std::string::npos)
        << ringing.err;
}

// polkitd stopped (SIGSTOP): five unprivileged connections ask for a ringtone, each waiting for
// polkit (5 s, then refused); root's calls meanwhile are answered at once, as before.
TEST_F(DaemonWithPolkit, AStoppedPolkitHoldsOnlyTheCallsThatAskedIt) {
    daemon.polkit().signal(SIGSTOP);
    std::vector<std::unique_ptr<testing::Process>> askers;
    const auto dir = daemon.store().parent_path();
    // Watches vibscored ask polkit, so that root calls once all five askers are held there.
    const auto checks = dir / "checks.log";
    testing::Process monitor(
        {"/usr/bin/env", "DBUS_SYSTEM_BUS_ADDRESS=" + daemon.bus_address(), "/usr/bin/busctl",
         "--system", "monitor", "--match=type='method_call',member='CheckAuthorization'"},
        checks);
    ASSERT_TRUE(testing::wait_until_file_contains(checks, "Monitoring bus message stream."))
        << testing::read_file(checks);
    for (int i = 0; i < 5; ++i) {
        askers.push_back(std::make_unique<testing::Process>(
            std::vector<std::string>{"/usr/bin/setpriv",
                                     "--reuid=65534",
                                     "--regid=65534",
                                     "--clear-groups",
                                     "--",
                                     "/usr/bin/env",
                                     "DBUS_SYSTEM_BUS_ADDRESS=" + daemon.bus_address(),
                                     "/usr/bin/busctl",
                                     "--system",
                                     "call",
                                     "org.vibscore.Haptics1",
                                     "/org/vibscore/Haptics1",
                                     "org.vibscore.Haptics1",
                                     "Play",
                                     "sa{sv}",
                                     "touch-tick",
                                     "1",
                                     "usage",
                                     "s",
                                     "ringtone"},
            dir / ("asker" + std::to_string(i) + ".log")));
    }
    ASSERT_TRUE(testing::wait_until([&] {
        const auto text = testing::read_file(checks);
        std::size_t asked = 0;
        for (auto at = text.find("Member=CheckAuthorization"); at != std::string::npos;
             at = text.find("Member=CheckAuthorization", at + 1)) {
            ++asked;
        }
        return asked >= askers.size();
    })) << testing::read_file(checks);  // all five are waiting
    auto root = daemon.client();
    const auto started = std::chrono::steady_clock::now();
    for (int i = 0; i < 10; ++i) {
        root->List("score");
    }
    const auto took_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                             std::chrono::steady_clock::now() - started)
                             .count();
    // Held behind polkit, root's calls would come back only after the askers' (5 s): they are
    // all still waiting.
    for (auto& asker : askers) {
        EXPECT_TRUE(asker->running()) << "root's ten calls took " << took_ms << " ms";
    }
    for (std::size_t i = 0; i < askers.size(); ++i) {
        EXPECT_NE(askers[i]->wait(), 0);
        const auto said = testing::read_file(dir / ("asker" + std::to_string(i) + ".log"));
        EXPECT_NE(said.find("polkit could not check it for uid 65534"), std::string::npos) << said;
    }
    daemon.polkit().signal(SIGCONT);
}

// A socket's path fills sun_path but for its terminating NUL; one character more is refused.
TEST(BusFixture, ASocketAddressTakesTheLongestPathItHoldsAndRefusesOneLonger) {
    const std::string longest(sizeof(sockaddr_un::sun_path) - 1, 'a');
    const sockaddr_un address = testing::unix_socket_address(longest);
    EXPECT_EQ(address.sun_family, AF_UNIX);
    EXPECT_EQ(std::string(address.sun_path), longest);
    EXPECT_THROW(testing::unix_socket_address(longest + "a"), std::runtime_error);
}

// The fixtures' bus is ready when its socket accepts a connection: a socket file bound but not
// yet listening (dbus-daemon between bind() and listen()) is not, and a bus that exits at start
// says so with its log.
TEST(BusFixture, ABusIsReadyOnlyOnceItsSocketAcceptsAndOneThatExitsSaysSo) {
    const testing::TempDir dir;
    const auto socket_path = dir.path() / "bus";
    const UniqueFd fd(socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
    ASSERT_GE(fd.get(), 0);
    const sockaddr_un address = testing::unix_socket_address(socket_path);
    ASSERT_EQ(bind(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    testing::Process running({"/bin/cat"}, dir.path() / "running.log", /*stdin_pipe=*/true);
    try {
        testing::wait_until_bus_accepts(running, socket_path, dir.path() / "running.log");
        ADD_FAILURE() << "a socket that is bound but not listening was taken as ready";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("did not listen within 5 s"), std::string::npos)
            << e.what();
    }
    ASSERT_EQ(listen(fd.get(), 4), 0);
    EXPECT_NO_THROW(
        testing::wait_until_bus_accepts(running, socket_path, dir.path() / "running.log"));
    running.close_stdin();
    EXPECT_EQ(running.wait(), 0);

    dir.write("exited.log", "Failed to start message bus: the reason\n");
    testing::Process exited({"/bin/true"}, dir.path() / "exited-output.log");
    try {
        testing::wait_until_bus_accepts(exited, dir.path() / "none", dir.path() / "exited.log");
        ADD_FAILURE() << "a bus that exited was taken as ready";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("exited at start"), std::string::npos) << what;
        EXPECT_NE(what.find("the reason"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace vibscore
