// Onset lateness of a repeating ringtone while another client sends the largest accepted inline
// score as fast as the daemon lets it, interleaved with quiet stretches of the same length in one
// run (the quiet ones are the peer to compare with): the real vibscored with the sim driver on a
// private bus, measured through its trace file. Also the daemon's peak RSS. Prints a table and
// one JSON line; asserts nothing.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "bench/flood.hpp"
#include "bench/report.hpp"
#include "bench/summary.hpp"
#include "common/monotonic_clock.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "tests/support/daemon_fixture.hpp"

namespace {

using namespace vibscore;
using testing::DaemonFixture;
using Options = std::map<std::string, sdbus::Variant>;

struct Window {
    std::int64_t from_ns, until_ns;
    bool attack;
};

}  // namespace

int main(int argc, char** argv) {
    int rounds = 5;
    double window_s = 3.0;
    CLI::App app{
        "Onset lateness of a repeating ringtone with and without a client flooding Play "
        "with the largest accepted inline score (interleaved), and peak RSS."};
    app.add_option("--rounds", rounds, "quiet + attack pairs (default 5)");
    app.add_option("--window", window_s, "seconds of each stretch (default 3)");
    CLI11_PARSE(app, argc, argv);
    setenv("VIBSCORED", VIBSCORE_BENCH_VIBSCORED, 0);
    setenv("VIBSCORE_CLEFS", VIBSCORE_BENCH_CLEFS, 0);
    setenv("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF, 0);

    DaemonFixture daemon;
    const auto bundle = load_score_file(std::filesystem::path(std::getenv("VIBSCORE_CLEFS")) /
                                        "ringtone.score.xml");
    const render::Performance performance(bundle);
    std::vector<render::Cue> drives;
    for (const auto& cue : render::cue_schedule(performance)) {
        if (cue.kind == render::Cue::Kind::drive) {
            drives.push_back(cue);
        }
    }
    const double duration = performance.duration();
    const std::string attack_score = bench::largest_inline_score();

    auto ringtone_client = daemon.client();
    const auto first_row = daemon.trace_rows().size();
    const auto ringtone = ringtone_client->Play(
        "ringtone", Options{{"usage", sdbus::Variant(std::string("ringtone"))},
                            {"repeat", sdbus::Variant(std::int32_t{-1})}});
    std::vector<Window> windows;
    std::atomic<bool> attacking{false};
    std::atomic<bool> done{false};
    std::atomic<long> sent{0}, refused{0};
    std::thread attacker([&] {
        auto client = daemon.client();
        while (!done) {
            if (!attacking) {
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
                continue;
            }
            try {
                client->Play(attack_score, Options{});
            } catch (const sdbus::Error&) {
                ++refused;
            }
            ++sent;
        }
    });
    for (int round = 0; round < rounds; ++round) {
        for (const bool attack : {false, true}) {
            const auto from = static_cast<std::int64_t>(monotonic_now_us()) * 1000;
            attacking = attack;
            std::this_thread::sleep_for(std::chrono::duration<double>(window_s));
            attacking = false;
            windows.push_back({from, static_cast<std::int64_t>(monotonic_now_us()) * 1000, attack});
        }
    }
    done = true;
    attacker.join();
    const pid_t pid = bench::owner_pid(daemon);
    const long peak_kib = pid > 0 ? bench::status_kib(pid, "VmHWM") : -1;
    ringtone_client->Stop(ringtone);

    const auto all = daemon.trace_rows();
    const std::vector<DaemonFixture::TraceRow> rows(
        all.begin() + static_cast<std::ptrdiff_t>(first_row), all.end());
    std::vector<double> quiet_ms, attack_ms;
    const double first_at = drives.front().at;
    for (std::size_t i = 0; i + 1 < rows.size(); ++i) {  // the last row is Stop's off
        const auto& cue = drives[i % drives.size()];
        const double pass = static_cast<double>(i / drives.size());
        const double scheduled_s = pass * duration + cue.at - first_at;
        const double actual_s = static_cast<double>(rows[i].time_ns - rows[0].time_ns) / 1e9;
        const double late_ms = (actual_s - scheduled_s) * 1e3;
        for (const auto& window : windows) {
            if (rows[i].time_ns >= window.from_ns && rows[i].time_ns < window.until_ns) {
                (window.attack ? attack_ms : quiet_ms).push_back(late_ms);
            }
        }
    }
    const auto quiet = bench::summarize(quiet_ms);
    const auto attack = bench::summarize(attack_ms);
    std::printf("attack_bench (%s; a shared, noisy machine)\n", bench::cpu_model().c_str());
    std::printf("  %-8s %6s %10s %10s %10s\n", "", "cues", "p50 ms", "p99 ms", "max ms");
    std::printf("  %-8s %6zu %10.3f %10.3f %10.3f\n", "quiet", quiet.n, quiet.p50, quiet.p99,
                quiet.max);
    std::printf("  %-8s %6zu %10.3f %10.3f %10.3f\n", "attack", attack.n, attack.p50, attack.p99,
                attack.max);
    std::printf("  attacker: %ld Play calls of %zu bytes, %ld refused; daemon peak RSS %.1f MiB\n",
                sent.load(), attack_score.size(), refused.load(),
                static_cast<double>(peak_kib) / 1024.0);
    std::printf(
        "{\"bench\":\"attack\",%s,%s,\"attack_calls\":%ld,\"attack_refused\":%ld,"
        "\"peak_rss_kib\":%ld}\n",
        bench::json_summary("quiet_lateness", quiet).c_str(),
        bench::json_summary("attack_lateness", attack).c_str(), sent.load(), refused.load(),
        peak_kib);
    return 0;
}
