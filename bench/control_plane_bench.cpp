// Root's List and Play round trips while unprivileged connections flood the daemon. By default
// issue 33's probe (row 1): 1 MiB inline scores sent with Play as fast as the daemon answers (so
// at the largest rate its admission lets through) from 8 and 20 connections of uid 65534,
// interleaved with quiet stretches in the same run; meanwhile another connection of the same
// user (another app, its own process) makes paced List and Play calls, whose p99 is reported
// too. With --all, issue 27's floods as well: polkit-checked calls (Play with usage ringtone,
// which asks Debian's polkitd on the private bus), the largest inline score of issue 27, 30 MB
// names, and polkit-checked calls with polkitd stopped (SIGSTOP), from 1, 8 and 20 connections.
// Each of root's calls is interleaved with a Peer.Ping to the daemon (answered inside sd-bus,
// the floor) measured in the same stretch. Prints a table and one JSON line; asserts nothing.
#include <signal.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/flood.hpp"
#include "bench/report.hpp"
#include "bench/summary.hpp"
#include "dbus/sdbus_compat.hpp"
#include "tests/support/daemon_fixture.hpp"

namespace {

using namespace vibscore;
using namespace std::chrono_literals;
using Options = std::map<std::string, sdbus::Variant>;

// What a flooder sends, as many times as the daemon lets it.
enum class Flood { quiet, polkit, inline_score, mib_score, big_name, polkit_stopped };

const char* name_of(Flood flood) {
    switch (flood) {
        case Flood::quiet:
            return "quiet";
        case Flood::polkit:
            return "polkit-checked";
        case Flood::inline_score:
            return "inline-score";
        case Flood::mib_score:
            return "1MiB-inline";
        case Flood::big_name:
            return "30MB-name";
        case Flood::polkit_stopped:
            return "polkit-stopped";
    }
    return "?";
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// The flooder process: `connections` threads, each with a connection of its own, calling Play
// with what `kind` says until killed.
int flood(const std::string& kind, int connections) {
    std::string score = "touch-tick";
    Options options;
    if (kind == "polkit") {
        options["usage"] = sdbus::Variant(std::string("ringtone"));
    } else if (kind == "inline") {
        score = bench::largest_inline_score();
    } else if (kind == "mib") {
        score = bench::inline_score_of(1u << 20);
    } else if (kind == "big") {
        score.assign(30u << 20, 'x');
    }
    std::atomic<long> admitted{0}, refused{0};
    std::vector<std::thread> threads;
    // How many were admitted and refused, every second: the last line is the stretch's.
    threads.emplace_back([&] {
        for (;;) {
            std::this_thread::sleep_for(1s);
            std::printf("admitted %ld refused %ld\n", admitted.load(), refused.load());
            std::fflush(stdout);
        }
    });
    for (int i = 0; i < connections; ++i) {
        threads.emplace_back([&] {
            try {
                auto connection = sdbus::createSystemBusConnection();
                auto proxy = dbus::create_proxy(*connection, "org.vibscore.Haptics1",
                                                "/org/vibscore/Haptics1");
                for (;;) {
                    try {
                        std::uint64_t id = 0;
                        proxy->callMethod("Play")
                            .onInterface("org.vibscore.Haptics1")
                            .withArguments(score, options)
                            .storeResultsTo(id);
                        ++admitted;
                    } catch (const sdbus::Error& error) {
                        ++refused;
                        // Refused (rate, polkit, size): at once again, as an attacker would.
                        if (std::getenv("VIBSCORE_FLOOD_VERBOSE") != nullptr) {
                            std::fprintf(stderr, "flooder: %s\n", error.getMessage().c_str());
                        }
                    }
                }
            } catch (const std::exception& error) {
                std::fprintf(stderr, "flooder: %s\n", error.what());
            }
        });
    }
    for (auto& thread : threads) {
        thread.join();
    }
    return 0;
}

// Another app of the flooding user: one connection of its own, List and Play (touch-tick) in
// turn, 50 ms apart (20 calls a second, within a connection's share of the default request
// rate, 25), `samples` of each; prints "list P50 P99 play P50 P99 refused N".
int other_app(int samples) {
    auto connection = sdbus::createSystemBusConnection();
    auto proxy = dbus::create_proxy(*connection, "org.vibscore.Haptics1", "/org/vibscore/Haptics1");
    std::vector<double> list_ms, play_ms;
    int refused = 0;
    for (int i = 0; i < samples; ++i) {
        auto start = std::chrono::steady_clock::now();
        try {
            std::vector<sdbus::Struct<std::string, std::string>> entries;
            proxy->callMethod("List")
                .onInterface("org.vibscore.Haptics1")
                .withArguments(std::string("score"))
                .storeResultsTo(entries);
        } catch (const sdbus::Error&) {
            ++refused;
        }
        list_ms.push_back(ms_since(start));
        std::this_thread::sleep_for(50ms);
        start = std::chrono::steady_clock::now();
        try {
            std::uint64_t id = 0;
            proxy->callMethod("Play")
                .onInterface("org.vibscore.Haptics1")
                .withArguments(std::string("touch-tick"), Options{})
                .storeResultsTo(id);
        } catch (const sdbus::Error&) {
            ++refused;
        }
        play_ms.push_back(ms_since(start));
        std::this_thread::sleep_for(50ms);
    }
    const auto list = bench::summarize(list_ms);
    const auto play = bench::summarize(play_ms);
    std::printf("list %.4f %.4f play %.4f %.4f refused %d\n", list.p50, list.p99, play.p50,
                play.p99, refused);
    return 0;
}

struct Row {
    Flood flood;
    int connections;
    bench::Summary list, play, ping;
    bench::Summary other_list, other_play;  // another app of the flooding user; n = 0: none
    int other_refused = 0;
    long flood_admitted = -1, flood_refused = -1;  // the flooder's calls; -1: no flooder
    int timeouts = 0;         // root's calls that got no answer within D-Bus's 25 s
    int refused = 0;          // root's calls refused (an error other than no answer)
    double daemon_cpu_s = 0;  // vibscored's CPU time over the stretch
    double stretch_s = 0;
};

// Starts `argv` of this program as uid 65534 on the fixture's bus, its output to `output`.
std::unique_ptr<testing::Process> as_nobody(const testing::DaemonFixture& daemon,
                                            const std::vector<std::string>& args,
                                            const std::filesystem::path& output) {
    const auto self = std::filesystem::read_symlink("/proc/self/exe").string();
    std::vector<std::string> argv{"/usr/bin/setpriv",
                                  "--reuid=65534",
                                  "--regid=65534",
                                  "--clear-groups",
                                  "--",
                                  "/usr/bin/env",
                                  "DBUS_SYSTEM_BUS_ADDRESS=" + daemon.bus_address(),
                                  self};
    argv.insert(argv.end(), args.begin(), args.end());
    return std::make_unique<testing::Process>(argv, output);
}

// The last "admitted A refused R" line of a flooder's output.
void read_flood_counts(const std::filesystem::path& output, long& admitted, long& refused) {
    std::ifstream in(output);
    for (std::string line; std::getline(in, line);) {
        long a = 0, r = 0;
        if (std::sscanf(line.c_str(), "admitted %ld refused %ld", &a, &r) == 2) {
            admitted = a;
            refused = r;
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    int samples = 200;
    std::string flood_kind;
    int flood_connections = 1;
    int other_app_samples = 0;
    bool all = false;
    CLI::App app{
        "Root's List and Play round trips (p50/p99) while 8 and 20 connections of uid 65534 flood "
        "vibscored with 1 MiB inline scores, interleaved with quiet stretches, and another "
        "connection of that user calls List and Play meanwhile; with --all, also issue 27's "
        "floods (polkit-checked calls, the largest inline score, 30 MB names, polkitd stopped). "
        "Each against a Peer.Ping floor measured in the same stretch."};
    app.add_option("--samples", samples, "root's calls of each kind per stretch (default 200)");
    app.add_flag("--all", all, "issue 27's floods too, from 1, 8 and 20 connections");
    app.add_option("--flood", flood_kind, "(internal) be a flooder: polkit, inline, mib or big");
    app.add_option("--connections", flood_connections, "(internal) the flooder's connections");
    app.add_option("--other-app", other_app_samples, "(internal) be the other app: N calls each");
    CLI11_PARSE(app, argc, argv);
    if (!flood_kind.empty()) {
        return flood(flood_kind, flood_connections);
    }
    if (other_app_samples > 0) {
        return other_app(other_app_samples);
    }
    setenv("VIBSCORED", VIBSCORE_BENCH_VIBSCORED, 0);
    setenv("VIBSCORE_CLEFS", VIBSCORE_BENCH_CLEFS, 0);
    setenv("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF, 0);

    testing::DaemonFixture daemon("", true);
    auto root = daemon.client();
    auto ping_connection = sdbus::createSystemBusConnection();
    auto ping =
        dbus::create_proxy(*ping_connection, "org.vibscore.Haptics1", "/org/vibscore/Haptics1");
    const auto scratch = daemon.store().parent_path();

    const pid_t daemon_pid = bench::owner_pid(daemon);
    std::vector<Row> rows;
    const auto measure = [&](Flood flood, int connections) {
        std::unique_ptr<testing::Process> flooder, other;
        const auto flood_output = scratch / "flooder.out";
        const auto other_output = scratch / "other-app.out";
        std::filesystem::remove(flood_output);
        std::filesystem::remove(other_output);
        if (flood != Flood::quiet) {
            const std::string kind = flood == Flood::inline_score ? "inline"
                                     : flood == Flood::mib_score  ? "mib"
                                     : flood == Flood::big_name   ? "big"
                                                                  : "polkit";
            if (flood == Flood::polkit_stopped) {
                daemon.polkit().signal(SIGSTOP);
            }
            flooder =
                as_nobody(daemon, {"--flood", kind, "--connections", std::to_string(connections)},
                          flood_output);
            std::this_thread::sleep_for(1s);  // flooding in earnest
        }
        if (flood == Flood::quiet || flood == Flood::mib_score) {
            other = as_nobody(daemon, {"--other-app", std::to_string(samples / 2)}, other_output);
        }
        std::vector<double> list_ms, play_ms, ping_ms;
        int timeouts = 0, refused = 0;
        // A call with no answer counts as taking the whole time it waited.
        const auto timed = [&](std::vector<double>& into, const auto& call) {
            const auto start = std::chrono::steady_clock::now();
            try {
                call();
            } catch (const sdbus::Error& error) {
                ++(dbus::error_name(error) == "org.freedesktop.DBus.Error.NoReply" ? timeouts
                                                                                   : refused);
            }
            into.push_back(ms_since(start));
        };
        const double cpu_before = bench::cpu_seconds(daemon_pid);
        const auto stretch_start = std::chrono::steady_clock::now();
        // Three calls without an answer (25 s each) say enough: the stretch ends there.
        for (int i = 0; i < samples && timeouts < 3; ++i) {
            timed(ping_ms,
                  [&] { ping->callMethod("Ping").onInterface("org.freedesktop.DBus.Peer"); });
            timed(list_ms, [&] { root->List("score"); });
            timed(play_ms, [&] { root->Stop(root->Play("touch-tick", {})); });
            // Paced, so root's samples span the stretch as the other app's do (about 10 s at
            // the default 200), not the first fraction of a second of it.
            std::this_thread::sleep_for(50ms);
        }
        Row row{flood, connections, bench::summarize(list_ms), bench::summarize(play_ms),
                bench::summarize(ping_ms)};
        if (other) {
            other->wait();  // its paced calls, still under the flood
            std::ifstream in(other_output);
            double list_p50 = 0, list_p99 = 0, play_p50 = 0, play_p99 = 0;
            std::string line;
            std::getline(in, line);
            if (std::sscanf(line.c_str(), "list %lf %lf play %lf %lf refused %d", &list_p50,
                            &list_p99, &play_p50, &play_p99, &row.other_refused) == 5) {
                row.other_list = {static_cast<std::size_t>(samples / 2), 0, list_p50, list_p99, 0};
                row.other_play = {static_cast<std::size_t>(samples / 2), 0, play_p50, play_p99, 0};
            }
        }
        const double stretch_s = ms_since(stretch_start) / 1000.0;
        const double daemon_cpu_s = bench::cpu_seconds(daemon_pid) - cpu_before;
        if (flooder) {
            read_flood_counts(flood_output, row.flood_admitted, row.flood_refused);
        }
        flooder.reset();
        if (flood == Flood::polkit_stopped) {
            daemon.polkit().signal(SIGCONT);
        }
        row.timeouts = timeouts;
        row.refused = refused;
        row.daemon_cpu_s = daemon_cpu_s;
        row.stretch_s = stretch_s;
        rows.push_back(row);
        std::printf(
            "  %-15s %3d   List %7.2f %8.2f   Play %7.2f %8.2f   Ping %6.2f %7.2f   %5.0f%%  "
            "%d/%d",
            name_of(flood), connections, row.list.p50, row.list.p99, row.play.p50, row.play.p99,
            row.ping.p50, row.ping.p99, 100.0 * daemon_cpu_s / stretch_s, timeouts, refused);
        if (row.other_list.n > 0) {
            std::printf("   other app List %.2f/%.2f Play %.2f/%.2f refused %d", row.other_list.p50,
                        row.other_list.p99, row.other_play.p50, row.other_play.p99,
                        row.other_refused);
        }
        if (row.flood_admitted >= 0) {
            std::printf("   flood %.1f admitted/s, %.0f refused/s",
                        static_cast<double>(row.flood_admitted) / (stretch_s + 1.0),
                        static_cast<double>(row.flood_refused) / (stretch_s + 1.0));
        }
        std::printf("\n");
        std::fflush(stdout);
    };

    std::printf(
        "control_plane_bench (%s; a shared, noisy machine: compare each row with its Ping)\n"
        "  %-15s %3s   %-18s   %-18s   %-16s   %6s  %s\n",
        bench::cpu_model().c_str(), "flood", "n", "List p50/p99 ms", "Play p50/p99 ms",
        "Ping p50/p99 ms", "daemon", "no answer/refused");
    // Issue 33's probe, interleaved with quiet stretches.
    measure(Flood::quiet, 0);
    measure(Flood::mib_score, 8);
    measure(Flood::quiet, 0);
    measure(Flood::mib_score, 20);
    measure(Flood::quiet, 0);
    if (all) {
        for (const auto flood :
             {Flood::polkit, Flood::inline_score, Flood::big_name, Flood::polkit_stopped}) {
            for (const int connections : {1, 8, 20}) {
                measure(flood, connections);
            }
        }
    }
    // With and without the flood: the quiet stretches' samples against each flood's.
    std::vector<double> quiet_list_p99, quiet_play_p99;
    for (const auto& row : rows) {
        if (row.flood == Flood::quiet) {
            quiet_list_p99.push_back(row.list.p99);
            quiet_play_p99.push_back(row.play.p99);
        }
    }
    const double quiet_list = bench::summarize(quiet_list_p99).p50;
    const double quiet_play = bench::summarize(quiet_play_p99).p50;
    std::string json = "{\"bench\":\"control_plane\"";
    int quiet_index = 0;
    for (const auto& row : rows) {
        std::string prefix =
            std::string(name_of(row.flood)) + "_" + std::to_string(row.connections);
        if (row.flood == Flood::quiet) {
            prefix += "_" + std::to_string(++quiet_index);
        } else if (row.flood == Flood::mib_score) {
            std::printf(
                "  %s %d: root's p99 with / without the flood: List %.2f / %.2f ms (x%.2f), "
                "Play %.2f / %.2f ms (x%.2f); other app of uid 65534 p99: List %.2f ms, "
                "Play %.2f ms\n",
                name_of(row.flood), row.connections, row.list.p99, quiet_list,
                row.list.p99 / quiet_list, row.play.p99, quiet_play, row.play.p99 / quiet_play,
                row.other_list.p99, row.other_play.p99);
            json += ",\"" + prefix +
                    "_list_p99_ratio\":" + std::to_string(row.list.p99 / quiet_list) + ",\"" +
                    prefix + "_play_p99_ratio\":" + std::to_string(row.play.p99 / quiet_play);
        }
        json += "," + bench::json_summary((prefix + "_list").c_str(), row.list) + "," +
                bench::json_summary((prefix + "_play").c_str(), row.play) + "," +
                bench::json_summary((prefix + "_ping").c_str(), row.ping) + ",\"" + prefix +
                "_timeouts\":" + std::to_string(row.timeouts) + ",\"" + prefix +
                "_refused\":" + std::to_string(row.refused) + ",\"" + prefix +
                "_daemon_cpu\":" + std::to_string(row.daemon_cpu_s / row.stretch_s);
        if (row.other_list.n > 0) {
            json +=
                "," + bench::json_summary((prefix + "_other_app_list").c_str(), row.other_list) +
                "," + bench::json_summary((prefix + "_other_app_play").c_str(), row.other_play) +
                ",\"" + prefix + "_other_app_refused\":" + std::to_string(row.other_refused);
        }
        if (row.flood_admitted >= 0) {
            json += ",\"" + prefix + "_flood_admitted\":" + std::to_string(row.flood_admitted) +
                    ",\"" + prefix + "_flood_refused\":" + std::to_string(row.flood_refused);
        }
    }
    std::printf("%s}\n", json.c_str());
    return 0;
}
