// Software PWM benchmark: the gpio-erm PWM thread at a 1 kHz carrier, duties 0.1 .. 0.9 for a few
// seconds each, on a line that records when each edge happened: a fake line by default, or a
// real gpiochip line (--chip X --line N, e.g. gpio-sim in the VM tier). Prints the duty-cycle
// error per period, edge lateness and the PWM thread's CPU use, then one JSON line; asserts
// nothing.
#include <pthread.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "bench/report.hpp"
#include "bench/summary.hpp"
#include "common/monotonic_clock.hpp"
#include "daemon/drivers/gpio_lines.hpp"
#include "daemon/drivers/gpio_pwm_actuator.hpp"

namespace {

using namespace vibscore::drivers;
using vibscore::monotonic_now_ns;

constexpr std::int64_t kNanosPerSecond = 1'000'000'000;
const std::vector<double> kDuties{0.1, 0.25, 0.5, 0.75, 0.9};
// Periods left out after each duty change: the one in which it happened and the next.
constexpr int kSettlePeriods = 2;

void sleep_for_ns(std::int64_t ns) {
    const std::int64_t deadline = monotonic_now_ns() + ns;
    const timespec until{static_cast<time_t>(deadline / kNanosPerSecond),
                         static_cast<long>(deadline % kNanosPerSecond)};
    while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) != 0) {
    }
}

struct Edge {
    std::int64_t time_ns;
    int level;
};

// What the PWM thread did: when each edge happened, and which thread made them, so that the
// benchmark can read that thread's CPU clock and context switches from outside.
class Recording {
  public:
    explicit Recording(std::size_t capacity) { edges_.reserve(capacity); }

    void record(std::int64_t time_ns, int level) {
        if (!thread_known_.load(std::memory_order_acquire)) {
            thread_ = ::pthread_self();
            tid_ = static_cast<pid_t>(::syscall(SYS_gettid));
            thread_known_.store(true, std::memory_order_release);
        }
        const std::lock_guard lock(mutex_);
        if (edges_.size() < edges_.capacity()) {
            edges_.push_back({time_ns, level});
        } else {
            ++dropped_;
        }
    }

    std::vector<Edge> edges() const {
        const std::lock_guard lock(mutex_);
        return edges_;
    }
    std::size_t dropped() const {
        const std::lock_guard lock(mutex_);
        return dropped_;
    }

    // CPU time of the PWM thread so far, in ns (0 before its first edge).
    std::int64_t thread_cpu_ns() const {
        if (!thread_known_.load(std::memory_order_acquire)) {
            return 0;
        }
        clockid_t clock{};
        timespec used{};
        if (::pthread_getcpuclockid(thread_, &clock) != 0 || ::clock_gettime(clock, &used) != 0) {
            return 0;
        }
        return static_cast<std::int64_t>(used.tv_sec) * kNanosPerSecond + used.tv_nsec;
    }

    // The PWM thread's voluntary context switches so far: one per sleep, i.e. its wake-ups.
    long thread_wakeups() const {
        if (!thread_known_.load(std::memory_order_acquire)) {
            return 0;
        }
        std::ifstream status("/proc/self/task/" + std::to_string(tid_) + "/status");
        for (std::string line; std::getline(status, line);) {
            if (line.rfind("voluntary_ctxt_switches:", 0) == 0) {
                return std::atol(line.c_str() + line.find(':') + 1);
            }
        }
        return 0;
    }

  private:
    mutable std::mutex mutex_;
    std::vector<Edge> edges_;
    std::size_t dropped_ = 0;
    std::atomic<bool> thread_known_{false};
    pthread_t thread_{};
    pid_t tid_ = 0;
};

// The real line (or none) with every set recorded at the time the kernel call returned, which
// is when the line changed.
class RecordingLines final : public GpioLines {
  public:
    RecordingLines(std::unique_ptr<GpioLines> inner, std::shared_ptr<Recording> recording)
        : inner_(std::move(inner)), recording_(std::move(recording)) {}

    std::size_t count() const override { return inner_ ? inner_->count() : 1; }
    std::string describe() const override { return inner_ ? inner_->describe() : "fake line"; }

    void set_values(const std::vector<int>& values) override {
        if (inner_) {
            inner_->set_values(values);
        }
        recording_->record(monotonic_now_ns(), values[0]);
    }

  private:
    std::unique_ptr<GpioLines> inner_;
    std::shared_ptr<Recording> recording_;
};

using vibscore::bench::json_escape;
using vibscore::bench::summarize;
using vibscore::bench::Summary;

struct Segment {
    double duty = 0;
    std::int64_t start_ns = 0, end_ns = 0;
    std::int64_t cpu_from_ns = 0;  // when the CPU clock and the wake-ups were first read
    std::int64_t cpu_start_ns = 0, cpu_end_ns = 0;
    long wakeups_start = 0, wakeups_end = 0;
};

struct SegmentFigures {
    std::size_t periods = 0;
    std::size_t long_periods = 0;  // more than 1.5 carrier periods from rise to rise
    Summary duty_error;            // |measured - intended| per period
    Summary lateness_us;           // both edges, past their deadline
    double cpu_percent = 0;
    double wakeups_per_s = 0;
};

// The thread keeps every edge on the grid anchor + k·T (+ high time for falls): lateness is the
// distance past the latest grid point. The anchor is the first edge, written at once when the
// first waveform was taken (within a microsecond of its period start). A wake-up later than 0.9
// of a period shows wrapped; the periods it stretches count as long periods.
SegmentFigures analyse(const std::vector<Edge>& edges, const Segment& segment,
                       std::int64_t anchor_ns, std::int64_t period_ns) {
    SegmentFigures figures;
    const std::int64_t high_ns = std::llround(segment.duty * static_cast<double>(period_ns));
    const std::int64_t from = segment.start_ns + kSettlePeriods * period_ns;
    std::vector<double> errors, lateness;
    // Lateness within [-T/10, 9T/10): the anchor itself is a little late, so an edge can show
    // as slightly early.
    const auto late_past = [&](std::int64_t time, std::int64_t offset) {
        std::int64_t since = (time - anchor_ns - offset) % period_ns;
        since += since < 0 ? period_ns : 0;
        since -= since >= period_ns - period_ns / 10 ? period_ns : 0;
        return static_cast<double>(since) / 1e3;
    };
    std::int64_t rise = -1, fall = -1;
    for (const Edge& edge : edges) {
        if (edge.time_ns < from || edge.time_ns > segment.end_ns) {
            continue;
        }
        if (edge.level == 1) {
            lateness.push_back(late_past(edge.time_ns, 0));
            if (rise >= 0 && fall > rise) {
                const double length = static_cast<double>(edge.time_ns - rise);
                errors.push_back(
                    std::abs(static_cast<double>(fall - rise) / length - segment.duty));
                figures.long_periods += length > 1.5 * static_cast<double>(period_ns) ? 1 : 0;
            }
            rise = edge.time_ns;
        } else {
            lateness.push_back(late_past(edge.time_ns, high_ns));
            fall = edge.time_ns;
        }
    }
    figures.periods = errors.size();
    figures.duty_error = summarize(errors);
    figures.lateness_us = summarize(lateness);
    const double wall_s = static_cast<double>(segment.end_ns - segment.cpu_from_ns) / 1e9;
    figures.cpu_percent =
        static_cast<double>(segment.cpu_end_ns - segment.cpu_start_ns) / 1e9 / wall_s * 100.0;
    figures.wakeups_per_s =
        static_cast<double>(segment.wakeups_end - segment.wakeups_start) / wall_s;
    return figures;
}

std::string json_number(double value) {
    std::ostringstream out;
    out.precision(6);
    out << value;
    return out.str();
}

struct Options {
    std::string chip;
    long line = -1;
    double seconds = 3.0;
    double carrier_hz = 1000.0;
    int rt_priority = 50;
};

int usage(const char* program, int status) {
    std::printf(
        "usage: %s [--chip CHIP --line N] [--seconds S] [--carrier-hz F] [--rt-priority P]\n"
        "Runs the gpio-erm PWM thread (default 1000 Hz, SCHED_FIFO 50) at duties 0.1 0.25 0.5\n"
        "0.75 0.9 for S seconds each (default 3) on a fake line, or on line N of CHIP (a name,\n"
        "/dev path, label or number). Prints the duty-cycle error per period, edge lateness\n"
        "and the PWM thread's CPU use, then one JSON line.\n",
        program);
    return status;
}

bool parse(int argc, char** argv, Options& options) {
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) {
            return false;
        }
        const char* value = argv[++i];
        char* end = nullptr;
        if (flag == "--chip") {
            options.chip = value;
            continue;
        }
        const double number = std::strtod(value, &end);
        if (end == value || *end != '\0') {
            return false;
        }
        if (flag == "--line") {
            options.line = static_cast<long>(number);
        } else if (flag == "--seconds") {
            options.seconds = number;
        } else if (flag == "--carrier-hz") {
            options.carrier_hz = number;
        } else if (flag == "--rt-priority") {
            options.rt_priority = static_cast<int>(number);
        } else {
            return false;
        }
    }
    return options.chip.empty() == (options.line < 0) && options.seconds > 0 &&
           options.carrier_hz >= 10 && options.carrier_hz <= 20000 && options.rt_priority >= 0 &&
           options.rt_priority <= 99;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 2 && std::string(argv[1]) == "--help") {
        return usage(argv[0], 0);
    }
    Options options;
    if (!parse(argc, argv, options)) {
        return usage(argv[0], 2);
    }
    try {
        const auto periods = static_cast<std::size_t>(options.seconds * options.carrier_hz + 1);
        const auto recording = std::make_shared<Recording>(2 * (periods + 10) * kDuties.size());
        auto lines = std::make_unique<RecordingLines>(
            options.chip.empty()
                ? nullptr
                : open_gpio_lines(options.chip, {static_cast<unsigned>(options.line)}),
            recording);
        const std::string target = lines->describe();
        std::vector<Segment> segments;
        bool realtime = false;
        {
            GpioPwmActuator erm({GpioPwmKind::erm, options.carrier_hz, false, options.rt_priority},
                                std::move(lines));
            realtime = erm.realtime();
            for (const double duty : kDuties) {
                Segment segment;
                segment.duty = duty;
                segment.start_ns = monotonic_now_ns();
                erm.apply({duty});
                // The thread is known once it has made its first edge.
                if (segments.empty()) {
                    sleep_for_ns(kSettlePeriods * kNanosPerSecond /
                                 static_cast<std::int64_t>(options.carrier_hz));
                }
                segment.cpu_from_ns = monotonic_now_ns();
                segment.cpu_start_ns = recording->thread_cpu_ns();
                segment.wakeups_start = recording->thread_wakeups();
                sleep_for_ns(static_cast<std::int64_t>(options.seconds * 1e9));
                segment.end_ns = monotonic_now_ns();
                segment.cpu_end_ns = recording->thread_cpu_ns();
                segment.wakeups_end = recording->thread_wakeups();
                segments.push_back(segment);
            }
            erm.off();
        }
        const auto edges = recording->edges();
        if (edges.empty()) {
            std::fprintf(stderr, "pwm_bench: no edge was recorded\n");
            return 1;
        }
        const auto period_ns = std::llround(1e9 / options.carrier_hz);
        std::printf("PWM thread on %s, carrier %.0f Hz, %s, %.1f s per duty\n", target.c_str(),
                    options.carrier_hz, realtime ? "SCHED_FIFO" : "normal priority",
                    options.seconds);
        std::printf("%6s %8s %10s %10s %10s %10s %10s %8s %9s %6s\n", "duty", "periods", "err mean",
                    "err p99", "late p50", "late p99", "late max", "cpu %", "wakeups/s", "long");
        std::string json = "{\"bench\":\"pwm\",\"line\":\"" + json_escape(target) +
                           "\",\"carrier_hz\":" + json_number(options.carrier_hz) +
                           ",\"seconds_per_duty\":" + json_number(options.seconds) +
                           ",\"realtime\":" + (realtime ? "true" : "false") +
                           ",\"dropped_edges\":" + std::to_string(recording->dropped()) +
                           ",\"duties\":[";
        for (std::size_t i = 0; i < segments.size(); ++i) {
            const auto f = analyse(edges, segments[i], edges.front().time_ns, period_ns);
            std::printf("%6.2f %8zu %10.4f %10.4f %8.1fus %8.1fus %8.1fus %8.2f %9.0f %6zu\n",
                        segments[i].duty, f.periods, f.duty_error.mean, f.duty_error.p99,
                        f.lateness_us.p50, f.lateness_us.p99, f.lateness_us.max, f.cpu_percent,
                        f.wakeups_per_s, f.long_periods);
            json += std::string(i == 0 ? "" : ",") + "{\"duty\":" + json_number(segments[i].duty) +
                    ",\"periods\":" + std::to_string(f.periods) +
                    ",\"duty_error_mean_abs\":" + json_number(f.duty_error.mean) +
                    ",\"duty_error_p99\":" + json_number(f.duty_error.p99) +
                    ",\"lateness_us_p50\":" + json_number(f.lateness_us.p50) +
                    ",\"lateness_us_p99\":" + json_number(f.lateness_us.p99) +
                    ",\"lateness_us_max\":" + json_number(f.lateness_us.max) +
                    ",\"cpu_percent\":" + json_number(f.cpu_percent) +
                    ",\"wakeups_per_s\":" + json_number(f.wakeups_per_s) +
                    ",\"long_periods\":" + std::to_string(f.long_periods) + "}";
        }
        json += "]}";
        std::printf("%s\n", json.c_str());
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "pwm_bench: %s\n", error.what());
        return 1;
    }
}
