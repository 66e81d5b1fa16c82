// evdev latency benchmark: the real vibscored with driver = evdev against a uinput
// force-feedback device (tests/hil's UinputVibrator), inside the hil guest (bench/vm-bench).
// For each Play of a one-note score: CLOCK_MONOTONIC just before the call, and the kernel's
// timestamp of the EV_FF play event the device receives. Two series: the same note again and
// again (after two plays both effect slots hold it, so a start is one write), and three
// different notes in turn (every start needs an upload first, answered by the device's
// thread). Prints a table and one JSON line; asserts nothing. In the usual TCG guest every
// figure is emulation, not a property of a real machine.
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bench/report.hpp"
#include "bench/summary.hpp"
#include "tests/hil/uinput_vibrator.hpp"
#include "tests/support/daemon_fixture.hpp"

namespace {

using namespace std::chrono_literals;
using vibscore::hil::FfEvent;
using vibscore::hil::UinputVibrator;
using vibscore::testing::DaemonFixture;
using Clock = std::chrono::steady_clock;

using vibscore::bench::cpu_model;
using vibscore::bench::json_escape;
using vibscore::bench::summarize;
using vibscore::bench::Summary;

double ms_between(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double, std::milli>(to - from).count();
}

std::string one_note(int string) {
    return "<VibScore version=\"1.0\"><Title>latency</Title>"
           "<Clef id=\"c\" href=\"lra-phone.clef.xml\"/><Bar clef=\"c\">"
           "<Note length=\"32th\" number=\"9\" string=\"" +
           std::to_string(string) + "\"/></Bar></VibScore>";
}

struct Series {
    std::vector<double> to_play_ms;  // Play call -> EV_FF play at the device
    std::vector<double> reply_ms;    // Play call -> its reply at the client
    std::size_t with_upload = 0;     // plays whose start needed an upload first
    int missed = 0;                  // no EV_FF play within 2 s, or no PlaybackFinished
};

Series measure(DaemonFixture& daemon, UinputVibrator& vibrator, int plays,
               const std::vector<std::string>& scores) {
    auto client = daemon.client();
    Series series;
    for (int i = 0; i < plays; ++i) {
        vibrator.clear_timeline();
        const auto asked = Clock::now();
        const auto id = client->Play(scores[static_cast<std::size_t>(i) % scores.size()], {});
        series.reply_ms.push_back(ms_between(asked, Clock::now()));
        const auto is_start = [](const FfEvent& e) {
            return e.kind == FfEvent::Kind::Play && e.value != 0;
        };
        if (!vibrator.wait_for(is_start, 2s) || !client->wait_finished(id, nullptr, 5s)) {
            ++series.missed;
            continue;
        }
        bool uploaded = false;
        for (const auto& event : vibrator.timeline()) {
            uploaded = uploaded || event.kind == FfEvent::Kind::Upload;
            if (is_start(event)) {
                series.to_play_ms.push_back(ms_between(asked, event.time));
                series.with_upload += uploaded ? 1 : 0;
                break;
            }
        }
    }
    return series;
}

void print_row(const char* name, const Summary& s) {
    std::printf("  %-44s n=%-4zu p50 %7.3f  p99 %7.3f  max %7.3f ms\n", name, s.n, s.p50, s.p99,
                s.max);
}

}  // namespace

int main(int argc, char** argv) {
    int plays = 200;
    if (argc == 3 && std::strcmp(argv[1], "--plays") == 0 && std::atoi(argv[2]) > 0) {
        plays = std::atoi(argv[2]);
    } else if (argc != 1) {
        std::fprintf(stderr,
                     "usage: %s [--plays N]\nPlay -> EV_FF latency of vibscored's evdev backend "
                     "against a uinput device, N plays per series (default 200). Runs in the "
                     "hil guest: bench/vm-bench.\n",
                     argv[0]);
        return 2;
    }
    if (std::getenv("VIBSCORE_HIL_GUEST") == nullptr) {
        std::fprintf(stderr,
                     "%s: creates a uinput device, so it runs in the hil test VM: "
                     "bench/vm-bench\n",
                     argv[0]);
        return 77;
    }
    setenv("VIBSCORED", VIBSCORE_BENCH_VIBSCORED, 0);
    setenv("VIBSCORE_CLEFS", VIBSCORE_BENCH_CLEFS, 0);
    setenv("VIBSCORE_PRIVATE_BUS_CONF", VIBSCORE_BENCH_PRIVATE_BUS_CONF, 0);

    Series prepared, uploading;
    try {
        UinputVibrator vibrator(vibscore::hil::UinputVibratorOptions::phone_vibrator());
        // No rate limit in the way of back-to-back plays.
        DaemonFixture daemon(
            "requests-per-second = 100000\nrequest-burst = 100000\n"
            "driver = evdev\n[evdev]\ndevice = " +
            vibrator.event_node().string());
        std::fprintf(stderr, "evdev latency: %d plays of one note...\n", plays);
        prepared = measure(daemon, vibrator, plays, {one_note(4)});
        std::fprintf(stderr, "evdev latency: %d plays of three notes in turn...\n", plays);
        uploading = measure(daemon, vibrator, plays, {one_note(2), one_note(4), one_note(6)});
    } catch (const std::exception& error) {
        std::fprintf(stderr, "evdev_latency: %s\n", error.what());
        return 1;
    }

    utsname system{};
    uname(&system);
    const std::string cpu = cpu_model();
    const auto same = summarize(prepared.to_play_ms);
    const auto upload = summarize(uploading.to_play_ms);
    const auto reply = summarize(prepared.reply_ms);
    std::printf("vibscored evdev backend, Play -> EV_FF play at a uinput device\n");
    std::printf("  kernel %s, CPU \"%s\" (\"QEMU TCG CPU\": emulated, not real time)\n",
                system.release, cpu.c_str());
    print_row("same note: start is one write", same);
    std::printf("    (%zu of %zu needed an upload: the first two fill the slots)\n",
                prepared.with_upload, prepared.to_play_ms.size());
    print_row("three notes in turn: upload, then start", upload);
    std::printf("    (%zu of %zu needed an upload)\n", uploading.with_upload,
                uploading.to_play_ms.size());
    print_row("Play call -> its reply (same note)", reply);
    std::printf("  missed: %d and %d\n", prepared.missed, uploading.missed);
    std::printf(
        "{\"bench\":\"evdev_latency\",\"kernel\":\"%s\",\"cpu\":\"%s\",%s,%s,%s,"
        "\"same_note_uploads\":%zu,\"three_notes_uploads\":%zu,\"missed\":%d}\n",
        json_escape(system.release).c_str(), json_escape(cpu).c_str(),
        json_summary("same_note_play", same).c_str(),
        json_summary("three_notes_play", upload).c_str(), json_summary("play_reply", reply).c_str(),
        prepared.with_upload, uploading.with_upload, prepared.missed + uploading.missed);
    return prepared.missed + uploading.missed == 0 ? 0 : 1;
}
