// feedback_bench: the feedbackd API side by side, in one run on one machine. Call round trips
// (call sent -> reply received) of TriggerFeedback on Debian's real feedbackd and on
// vibscore-feedback (each on a private session bus of its own), of vibscored's Play (private
// system bus), and of a bare D-Bus Peer.Ping to vibscore-feedback as the floor; the rounds are
// interleaved so the machine's noise falls on all alike. Prints a table and one JSON line.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <thread>

#include "bench/report.hpp"
#include "bench/summary.hpp"
#include "dbus/sdbus_compat.hpp"
#include "tests/support/feedback_fixture.hpp"

using namespace vibscore;
using namespace vibscore::bench;
using namespace std::chrono_literals;

namespace {

double ms_of(const std::function<void()>& call) {
    const auto start = std::chrono::steady_clock::now();
    call();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

void print(const char* name, const Summary& s) {
    std::printf("  %-34s n=%zu  p50 %.3f  p99 %.3f  max %.3f ms\n", name, s.n, s.p50, s.p99, s.max);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "feedback_bench - call round trips of TriggerFeedback on Debian's feedbackd and on\n"
        "vibscore-feedback, of vibscored's Play and of a bare D-Bus ping, interleaved, on\n"
        "private buses. Prints a table and one JSON line. VIBSCORED, VIBSCORE_FEEDBACK,\n"
        "VIBSCORE_CLEFS, VIBSCORE_FEEDBACK_THEME and VIBSCORE_PRIVATE_BUS_CONF override the\n"
        "build tree's paths.",
        "feedback_bench"};
    int rounds = 300;
    std::string event = "button-pressed";
    app.add_option("--rounds", rounds, "interleaved rounds (default 300)")
        ->check(CLI::Range(1, 100'000));
    app.add_option("--event", event, "the event triggered (default button-pressed)");
    CLI11_PARSE(app, argc, argv);

    for (const auto& [name, value] :
         {std::pair{"VIBSCORED", VIBSCORE_BENCH_VIBSCORED},
          std::pair{"VIBSCORE_FEEDBACK", VIBSCORE_BENCH_FEEDBACK},
          std::pair{"VIBSCORE_CLEFS", VIBSCORE_BENCH_CLEFS},
          std::pair{"VIBSCORE_FEEDBACK_THEME", VIBSCORE_BENCH_FEEDBACK_THEME},
          std::pair{"VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF}}) {
        setenv(name, value, 0);
    }
    if (!std::filesystem::exists("/usr/libexec/feedbackd")) {
        std::cerr << "feedback_bench: no /usr/libexec/feedbackd (Debian package feedbackd)\n";
        return 1;
    }

    // vibscored first: vibscore-feedback finds its private system bus in the environment.
    testing::DaemonFixture daemon;
    auto haptics = daemon.client();
    testing::SessionBus ours_bus, theirs_bus;
    testing::FeedbackServer ours(
        ours_bus,
        testing::vibscore_feedback({"--theme", testing::required_env("VIBSCORE_FEEDBACK_THEME")}));
    testing::FeedbackServer theirs(theirs_bus, testing::real_feedbackd());
    testing::FeedbackClient ours_client(ours_bus), theirs_client(theirs_bus);
    auto ping_connection = sdbus::createSessionBusConnectionWithAddress(ours_bus.address());
    auto ping =
        dbus::create_proxy(*ping_connection, testing::kFeedbackName, testing::kFeedbackPath);

    // No sound step in feedbackd (and the same entry in both themes): the quiet profile.
    const std::map<std::string, sdbus::Variant> hints{{"profile", sdbus::Variant("quiet")}};
    std::vector<double> ours_ms, theirs_ms, play_ms, ping_ms;
    for (int round = 0; round < rounds; ++round) {
        theirs_ms.push_back(
            ms_of([&] { theirs_client.TriggerFeedback("org.vibscore.Bench", event, hints, -1); }));
        ours_ms.push_back(
            ms_of([&] { ours_client.TriggerFeedback("org.vibscore.Bench", event, hints, -1); }));
        play_ms.push_back(ms_of([&] { haptics->Play("touch-tick", {}); }));
        ping_ms.push_back(
            ms_of([&] { ping->callMethod("Ping").onInterface("org.freedesktop.DBus.Peer"); }));
        std::this_thread::sleep_for(20ms);  // the 15 ms event ends before the next round
    }
    const auto theirs_s = summarize(theirs_ms), ours_s = summarize(ours_ms),
               play_s = summarize(play_ms), ping_s = summarize(ping_ms);
    const std::string cpu = cpu_model();
    std::printf(
        "feedback_bench: %d interleaved rounds, event %s (profile quiet), CPU %s, %u "
        "cores; a shared, noisy machine: compare the rows, not the absolute figures\n",
        rounds, event.c_str(), cpu.c_str(), std::thread::hardware_concurrency());
    print("TriggerFeedback, feedbackd", theirs_s);
    print("TriggerFeedback, vibscore-feedback", ours_s);
    print("Play, vibscored", play_s);
    print("Peer.Ping (bare D-Bus floor)", ping_s);
    const double speedup_p99 = theirs_s.p99 / ours_s.p99;
    const double over_ping_p99 = ours_s.p99 / ping_s.p99;
    std::printf(
        "  feedbackd / vibscore-feedback: p50 %.2fx, p99 %.2fx (aim >= 3x at p99); "
        "vibscore-feedback / ping: p50 %.2fx, p99 %.2fx (aim <= 2x)\n",
        theirs_s.p50 / ours_s.p50, speedup_p99, ours_s.p50 / ping_s.p50, over_ping_p99);
    std::printf(
        "{\"bench\":\"feedback\",\"cpu\":\"%s\",\"rounds\":%d,%s,%s,%s,%s,"
        "\"feedbackd_over_ours_p99\":%.3f,\"ours_over_ping_p99\":%.3f}\n",
        json_escape(cpu).c_str(), rounds, json_summary("feedbackd", theirs_s).c_str(),
        json_summary("vibscore_feedback", ours_s).c_str(), json_summary("play", play_s).c_str(),
        json_summary("ping", ping_s).c_str(), speedup_p99, over_ping_p99);
    return 0;
}
