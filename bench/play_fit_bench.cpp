// Play round trip through a clef fitted to the actuator ([clefs] fit = auto), for two builds of
// vibscored side by side: each on its own private bus with the sim driver and the same declared
// LRA, Play of the same shipped score timed from the call to its reply, in alternating blocks so
// that the machine's other load falls on both alike. Made to compare a daemon that fits the
// device clefs at every Play with one that keeps them (issue 30, item 5; docs/performance.md).
// Prints a table and one JSON line; asserts nothing.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/report.hpp"
#include "bench/summary.hpp"
#include "common/monotonic_clock.hpp"
#include "daemon/render/fitting/clef_fit.hpp"
#include "score/bundle.hpp"
#include "tests/support/daemon_fixture.hpp"

namespace {

using namespace vibscore;
using testing::DaemonFixture;
using testing::HapticsClient;
using vibscore::bench::json_escape;
using vibscore::bench::json_summary;
using vibscore::bench::summarize;
using vibscore::bench::Summary;
using Options = std::map<std::string, sdbus::Variant>;

struct Settings {
    std::string before_daemon;  // empty: measure only the build tree's daemon
    std::string before_clefs;   // the shipped documents of the before daemon's checkout
    std::string score = "alarm";
    int plays = 200;
    int block = 20;
    double resonance_hz = 170.0;
    double q = 15.0;
    bool verbose = false;  // each block's median too, to tell load from the daemon
};

// One daemon under test: its private bus, its client, and the round trips measured so far.
struct Subject {
    std::string name;
    std::unique_ptr<DaemonFixture> daemon;
    std::unique_ptr<HapticsClient> client;
    std::vector<double> ms;
    int errors = 0;
    std::string first_error;
};

std::string config_lines(const Settings& settings) {
    return "[actuator]\nkind = lra\nresonance-hz = " + std::to_string(settings.resonance_hz) +
           "\nq = " + std::to_string(settings.q) + "\n[clefs]\nfit = auto\n";
}

// Starts `path` on a private bus of its own, with `clefs` as its shipped documents. The fixture
// reads VIBSCORED and VIBSCORE_CLEFS, and sets the system bus address a client connects to, as
// it starts: so the client is made here, before the next daemon's fixture moves the address.
Subject start(const std::string& name, const std::string& path, const std::string& clefs,
              const Settings& settings) {
    setenv("VIBSCORED", path.c_str(), 1);
    setenv("VIBSCORE_CLEFS", clefs.c_str(), 1);
    Subject subject;
    subject.name = name;
    subject.daemon = std::make_unique<DaemonFixture>(config_lines(settings));
    subject.client = subject.daemon->client();
    return subject;
}

// `count` Plays of the score, each timed from the call to its reply; each playback stopped
// (untimed) so that the next Play starts from an idle player.
void play_block(Subject& subject, const Settings& settings, int count) {
    const Options none;
    for (int i = 0; i < count; ++i) {
        const auto t0 = monotonic_now_ns();
        std::uint64_t id = 0;
        try {
            id = subject.client->Play(settings.score, none);
        } catch (const sdbus::Error& error) {
            if (subject.errors++ == 0) {
                subject.first_error = error.getName() + ": " + error.getMessage();
            }
            continue;
        }
        subject.ms.push_back(static_cast<double>(monotonic_now_ns() - t0) / 1e6);
        try {
            subject.client->Stop(id);
        } catch (const sdbus::Error&) {
            // Already finished: nothing to stop.
        }
    }
}

// What one fit costs by itself, in-process: the written clef `name` fitted to the declared LRA
// `fits` times, each timed (microseconds). The part of a Play the cache saves, per clef.
Summary fit_cost_us(const std::string& clefs, const std::string& name, const Settings& settings,
                    int fits) {
    const auto written = load_clef_file(std::filesystem::path(clefs) / (name + ".clef.xml"));
    actuator::Declaration declared;
    declared.kind = actuator::Kind::lra;
    declared.resonance_hz = settings.resonance_hz;
    declared.q = settings.q;
    std::vector<double> us;
    std::size_t strings = 0;
    for (int i = 0; i < fits; ++i) {
        const auto t0 = monotonic_now_ns();
        const auto fit = render::fit_clef(written, declared);
        us.push_back(static_cast<double>(monotonic_now_ns() - t0) / 1e3);
        strings += fit.clef.strings.size();  // used, so the fit is not optimised away
    }
    if (strings == 0) {
        std::fprintf(stderr, "play_fit_bench: %s fitted to no strings\n", name.c_str());
    }
    return summarize(std::move(us));
}

void print_row(const Subject& subject, const Summary& s) {
    std::printf("  %-8s n=%zu  p50 %.3f  p99 %.3f  max %.3f  mean %.3f ms  errors %d%s%s\n",
                subject.name.c_str(), s.n, s.p50, s.p99, s.max, s.mean, subject.errors,
                subject.errors ? "  first: " : "", subject.first_error.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "play_fit_bench - Play round trip of a shipped score through clefs fitted to a declared\n"
        "LRA ([clefs] fit = auto), on the build tree's vibscored and optionally another build\n"
        "(--before), each on its own private bus, in alternating blocks. Prints a table and one\n"
        "JSON line. VIBSCORED, VIBSCORE_CLEFS and VIBSCORE_PRIVATE_BUS_CONF override the build\n"
        "tree's daemon, shipped documents and private bus configuration.",
        "play_fit_bench"};
    Settings settings;
    app.add_option("--before", settings.before_daemon,
                   "another vibscored to measure alongside (e.g. an older commit's build)");
    app.add_option("--before-clefs", settings.before_clefs,
                   "the --before daemon's shipped documents (default: the same as the other's)");
    app.add_option("--score", settings.score, "shipped score to play (default alarm)");
    app.add_option("--plays", settings.plays, "Plays per daemon (default 200)")
        ->check(CLI::Range(1, 1'000'000));
    app.add_option("--block", settings.block, "Plays in a row before switching (default 20)")
        ->check(CLI::Range(1, 1'000'000));
    app.add_option("--resonance-hz", settings.resonance_hz, "declared LRA resonance (default 170)")
        ->check(CLI::Range(50.0, 400.0));
    app.add_flag("--verbose", settings.verbose, "print each block's median round trip");
    app.add_option("--q", settings.q, "declared LRA Q (default 15)")->check(CLI::Range(1.0, 100.0));
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "play_fit_bench: " << e.what() << "\nRun 'play_fit_bench --help' for usage.\n";
        return 2;
    }

    setenv("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF, 0);
    const char* env_daemon = std::getenv("VIBSCORED");
    const char* env_clefs = std::getenv("VIBSCORE_CLEFS");
    const std::string after_daemon = env_daemon ? env_daemon : VIBSCORE_BENCH_VIBSCORED;
    const std::string clefs = env_clefs ? env_clefs : VIBSCORE_BENCH_CLEFS;
    if (settings.before_clefs.empty()) {
        settings.before_clefs = clefs;
    }

    std::vector<Subject> subjects;
    try {
        if (!settings.before_daemon.empty()) {
            subjects.push_back(
                start("before", settings.before_daemon, settings.before_clefs, settings));
        }
        subjects.push_back(start("after", after_daemon, clefs, settings));
        // One untimed Play each first: the start-up's work (and the first fit) out of the way.
        for (auto& subject : subjects) {
            play_block(subject, settings, 1);
            subject.ms.clear();
        }
        for (int done = 0; done < settings.plays; done += settings.block) {
            const int count = std::min(settings.block, settings.plays - done);
            // Alternate which daemon goes first, so neither always follows the other.
            const bool reverse = (done / settings.block) % 2 == 1;
            for (std::size_t i = 0; i < subjects.size(); ++i) {
                auto& subject = subjects[reverse ? subjects.size() - 1 - i : i];
                const auto from = subject.ms.size();
                play_block(subject, settings, count);
                if (settings.verbose) {
                    const std::vector<double> block(
                        subject.ms.begin() + static_cast<std::ptrdiff_t>(from), subject.ms.end());
                    std::fprintf(stderr, "block %d %-6s p50 %.3f ms\n", done / settings.block,
                                 subject.name.c_str(), summarize(block).p50);
                }
            }
        }
    } catch (const std::exception& error) {
        std::cerr << "play_fit_bench: setup failed: " << error.what() << "\n";
        return 1;
    }

    // What each daemon said of its clefs at start (fitted, or why not): the evidence that the
    // score plays through fitted clefs at all.
    for (const auto& subject : subjects) {
        std::istringstream log(subject.daemon->daemon_log());
        for (std::string line; std::getline(log, line);) {
            if (line.find("device clefs:") != std::string::npos ||
                line.find("clef \"lra-phone\" fitted") != std::string::npos) {
                std::fprintf(stderr, "%s: %s\n", subject.name.c_str(), line.c_str());
            }
        }
    }

    Summary fit_us;
    try {
        fit_us = fit_cost_us(clefs, "lra-phone", settings, 1000);
    } catch (const std::exception& error) {
        std::cerr << "play_fit_bench: fitting lra-phone failed: " << error.what() << "\n";
        return 1;
    }

    const unsigned nproc = std::thread::hardware_concurrency();
    const std::string cpu = vibscore::bench::cpu_model();
    std::printf(
        "Play round trip, %s through clefs fitted to an LRA (%.0f Hz, Q %.0f), %d plays "
        "per daemon in blocks of %d\n",
        settings.score.c_str(), settings.resonance_hz, settings.q, settings.plays, settings.block);
    std::printf("  machine  %u CPUs, %s\n", nproc, cpu.c_str());
    std::string json = "{\"bench\":\"play_fit\",\"score\":\"" + json_escape(settings.score) +
                       "\",\"plays\":" + std::to_string(settings.plays) +
                       ",\"cpus\":" + std::to_string(nproc) + ",\"cpu\":\"" + json_escape(cpu) +
                       "\"";
    std::printf("  one fit of lra-phone, in-process: p50 %.1f  p99 %.1f us (1000 fits)\n",
                fit_us.p50, fit_us.p99);
    char fit_text[96];
    std::snprintf(fit_text, sizeof fit_text, ",\"fit_p50_us\":%.2f,\"fit_p99_us\":%.2f", fit_us.p50,
                  fit_us.p99);
    json += fit_text;
    std::vector<Summary> summaries;
    for (const auto& subject : subjects) {
        summaries.push_back(summarize(subject.ms));
        print_row(subject, summaries.back());
        json += "," + json_summary(subject.name.c_str(), summaries.back()) + ",\"" + subject.name +
                "_errors\":" + std::to_string(subject.errors);
    }
    if (summaries.size() == 2 && summaries[1].p50 > 0 && summaries[1].p99 > 0) {
        const double p50_ratio = summaries[0].p50 / summaries[1].p50;
        const double p99_ratio = summaries[0].p99 / summaries[1].p99;
        std::printf("  before/after  p50 x%.2f  p99 x%.2f\n", p50_ratio, p99_ratio);
        char text[96];
        std::snprintf(text, sizeof text, ",\"p50_ratio\":%.3f,\"p99_ratio\":%.3f", p50_ratio,
                      p99_ratio);
        json += text;
    }
    std::printf("%s}\n", json.c_str());
    return 0;
}
