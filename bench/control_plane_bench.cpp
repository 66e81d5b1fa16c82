// Root's List and Play round trips while unprivileged connections flood the daemon (issue 27):
// polkit-checked calls (Play with usage ringtone, which asks Debian's polkitd on the private
// bus), the largest accepted inline score, 30 MB names, and polkit-checked calls with polkitd
// stopped (SIGSTOP). 1, 8 and 20 flooding connections of one user (uid 65534), each its own
// thread in a flooder process this program starts as that user. Each of root's calls is
// interleaved with a Peer.Ping to the daemon (answered inside sd-bus, the floor) and measured in
// the same stretch, so the ratio to the floor means something on a noisy machine. Prints a table
// and one JSON line; asserts nothing.
#include <signal.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
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
enum class Flood { quiet, polkit, inline_score, big_name, polkit_stopped };

const char* name_of(Flood flood) {
    switch (flood) {
        case Flood::quiet:
            return "quiet";
        case Flood::polkit:
            return "polkit-checked";
        case Flood::inline_score:
            return "inline-score";
        case Flood::big_name:
            return "30MB-name";
        case Flood::polkit_stopped:
            return "polkit-stopped";
    }
    return "?";
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
    } else if (kind == "big") {
        score.assign(30u << 20, 'x');
    }
    std::vector<std::thread> threads;
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
                    } catch (const sdbus::Error& error) {
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

struct Row {
    Flood flood;
    int connections;
    bench::Summary list, play, ping;
    int timeouts = 0;         // root's calls that got no answer within D-Bus's 25 s
    int refused = 0;          // root's calls refused (an error other than no answer)
    double daemon_cpu_s = 0;  // vibscored's CPU time over the stretch
    double stretch_s = 0;
};

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

}  // namespace

int main(int argc, char** argv) {
    int samples = 200;
    std::string flood_kind;
    int flood_connections = 1;
    CLI::App app{
        "Root's List and Play round trips (p50/p99) while 1, 8 and 20 unprivileged connections "
        "flood vibscored with polkit-checked calls, the largest inline score and 30 MB names, and "
        "with polkitd stopped; each against a Peer.Ping floor measured in the same stretch."};
    app.add_option("--samples", samples, "root's calls of each kind per stretch (default 200)");
    app.add_option("--flood", flood_kind, "(internal) be a flooder: polkit, inline or big");
    app.add_option("--connections", flood_connections, "(internal) the flooder's connections");
    CLI11_PARSE(app, argc, argv);
    if (!flood_kind.empty()) {
        return flood(flood_kind, flood_connections);
    }
    setenv("VIBSCORED", VIBSCORE_BENCH_VIBSCORED, 0);
    setenv("VIBSCORE_CLEFS", VIBSCORE_BENCH_CLEFS, 0);
    setenv("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF, 0);

    testing::DaemonFixture daemon("", true);
    const auto self = std::filesystem::read_symlink("/proc/self/exe").string();
    auto root = daemon.client();
    auto ping_connection = sdbus::createSystemBusConnection();
    auto ping =
        dbus::create_proxy(*ping_connection, "org.vibscore.Haptics1", "/org/vibscore/Haptics1");

    const pid_t daemon_pid = bench::owner_pid(daemon);
    std::vector<Row> rows;
    const auto measure = [&](Flood flood, int connections) {
        std::unique_ptr<testing::Process> flooder;
        if (flood != Flood::quiet) {
            const std::string kind = flood == Flood::inline_score ? "inline"
                                     : flood == Flood::big_name   ? "big"
                                                                  : "polkit";
            if (flood == Flood::polkit_stopped) {
                daemon.polkit().signal(SIGSTOP);
            }
            flooder = std::make_unique<testing::Process>(
                std::vector<std::string>{
                    "/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--",
                    "/usr/bin/env", "DBUS_SYSTEM_BUS_ADDRESS=" + daemon.bus_address(), self,
                    "--flood", kind, "--connections", std::to_string(connections)},
                "/dev/null");
            std::this_thread::sleep_for(1s);  // flooding in earnest
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
        }
        const double stretch_s = ms_since(stretch_start) / 1000.0;
        const double daemon_cpu_s = bench::cpu_seconds(daemon_pid) - cpu_before;
        flooder.reset();
        if (flood == Flood::polkit_stopped) {
            daemon.polkit().signal(SIGCONT);
        }
        rows.push_back({flood, connections, bench::summarize(list_ms), bench::summarize(play_ms),
                        bench::summarize(ping_ms), timeouts, refused, daemon_cpu_s, stretch_s});
        const auto& row = rows.back();
        std::printf(
            "  %-15s %3d   List %7.2f %8.2f   Play %7.2f %8.2f   Ping %6.2f %7.2f   %5.0f%%  "
            "%d/%d\n",
            name_of(flood), connections, row.list.p50, row.list.p99, row.play.p50, row.play.p99,
            row.ping.p50, row.ping.p99, 100.0 * daemon_cpu_s / stretch_s, timeouts, refused);
        std::fflush(stdout);
    };

    std::printf(
        "control_plane_bench (%s; a shared, noisy machine: compare each row with its Ping)\n"
        "  %-15s %3s   %-18s   %-18s   %-16s   %6s  %s\n",
        bench::cpu_model().c_str(), "flood", "n", "List p50/p99 ms", "Play p50/p99 ms",
        "Ping p50/p99 ms", "daemon", "no answer/refused");
    measure(Flood::quiet, 0);
    for (const auto flood :
         {Flood::polkit, Flood::inline_score, Flood::big_name, Flood::polkit_stopped}) {
        for (const int connections : {1, 8, 20}) {
            measure(flood, connections);
        }
    }
    std::string json = "{\"bench\":\"control_plane\"";
    for (const auto& row : rows) {
        const std::string prefix =
            std::string(name_of(row.flood)) + "_" + std::to_string(row.connections);
        json += "," + bench::json_summary((prefix + "_list").c_str(), row.list) + "," +
                bench::json_summary((prefix + "_play").c_str(), row.play) + "," +
                bench::json_summary((prefix + "_ping").c_str(), row.ping) + ",\"" + prefix +
                "_timeouts\":" + std::to_string(row.timeouts) + ",\"" + prefix +
                "_refused\":" + std::to_string(row.refused) + ",\"" + prefix +
                "_daemon_cpu\":" + std::to_string(row.daemon_cpu_s / row.stretch_s);
    }
    std::printf("%s}\n", json.c_str());
    return 0;
}
