// feedback latency benchmark, inside the hil guest (bench/vm-bench): TriggerFeedback call ->
// the first actuator command, on one uinput force-feedback vibra (tests/hil's UinputVibrator,
// marked for feedbackd as a phone's vibra is). Debian's feedbackd drives it directly; vibscore
// plays the same event through vibscore-feedback and vibscored's evdev backend (path 2), and a
// second feedbackd plays it on vibscored's virtual vibra, which vibscored plays on the same
// device (path 1). With --feedbackd-root DIR (another Debian release's root, e.g. the Debian 13
// chroot /srv/trixie with feedbackd 0.8.2), that release's feedbackd runs too, chrooted in DIR,
// both directly and on the virtual vibra. All are triggered in turn, round after round, on
// session buses of their own, so the guest's noise falls on all alike.
// The time is CLOCK_MONOTONIC before the call to the kernel's timestamp of the EV_FF play the
// device receives. Prints a table and one JSON line; asserts nothing. Under TCG every figure
// is emulation: only the ratios mean anything.
#include <sys/mount.h>
#include <sys/utsname.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
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

// One program serving the feedbackd API on a session bus of its own, and a client of it.
struct Peer {
    std::string name;  // for the table
    std::string key;   // for the JSON line
    std::unique_ptr<SessionBus> bus = std::make_unique<SessionBus>();
    std::unique_ptr<FeedbackServer> server;
    std::unique_ptr<FeedbackClient> client;
    Series series;

    Peer(std::string name_, std::string key_, const std::vector<std::string>& argv)
        : name(std::move(name_)), key(std::move(key_)) {
        server = std::make_unique<FeedbackServer>(*bus, argv);
        client = std::make_unique<FeedbackClient>(*bus);
    }
};

// The guest's /dev, /proc, /sys, /run and /tmp seen in another release's root, so that a
// program chrooted there finds the vibra, udev's database and the session bus's socket. Only in
// the hil guest, whose mounts go with it.
class ChrootMounts {
  public:
    explicit ChrootMounts(const std::filesystem::path& root) {
        for (const char* dir : {"/dev", "/proc", "/sys", "/run", "/tmp"}) {
            const auto target = root.string() + dir;
            if (::mount(dir, target.c_str(), nullptr, MS_BIND | MS_REC, nullptr) != 0) {
                throw std::system_error(errno, std::generic_category(),
                                        std::string("cannot bind ") + dir + " to " + target);
            }
            mounted_.push_back(target);
        }
    }
    ~ChrootMounts() {
        for (auto target = mounted_.rbegin(); target != mounted_.rend(); ++target) {
            ::umount2(target->c_str(), MNT_DETACH);
        }
    }
    ChrootMounts(const ChrootMounts&) = delete;
    ChrootMounts& operator=(const ChrootMounts&) = delete;

  private:
    std::vector<std::string> mounted_;
};

// The feedbackd package's version installed in `root`, from dpkg's database.
std::string feedbackd_version(const std::filesystem::path& root) {
    std::ifstream status(root / "var/lib/dpkg/status");
    std::string line;
    bool ours = false;
    while (std::getline(status, line)) {
        if (line.starts_with("Package: ")) {
            ours = line == "Package: feedbackd";
        } else if (ours && line.starts_with("Version: ")) {
            return line.substr(9);
        }
    }
    return "?";
}

// "0.8.2-1" -> "0_8_2": the upstream version as a JSON key.
std::string version_key(const std::string& version) {
    std::string key;
    for (const char c : version.substr(0, version.find('-'))) {
        key += std::isalnum(static_cast<unsigned char>(c)) != 0 ? c : '_';
    }
    return key;
}

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

void print_row(const std::string& name, const Summary& s) {
    std::printf("  %-52s n=%-4zu p50 %7.3f  p99 %7.3f  max %7.3f ms\n", name.c_str(), s.n, s.p50,
                s.p99, s.max);
}

int usage(const char* program) {
    std::fprintf(stderr,
                 "usage: %s [--rounds N] [--event NAME] [--feedbackd-root DIR]...\n"
                 "TriggerFeedback -> EV_FF play on a uinput vibra: feedbackd directly versus "
                 "vibscore-feedback + vibscored (default 100 rounds of message-new-instant); "
                 "--feedbackd-root adds the feedbackd of another Debian root (e.g. "
                 "/srv/trixie), chrooted. Runs in the hil guest: bench/vm-bench.\n",
                 program);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    int rounds = 100;
    std::string event = "message-new-instant";
    std::vector<std::filesystem::path> roots;
    for (int i = 1; i < argc; i += 2) {
        if (i + 1 >= argc) {
            return usage(argv[0]);
        }
        if (std::strcmp(argv[i], "--rounds") == 0 && std::atoi(argv[i + 1]) > 0) {
            rounds = std::atoi(argv[i + 1]);
        } else if (std::strcmp(argv[i], "--event") == 0) {
            event = argv[i + 1];
        } else if (std::strcmp(argv[i], "--feedbackd-root") == 0 &&
                   std::filesystem::exists(std::filesystem::path(argv[i + 1]) /
                                           "usr/libexec/feedbackd")) {
            roots.emplace_back(argv[i + 1]);
        } else {
            return usage(argv[0]);
        }
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

    const std::string host_version = feedbackd_version("/");
    std::vector<std::unique_ptr<Peer>> peers;
    std::vector<std::pair<std::string, std::string>> versions{{host_version, "/"}};
    try {
        // The vibra first: feedbackd finds it in udev's database when it starts. vibscored
        // drives it, and serves its virtual vibra too (which it never drives itself).
        UinputVibrator vibrator(vibscore::hil::UinputVibratorOptions::phone_vibrator());
        DaemonFixture daemon(
            "requests-per-second = 100000\nrequest-burst = 100000\n"
            "driver = evdev\n[virtual-vibra]\nenabled = true\n"
            "[evdev]\ndevice = " +
            vibrator.event_node().string());
        std::vector<std::unique_ptr<ChrootMounts>> mounts;
        for (const auto& root : roots) {
            mounts.push_back(std::make_unique<ChrootMounts>(root));
            versions.emplace_back(feedbackd_version(root), root.string());
        }
        peers.push_back(std::make_unique<Peer>("feedbackd " + host_version + ", directly",
                                               "feedbackd", real_feedbackd()));
        for (std::size_t i = 0; i < roots.size(); ++i) {
            const auto& version = versions[i + 1].first;
            peers.push_back(std::make_unique<Peer>(
                "feedbackd " + version + " (" + roots[i].string() + "), directly",
                "feedbackd_" + version_key(version), real_feedbackd(roots[i])));
        }
        peers.push_back(std::make_unique<Peer>(
            "vibscore-feedback -> vibscored (evdev)", "vibscore",
            vibscore_feedback({"--theme", required_env("VIBSCORE_FEEDBACK_THEME")})));
        // More feedbackds that find only the virtual vibra; the first ones keep the one they have.
        const auto virtual_vibra = vibscore::hil::find_virtual_vibra();
        if (!virtual_vibra) {
            throw std::runtime_error("vibscored made no virtual vibra");
        }
        std::filesystem::remove(vibrator.udev_entry());
        vibscore::hil::FeedbackdVibraMark mark(*virtual_vibra);
        peers.push_back(
            std::make_unique<Peer>("feedbackd " + host_version + " -> virtual vibra -> vibscored",
                                   "feedbackd_virtual_vibra", real_feedbackd()));
        for (std::size_t i = 0; i < roots.size(); ++i) {
            const auto& version = versions[i + 1].first;
            peers.push_back(std::make_unique<Peer>(
                "feedbackd " + version + " -> virtual vibra -> vibscored",
                "feedbackd_" + version_key(version) + "_virtual_vibra", real_feedbackd(roots[i])));
        }
        std::fprintf(stderr, "feedback latency: %d rounds of %s on %zu peers...\n", rounds,
                     event.c_str(), peers.size());
        for (int round = 0; round < rounds; ++round) {
            for (auto& peer : peers) {
                trigger_once(*peer->client, vibrator, event, peer->series);
            }
        }
        // The clients and servers go before the mounts their programs run in.
        for (auto& peer : peers) {
            peer->client.reset();
            peer->server.reset();
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "feedback_latency: %s\n", error.what());
        return 1;
    }

    utsname system{};
    uname(&system);
    const std::string cpu = cpu_model();
    std::printf("TriggerFeedback(%s, profile quiet) -> EV_FF play at a uinput vibra\n",
                event.c_str());
    std::printf("  kernel %s, CPU \"%s\" (\"QEMU TCG CPU\": emulated, not real time)\n",
                system.release, cpu.c_str());
    int missed = 0;
    Summary vibscore;
    std::string json;
    for (const auto& peer : peers) {
        const auto summary = summarize(peer->series.ms);
        print_row(peer->name, summary);
        missed += peer->series.missed;
        if (peer->key == "vibscore") {
            vibscore = summary;
        }
        json += "," + json_summary(peer->key.c_str(), summary);
    }
    for (const auto& peer : peers) {
        if (peer->key.starts_with("feedbackd") && !peer->key.ends_with("virtual_vibra")) {
            const auto summary = summarize(peer->series.ms);
            std::printf(
                "  %s / vibscore-feedback at p50: %.2fx, at p99: %.2fx (aim >= 3x at p99)\n",
                peer->name.substr(0, peer->name.find(',')).c_str(), summary.p50 / vibscore.p50,
                summary.p99 / vibscore.p99);
            json += ",\"" + peer->key +
                    "_over_vibscore_p50\":" + std::to_string(summary.p50 / vibscore.p50) + ",\"" +
                    peer->key +
                    "_over_vibscore_p99\":" + std::to_string(summary.p99 / vibscore.p99);
        }
    }
    std::printf("  missed %d\n", missed);
    std::string version_list;
    for (const auto& [version, root] : versions) {
        version_list += std::string(version_list.empty() ? "" : ",") + "{\"root\":\"" +
                        json_escape(root) + "\",\"feedbackd\":\"" + json_escape(version) + "\"}";
    }
    std::printf(
        "{\"bench\":\"feedback_latency\",\"kernel\":\"%s\",\"cpu\":\"%s\",\"event\":\"%s\","
        "\"feedbackd_versions\":[%s]%s,\"missed\":%d}\n",
        json_escape(system.release).c_str(), json_escape(cpu).c_str(), json_escape(event).c_str(),
        version_list.c_str(), json.c_str(), missed);
    return missed == 0 ? 0 : 1;
}
