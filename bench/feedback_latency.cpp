// feedback latency benchmark, inside the hil guest (bench/vm-bench): TriggerFeedback call ->
// the first actuator command, on one uinput force-feedback vibra (tests/hil's UinputVibrator,
// marked for feedbackd as a phone's vibra is). Debian's feedbackd drives it directly; vibscore
// plays the same event through vibscore-feedback and vibscored's evdev backend (path 2), and a
// second feedbackd plays it on vibscored's virtual vibra, which vibscored plays on the same
// device (path 1). The three are triggered in turn, on session buses of their own, so the
// guest's noise falls on all alike.
// The time is CLOCK_MONOTONIC before the call to the kernel's timestamp of the EV_FF play the
// device receives. Prints a table and one JSON line; asserts nothing. Under TCG every figure
// is emulation: only the ratio means anything.
#include <sys/utsname.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/report.hpp"
#include "bench/summary.hpp"
#include "tests/hil/uinput_vibrator.hpp"
#include "tests/hil/virtual_vibra_node.hpp"
#include "tests/support/feedback_fixture.hpp"

namespace {

using namespace std::chrono_literals;
using vibscore::hil::FfEvent;
using vibscore::hil::UinputVibrator;
using namespace vibscore::testing;
using namespace vibscore::bench;
using Clock = std::chrono::steady_clock;

struct Series {
    std::vector<double> ms;  // call -> EV_FF play at the device
    int missed = 0;          // no play within 2 s
};

// One trigger of `event`, timed to the device's first play; then waits for its end.
void trigger_once(FeedbackClient& client, UinputVibrator& vibrator, const std::string& event,
                  Series& series) {
    static const std::map<std::string, sdbus::Variant> hints{{"profile", sdbus::Variant("quiet")}};
    vibrator.clear_timeline();
    const auto asked = Clock::now();
    const auto id = client.TriggerFeedback("org.vibscore.Bench", event, hints, -1);
    const auto is_start = [](const FfEvent& e) {
        return e.kind == FfEvent::Kind::Play && e.value != 0;
    };
    if (!vibrator.wait_for(is_start, 2s)) {
        ++series.missed;
    } else {
        for (const auto& seen : vibrator.timeline()) {
            if (is_start(seen)) {
                series.ms.push_back(
                    std::chrono::duration<double, std::milli>(seen.time - asked).count());
                break;
            }
        }
    }
    client.wait_ended(id, 3s);
}

void print_row(const char* name, const Summary& s) {
    std::printf("  %-40s n=%-4zu p50 %7.3f  p99 %7.3f  max %7.3f ms\n", name, s.n, s.p50, s.p99,
                s.max);
}

}  // namespace

int main(int argc, char** argv) {
    int rounds = 100;
    std::string event = "message-new-instant";
    bool usage_ok = true;
    for (int i = 1; i < argc; i += 2) {
        if (i + 1 < argc && std::strcmp(argv[i], "--rounds") == 0 && std::atoi(argv[i + 1]) > 0) {
            rounds = std::atoi(argv[i + 1]);
        } else if (i + 1 < argc && std::strcmp(argv[i], "--event") == 0) {
            event = argv[i + 1];
        } else {
            usage_ok = false;
        }
    }
    if (!usage_ok) {
        std::fprintf(stderr,
                     "usage: %s [--rounds N] [--event NAME]\nTriggerFeedback -> EV_FF play on a "
                     "uinput vibra: feedbackd directly versus vibscore-feedback + vibscored "
                     "(default 100 rounds of message-new-instant). Runs in the hil guest: "
                     "bench/vm-bench.\n",
                     argv[0]);
        return 2;
    }
    if (std::getenv("VIBSCORE_HIL_GUEST") == nullptr) {
        std::fprintf(stderr,
                     "%s: creates a uinput device, so it runs in the hil VM: "
                     "bench/vm-bench\n",
                     argv[0]);
        return 77;
    }
    setenv("VIBSCORED", VIBSCORE_BENCH_VIBSCORED, 0);
    setenv("VIBSCORE_FEEDBACK", VIBSCORE_BENCH_FEEDBACK, 0);
    setenv("VIBSCORE_CLEFS", VIBSCORE_BENCH_CLEFS, 0);
    setenv("VIBSCORE_FEEDBACK_THEME", VIBSCORE_BENCH_FEEDBACK_THEME, 0);
    setenv("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF, 0);

    Series theirs, ours, through_vibra;
    try {
        // The vibra first: feedbackd finds it in udev's database when it starts. vibscored
        // drives it, and serves its virtual vibra too (which it never drives itself).
        UinputVibrator vibrator(vibscore::hil::UinputVibratorOptions::phone_vibrator());
        DaemonFixture daemon(
            "requests-per-second = 100000\nrequest-burst = 100000\n"
            "driver = evdev\n[virtual-vibra]\nenabled = true\n"
            "[evdev]\ndevice = " +
            vibrator.event_node().string());
        SessionBus theirs_bus, ours_bus, vibra_bus;
        FeedbackServer feedbackd(theirs_bus, real_feedbackd());
        FeedbackServer vibscore_feedback_server(
            ours_bus, vibscore_feedback({"--theme", required_env("VIBSCORE_FEEDBACK_THEME")}));
        // A second feedbackd that finds only the virtual vibra; the first keeps the one it has.
        const auto virtual_vibra = vibscore::hil::find_virtual_vibra();
        if (!virtual_vibra) {
            throw std::runtime_error("vibscored made no virtual vibra");
        }
        std::filesystem::remove(vibrator.udev_entry());
        vibscore::hil::FeedbackdVibraMark mark(*virtual_vibra);
        FeedbackServer feedbackd_on_vibscore(vibra_bus, real_feedbackd());
        FeedbackClient theirs_client(theirs_bus), ours_client(ours_bus), vibra_client(vibra_bus);
        std::fprintf(stderr, "feedback latency: %d rounds of %s...\n", rounds, event.c_str());
        for (int round = 0; round < rounds; ++round) {
            trigger_once(theirs_client, vibrator, event, theirs);
            trigger_once(ours_client, vibrator, event, ours);
            trigger_once(vibra_client, vibrator, event, through_vibra);
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "feedback_latency: %s\n", error.what());
        return 1;
    }

    utsname system{};
    uname(&system);
    const std::string cpu = cpu_model();
    const auto theirs_s = summarize(theirs.ms), ours_s = summarize(ours.ms),
               vibra_s = summarize(through_vibra.ms);
    const int missed = theirs.missed + ours.missed + through_vibra.missed;
    std::printf("TriggerFeedback(%s, profile quiet) -> EV_FF play at a uinput vibra\n",
                event.c_str());
    std::printf("  kernel %s, CPU \"%s\" (\"QEMU TCG CPU\": emulated, not real time)\n",
                system.release, cpu.c_str());
    print_row("feedbackd, directly", theirs_s);
    print_row("vibscore-feedback -> vibscored (evdev)", ours_s);
    print_row("feedbackd -> virtual vibra -> vibscored", vibra_s);
    std::printf(
        "  feedbackd / vibscore-feedback at p50: %.2fx, at p99: %.2fx (aim >= 3x at p99); "
        "missed %d\n",
        theirs_s.p50 / ours_s.p50, theirs_s.p99 / ours_s.p99, missed);
    std::printf(
        "{\"bench\":\"feedback_latency\",\"kernel\":\"%s\",\"cpu\":\"%s\",\"event\":\"%s\","
        "%s,%s,%s,\"feedbackd_over_vibscore_p50\":%.3f,"
        "\"feedbackd_over_vibscore_p99\":%.3f,\"missed\":%d}\n",
        json_escape(system.release).c_str(), json_escape(cpu).c_str(), json_escape(event).c_str(),
        json_summary("feedbackd", theirs_s).c_str(), json_summary("vibscore", ours_s).c_str(),
        json_summary("feedbackd_virtual_vibra", vibra_s).c_str(), theirs_s.p50 / ours_s.p50,
        theirs_s.p99 / ours_s.p99, missed);
    return missed == 0 ? 0 : 1;
}
