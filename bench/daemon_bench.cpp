// Daemon benchmark: the real vibscored with the sim driver on a private bus (the integration
// tests' DaemonFixture), measured from the outside through its trace file and its /proc entry:
// Play -> first drive latency, Stop -> actuator off latency, onset accuracy over a long score,
// idle wake-ups and memory, and many concurrent clients. Prints a table and one JSON line;
// asserts nothing.
#include <CLI/CLI.hpp>

#include <csignal>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

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
using TraceRow = DaemonFixture::TraceRow;
using Options = std::map<std::string, sdbus::Variant>;

// Limits high enough that the daemon's per-caller rate limiter never refuses a request.
const char* const kHighLimitConfig = "requests-per-second = 100000\nrequest-burst = 100000";

struct Settings {
    bool quick = false;
    int plays = 1000;
    int stops = 1000;
    double onset_seconds = 600.0;
    std::string onset_score = "ode-to-joy";
    double idle_seconds = 10.0;
    int clients = 32;
    double concurrency_seconds = 30.0;
    double pairs_per_second = 10.0;
    bool high_limit_for_clients = false;
};

void sleep_ms(double ms) {
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(ms));
}

using vibscore::bench::cpu_model;
using vibscore::bench::json_escape;
using vibscore::bench::summarize;
using vibscore::bench::Summary;

const char* verdict(bool ok) {
    return ok ? "ok" : "MISSED";
}

// Rows of `rows` from `first` on whose time is in [from, until) and that satisfy `match`; the
// index of the first one, or rows.size().
template <typename Match>
std::size_t find_row(const std::vector<TraceRow>& rows, std::size_t first, std::int64_t from,
                     std::int64_t until, Match&& match) {
    auto it =
        std::lower_bound(rows.begin() + static_cast<std::ptrdiff_t>(first), rows.end(), from,
                         [](const TraceRow& row, std::int64_t time) { return row.time_ns < time; });
    for (; it != rows.end() && it->time_ns < until; ++it) {
        if (match(*it)) {
            return static_cast<std::size_t>(it - rows.begin());
        }
    }
    return rows.size();
}

// ---- 1 and 2: command latency seen on the actuator -----------------------------------------

struct LatencyResult {
    Summary ms;
    int missed = 0;  // no matching trace row before the next attempt
    int errors = 0;  // bus errors
};

// Each attempt: t0 just before the call that should move the actuator, and the time after
// which a row can no longer belong to this attempt.
struct Attempt {
    std::int64_t t0 = 0;
    std::int64_t until = 0;
};

template <typename Match>
LatencyResult match_attempts(const DaemonFixture& daemon, std::size_t first_row,
                             const std::vector<Attempt>& attempts, int errors, Match&& match) {
    const auto rows = daemon.trace_rows();
    LatencyResult result;
    result.errors = errors;
    std::vector<double> ms;
    std::size_t cursor = first_row;
    for (const auto& attempt : attempts) {
        const auto found = find_row(rows, cursor, attempt.t0, attempt.until, match);
        if (found == rows.size()) {
            ++result.missed;
            continue;
        }
        ms.push_back(static_cast<double>(rows[found].time_ns - attempt.t0) / 1e6);
        cursor = found;
    }
    result.ms = summarize(std::move(ms));
    return result;
}

LatencyResult play_latency(DaemonFixture& daemon, int count) {
    auto client = daemon.client();
    const auto first_row = daemon.trace_rows().size();
    const Options touch{{"usage", sdbus::Variant(std::string("touch"))}};
    std::vector<Attempt> attempts;
    int errors = 0;
    for (int i = 0; i < count; ++i) {
        const auto t0 = monotonic_now_ns();
        try {
            const auto id = client->Play("touch-tick", touch);
            client->Stop(id);
        } catch (const sdbus::Error&) {
            ++errors;
        }
        sleep_ms(2.0);
        if (!attempts.empty()) {
            attempts.back().until = t0;
        }
        attempts.push_back({t0, std::numeric_limits<std::int64_t>::max()});
    }
    return match_attempts(daemon, first_row, attempts, errors,
                          [](const TraceRow& row) { return row.amplitude > 0.0; });
}

LatencyResult stop_latency(DaemonFixture& daemon, int count) {
    auto client = daemon.client();
    const auto first_row = daemon.trace_rows().size();
    const Options ringing{{"usage", sdbus::Variant(std::string("ringtone"))},
                          {"repeat", sdbus::Variant(std::int32_t{-1})}};
    std::vector<Attempt> attempts;
    int errors = 0;
    for (int i = 0; i < count; ++i) {
        const auto played_at = monotonic_now_ns();
        if (!attempts.empty()) {
            attempts.back().until = played_at;
        }
        std::uint64_t id = 0;
        try {
            id = client->Play("ringtone", ringing);
        } catch (const sdbus::Error&) {
            ++errors;
            continue;
        }
        sleep_ms(5.0);
        const auto t0 = monotonic_now_ns();
        try {
            client->Stop(id);
        } catch (const sdbus::Error&) {
            ++errors;
        }
        attempts.push_back({t0, std::numeric_limits<std::int64_t>::max()});
        sleep_ms(2.0);
    }
    return match_attempts(daemon, first_row, attempts, errors,
                          [](const TraceRow& row) { return row.amplitude == 0.0; });
}

// ---- 3: onset accuracy ------------------------------------------------------------------------

struct OnsetResult {
    std::string score;
    int passes = 0;
    double seconds = 0;        // scheduled length of the whole playback
    std::size_t expected = 0;  // drive rows the schedule asks for
    std::size_t rows = 0;      // rows the playback wrote (drives and the final off)
    std::size_t compared = 0;  // rows paired with a cue
    std::size_t amplitude_mismatches = 0;
    std::string reason;  // PlaybackFinished reason
    Summary abs_error_ms;
    double last_error_ms = 0;  // signed: actual - scheduled of the last cue (drift)
    double slope_ppm = 0;      // least-squares trend of the error over time
};

OnsetResult onset_accuracy(DaemonFixture& daemon, const Settings& settings) {
    OnsetResult result;
    result.score = settings.onset_score;
    // The same schedule the daemon builds: the shipped score through its clefs, with the
    // daemon's default separation (30 ms, also RenderOptions' default) and cue options.
    const auto bundle = load_score_file(std::filesystem::path(std::getenv("VIBSCORE_CLEFS")) /
                                        (settings.onset_score + ".score.xml"));
    const render::Performance performance(bundle);
    std::vector<render::Cue> drives;
    for (const auto& cue : render::cue_schedule(performance)) {
        if (cue.kind == render::Cue::Kind::drive) {
            drives.push_back(cue);
        }
    }
    const double duration = performance.duration();
    result.passes = std::max(1, static_cast<int>(std::ceil(settings.onset_seconds / duration)));
    result.seconds = duration * result.passes;
    result.expected = drives.size() * static_cast<std::size_t>(result.passes);

    auto client = daemon.client();
    const auto first_row = daemon.trace_rows().size();
    std::fprintf(stderr, "onset: playing %s %d time(s), %.0f s...\n", result.score.c_str(),
                 result.passes, result.seconds);
    const auto started = std::chrono::steady_clock::now();
    const auto id = client->Play(
        settings.onset_score, Options{{"repeat", sdbus::Variant(std::int32_t{result.passes - 1})}});
    // Sleep through most of it without polling the client's signal list.
    const auto near_end = started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>(result.seconds - 2.0));
    while (std::chrono::steady_clock::now() < near_end) {
        std::this_thread::sleep_for(std::min<std::chrono::steady_clock::duration>(
            near_end - std::chrono::steady_clock::now(), std::chrono::seconds(1)));
    }
    if (!client->wait_finished(id, &result.reason, std::chrono::seconds(60))) {
        result.reason = "<not finished>";
    }

    const auto all = daemon.trace_rows();
    const std::vector<TraceRow> rows(all.begin() + static_cast<std::ptrdiff_t>(first_row),
                                     all.end());
    result.rows = rows.size();
    result.compared = std::min(rows.size(), result.expected);
    if (result.compared == 0) {
        return result;
    }
    const double first_at = drives.front().at;
    std::vector<double> abs_ms;
    double sum_t = 0, sum_e = 0, sum_tt = 0, sum_te = 0;
    for (std::size_t i = 0; i < result.compared; ++i) {
        const auto& cue = drives[i % drives.size()];
        const double pass = static_cast<double>(i / drives.size());
        const double scheduled_s = pass * duration + cue.at - first_at;
        const double actual_s = static_cast<double>(rows[i].time_ns - rows[0].time_ns) / 1e9;
        const double error_ms = (actual_s - scheduled_s) * 1e3;
        abs_ms.push_back(std::abs(error_ms));
        sum_t += scheduled_s;
        sum_e += error_ms;
        sum_tt += scheduled_s * scheduled_s;
        sum_te += scheduled_s * error_ms;
        if (std::abs(rows[i].amplitude - std::clamp(cue.amplitude, 0.0, 1.0)) > 1e-9) {
            ++result.amplitude_mismatches;
        }
        result.last_error_ms = error_ms;
    }
    const double n = static_cast<double>(result.compared);
    const double denominator = n * sum_tt - sum_t * sum_t;
    if (denominator > 0) {
        // ms of error per s of playback, times 1000 = parts per million.
        result.slope_ppm = (n * sum_te - sum_t * sum_e) / denominator * 1e3;
    }
    result.abs_error_ms = summarize(std::move(abs_ms));
    return result;
}

// ---- 4: idle daemon -----------------------------------------------------------------------------

pid_t daemon_pid(const DaemonFixture& daemon) {
    const auto status = daemon.busctl({"status", "--no-pager", "org.vibscore.Haptics1"});
    std::istringstream lines(status.out);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind("PID=", 0) == 0) {
            return static_cast<pid_t>(std::stol(line.substr(4)));
        }
    }
    throw std::runtime_error("busctl status did not name the daemon's PID:\n" + status.out +
                             status.err);
}

// A number field ("VmRSS:  1234 kB" -> 1234) of a /proc status file; -1 if absent.
long status_field(const std::filesystem::path& file, const std::string& key) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key + ":", 0) == 0) {
            return std::stol(line.substr(key.size() + 1));
        }
    }
    return -1;
}

struct ProcessSample {
    long context_switches = 0;  // voluntary + nonvoluntary, summed over every thread
    int threads = 0;
    double rss_mib = 0;
};

ProcessSample sample_process(pid_t pid) {
    ProcessSample sample;
    const std::filesystem::path proc = "/proc/" + std::to_string(pid);
    for (const auto& task : std::filesystem::directory_iterator(proc / "task")) {
        sample.context_switches +=
            status_field(task.path() / "status", "voluntary_ctxt_switches") +
            status_field(task.path() / "status", "nonvoluntary_ctxt_switches");
        ++sample.threads;
    }
    sample.rss_mib = static_cast<double>(status_field(proc / "status", "VmRSS")) / 1024.0;
    return sample;
}

struct IdleResult {
    pid_t pid = 0;
    long wakeups = 0;
    int threads = 0;
    double rss_mib = 0;
};

IdleResult idle_daemon(const DaemonFixture& daemon, double seconds) {
    IdleResult result;
    result.pid = daemon_pid(daemon);  // a bus client; let the daemon see it come and go first
    sleep_ms(1000.0);
    const auto before = sample_process(result.pid);
    sleep_ms(seconds * 1e3);
    const auto after = sample_process(result.pid);
    result.wakeups = after.context_switches - before.context_switches;
    result.threads = after.threads;
    result.rss_mib = after.rss_mib;
    return result;
}

// ---- 5: concurrent clients ----------------------------------------------------------------------

struct ConcurrencyResult {
    std::string limiter;
    long calls = 0;
    long errors = 0;
    std::map<std::string, long> error_names;
    Summary all_ms, play_ms, stop_ms;
};

void use_default_limiter(DaemonFixture& daemon) {
    const auto reloads = [&] {
        const auto log = daemon.daemon_log();
        std::size_t count = 0;
        for (auto at = log.find("configuration reloaded"); at != std::string::npos;
             at = log.find("configuration reloaded", at + 1)) {
            ++count;
        }
        return count;
    };
    const auto before = reloads();
    // The same [sim] settings, so the daemon keeps its actuator and trace; [daemon] defaults.
    daemon.write_config("", "trace = " + daemon.trace().string());
    daemon.signal_daemon(SIGHUP);
    for (int i = 0; i < 500 && reloads() == before; ++i) {
        sleep_ms(10.0);
    }
    if (reloads() == before) {
        throw std::runtime_error("the daemon did not reload its configuration:\n" +
                                 daemon.daemon_log());
    }
}

ConcurrencyResult concurrent_clients(DaemonFixture& daemon, const Settings& settings) {
    ConcurrencyResult result;
    if (settings.high_limit_for_clients) {
        result.limiter = "high (100000/s, burst 100000)";
    } else {
        use_default_limiter(daemon);
        result.limiter = "default (50/s, burst 100 per client)";
    }
    struct Worker {
        std::unique_ptr<testing::HapticsClient> client;
        std::vector<double> play_ms, stop_ms;
        long errors = 0;
        std::map<std::string, long> error_names;
        std::thread thread;
    };
    std::vector<Worker> workers(static_cast<std::size_t>(settings.clients));
    for (auto& worker : workers) {
        worker.client = daemon.client();
    }
    const Options touch{{"usage", sdbus::Variant(std::string("touch"))}};
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / settings.pairs_per_second));
    const auto start = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
    const auto end = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(settings.concurrency_seconds));
    for (std::size_t i = 0; i < workers.size(); ++i) {
        workers[i].thread = std::thread([&, i] {
            auto& worker = workers[i];
            const auto timed = [&](std::vector<double>& into, const auto& call) {
                const auto t0 = monotonic_now_ns();
                try {
                    call();
                    into.push_back(static_cast<double>(monotonic_now_ns() - t0) / 1e6);
                    return true;
                } catch (const sdbus::Error& error) {
                    into.push_back(static_cast<double>(monotonic_now_ns() - t0) / 1e6);
                    ++worker.errors;
                    ++worker.error_names[error.getName()];
                    return false;
                }
            };
            // Spread the clients across the period rather than all calling at once.
            auto next = start + period * static_cast<long>(i) / static_cast<long>(workers.size());
            for (; next < end; next += period) {
                std::this_thread::sleep_until(next);
                std::uint64_t id = 0;
                if (timed(worker.play_ms, [&] { id = worker.client->Play("touch-tick", touch); })) {
                    timed(worker.stop_ms, [&] { worker.client->Stop(id); });
                }
            }
        });
    }
    std::vector<double> all, play, stop;
    for (auto& worker : workers) {
        worker.thread.join();
        play.insert(play.end(), worker.play_ms.begin(), worker.play_ms.end());
        stop.insert(stop.end(), worker.stop_ms.begin(), worker.stop_ms.end());
        result.errors += worker.errors;
        for (const auto& [name, count] : worker.error_names) {
            result.error_names[name] += count;
        }
    }
    workers.clear();  // leave the bus before the results are read
    all = play;
    all.insert(all.end(), stop.begin(), stop.end());
    result.calls = static_cast<long>(all.size());
    result.all_ms = summarize(std::move(all));
    result.play_ms = summarize(std::move(play));
    result.stop_ms = summarize(std::move(stop));
    return result;
}

// ---- output -------------------------------------------------------------------------------------

void print_latency(const char* name, const LatencyResult& r, double target_ms) {
    std::printf(
        "  %-26s n=%zu  p50 %.3f  p99 %.3f  max %.3f ms  missed %d  errors %d  "
        "(target p99 < %.1f ms: %s)\n",
        name, r.ms.n, r.ms.p50, r.ms.p99, r.ms.max, r.missed, r.errors, target_ms,
        verdict(r.ms.n > 0 && r.ms.p99 < target_ms && r.missed == 0 && r.errors == 0));
}

// Paths of a build tree, for running the benchmark straight from it.
void default_env(const char* name, const char* value) {
    setenv(name, value, 0);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "daemon_bench - measures the real vibscored (sim driver, private bus): Play -> first\n"
        "actuator command and Stop -> actuator off latency, onset accuracy over a long score,\n"
        "idle wake-ups and memory, and concurrent clients. Prints a table and one JSON line.\n"
        "VIBSCORED, VIBSCORE_CLEFS and VIBSCORE_PRIVATE_BUS_CONF override the build tree's\n"
        "daemon, shipped documents and private bus configuration. Takes about 12 minutes\n"
        "(--quick: about 1 minute).",
        "daemon_bench"};
    Settings settings;
    bool quick = false;
    app.add_flag("--quick", quick,
                 "a smoke run: 200 plays and stops, 30 s onset run, 5 s idle, 5 s of clients");
    auto* plays = app.add_option("--plays", settings.plays, "Play latency samples (default 1000)")
                      ->check(CLI::Range(1, 1'000'000));
    auto* stops = app.add_option("--stops", settings.stops, "Stop latency samples (default 1000)")
                      ->check(CLI::Range(1, 1'000'000));
    auto* onset = app.add_option("--onset-seconds", settings.onset_seconds,
                                 "length of the onset accuracy run; the score repeats to cover it "
                                 "(default 600)")
                      ->check(CLI::Range(1.0, 86400.0));
    app.add_option("--onset-score", settings.onset_score,
                   "shipped score for the onset run (default ode-to-joy)");
    auto* idle = app.add_option("--idle-seconds", settings.idle_seconds,
                                "idle observation time (default 10)")
                     ->check(CLI::Range(0.1, 3600.0));
    app.add_option("--clients", settings.clients, "concurrent clients (default 32)")
        ->check(CLI::Range(1, 1000));
    auto* concurrency = app.add_option("--concurrency-seconds", settings.concurrency_seconds,
                                       "length of the concurrent clients run (default 30)")
                            ->check(CLI::Range(0.1, 3600.0));
    app.add_option("--pairs-per-second", settings.pairs_per_second,
                   "Play/Stop pairs per client per second (default 10)")
        ->check(CLI::Range(0.1, 1000.0));
    app.add_flag("--high-limit", settings.high_limit_for_clients,
                 "keep the high request limit for the concurrent clients instead of resetting "
                 "the daemon to its default (50/s, burst 100)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "daemon_bench: " << e.what() << "\nRun 'daemon_bench --help' for usage.\n";
        return 2;
    }
    if (quick) {
        settings.quick = true;
        if (plays->count() == 0)
            settings.plays = 200;
        if (stops->count() == 0)
            settings.stops = 200;
        if (onset->count() == 0)
            settings.onset_seconds = 30.0;
        if (idle->count() == 0)
            settings.idle_seconds = 5.0;
        if (concurrency->count() == 0)
            settings.concurrency_seconds = 5.0;
    }

    default_env("VIBSCORED", VIBSCORE_BENCH_VIBSCORED);
    default_env("VIBSCORE_CLEFS", VIBSCORE_BENCH_CLEFS);
    default_env("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF);

    const unsigned nproc = std::thread::hardware_concurrency();
    const std::string cpu = cpu_model();
    LatencyResult play, stop;
    OnsetResult onset_result;
    IdleResult idle_result;
    ConcurrencyResult clients;
    try {
        DaemonFixture daemon(kHighLimitConfig);
        std::fprintf(stderr, "play latency: %d plays...\n", settings.plays);
        play = play_latency(daemon, settings.plays);
        std::fprintf(stderr, "stop latency: %d stops...\n", settings.stops);
        stop = stop_latency(daemon, settings.stops);
        onset_result = onset_accuracy(daemon, settings);
        std::fprintf(stderr, "idle: %.0f s...\n", settings.idle_seconds);
        idle_result = idle_daemon(daemon, settings.idle_seconds);
        std::fprintf(stderr, "clients: %d for %.0f s...\n", settings.clients,
                     settings.concurrency_seconds);
        clients = concurrent_clients(daemon, settings);
    } catch (const std::exception& error) {
        std::cerr << "daemon_bench: setup failed: " << error.what() << "\n";
        return 1;
    }

    std::printf("vibscored benchmark%s (sim driver, private bus)\n",
                settings.quick ? " --quick" : "");
    std::printf("  machine                    %u CPUs, %s\n", nproc, cpu.c_str());
    print_latency("Play -> first drive", play, 1.0);
    print_latency("Stop -> actuator off", stop, 1.0);
    const auto& o = onset_result;
    const bool onset_ok = o.compared == o.expected && o.rows == o.expected + 1 &&
                          o.amplitude_mismatches == 0 && o.abs_error_ms.p99 < 0.5 &&
                          std::abs(o.last_error_ms) < 0.5;
    std::printf(
        "  onset accuracy             %s x%d (%.0f s), %zu drive rows of %zu expected "
        "(+1 final off: %s), %zu amplitude mismatches, finished \"%s\"\n",
        o.score.c_str(), o.passes, o.seconds, o.compared, o.expected,
        o.rows == o.expected + 1 ? "yes" : "no", o.amplitude_mismatches, o.reason.c_str());
    std::printf(
        "  |actual - scheduled|       p50 %.3f  p99 %.3f  max %.3f ms; last cue %+.3f ms, "
        "trend %+.3f ppm  (target p99 < 0.5 ms, no drift: %s)\n",
        o.abs_error_ms.p50, o.abs_error_ms.p99, o.abs_error_ms.max, o.last_error_ms, o.slope_ppm,
        verdict(onset_ok));
    std::printf(
        "  %-26s %ld wake-ups in %.0f s (target 0: %s), VmRSS %.2f MiB "
        "(target < 8: %s), %d thread(s)\n",
        ("idle daemon (pid " + std::to_string(idle_result.pid) + ")").c_str(), idle_result.wakeups,
        settings.idle_seconds, verdict(idle_result.wakeups == 0), idle_result.rss_mib,
        verdict(idle_result.rss_mib < 8.0), idle_result.threads);
    std::string error_list;
    for (const auto& [name, count] : clients.error_names) {
        error_list += " " + name + " x" + std::to_string(count);
    }
    std::printf(
        "  %-26s %ld calls at %.0f Play/Stop pairs/s each, limiter %s, %ld errors%s\n",
        (std::to_string(settings.clients) + " clients x " +
         std::to_string(static_cast<long>(std::lround(settings.concurrency_seconds))) + " s")
            .c_str(),
        clients.calls, settings.pairs_per_second, clients.limiter.c_str(), clients.errors,
        error_list.c_str());
    std::printf(
        "  call latency               p50 %.3f  p99 %.3f  max %.3f ms (Play p99 %.3f, "
        "Stop p99 %.3f)  (target 0 errors, p99 < 5 ms: %s)\n",
        clients.all_ms.p50, clients.all_ms.p99, clients.all_ms.max, clients.play_ms.p99,
        clients.stop_ms.p99, verdict(clients.errors == 0 && clients.all_ms.p99 < 5.0));

    std::printf("{\"benchmark\":\"daemon\",\"quick\":%s,\"nproc\":%u,\"cpu\":\"%s\",",
                settings.quick ? "true" : "false", nproc, json_escape(cpu).c_str());
    std::printf("%s,\"play_missed\":%d,\"play_errors\":%d,",
                json_summary("play_first_drive", play.ms).c_str(), play.missed, play.errors);
    std::printf("%s,\"stop_missed\":%d,\"stop_errors\":%d,",
                json_summary("stop_off", stop.ms).c_str(), stop.missed, stop.errors);
    std::printf(
        "\"onset_score\":\"%s\",\"onset_passes\":%d,\"onset_seconds\":%.1f,"
        "\"onset_rows_expected\":%zu,\"onset_rows\":%zu,\"onset_amplitude_mismatches\":%zu,"
        "%s,\"onset_last_error_ms\":%.4f,\"onset_trend_ppm\":%.4f,",
        json_escape(o.score).c_str(), o.passes, o.seconds, o.expected, o.rows,
        o.amplitude_mismatches, json_summary("onset_abs_error", o.abs_error_ms).c_str(),
        o.last_error_ms, o.slope_ppm);
    std::printf(
        "\"idle_seconds\":%.1f,\"idle_wakeups\":%ld,\"idle_rss_mib\":%.3f,"
        "\"idle_threads\":%d,",
        settings.idle_seconds, idle_result.wakeups, idle_result.rss_mib, idle_result.threads);
    std::printf(
        "\"clients\":%d,\"clients_seconds\":%.1f,\"clients_limiter\":\"%s\","
        "\"clients_calls\":%ld,\"clients_errors\":%ld,%s,%s,%s}\n",
        settings.clients, settings.concurrency_seconds,
        settings.high_limit_for_clients ? "high" : "default", clients.calls, clients.errors,
        json_summary("clients_call", clients.all_ms).c_str(),
        json_summary("clients_play", clients.play_ms).c_str(),
        json_summary("clients_stop", clients.stop_ms).c_str());
    return 0;
}
