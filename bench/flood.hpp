#pragma once

#include <sys/types.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "tests/support/daemon_fixture.hpp"

// What the benchmarks that flood vibscored share: the largest inline score the limits admit, and
// the daemon's process as the bus sees it.
namespace vibscore::bench {

// 2,250 whole notes through lra-phone (0.8 s each): 30 minutes, inside the one-hour limit.
inline std::string largest_inline_score() {
    std::string bars;
    for (int i = 0; i < 2250; ++i) {
        bars += "<Bar clef=\"l\"><Note length=\"whole\" number=\"" + std::to_string(1 + i % 9) +
                "\" string=\"" + std::to_string(1 + i % 6) + "\"/></Bar>";
    }
    return "<VibScore><Title>flood</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>" + bars +
           "</VibScore>";
}

// An ordinary inline score of about `bytes` (at most 1 MiB, the document limit): bars of four
// 32nd notes through lra-phone, about 45 bytes a note, so 1 MiB is some 23,000 notes (about
// 5,800 bars, under 10 minutes): issue 33's probe sent 1 MiB inline scores.
inline std::string inline_score_of(std::size_t bytes) {
    const std::string head =
        "<VibScore><Title>flood</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>";
    const std::string tail = "</VibScore>";
    std::string bars;
    for (int i = 0; head.size() + bars.size() + tail.size() + 300 < bytes; ++i) {
        bars += "<Bar clef=\"l\">";
        for (int note = 0; note < 4; ++note) {
            bars += "<Note length=\"32th\" number=\"" + std::to_string(1 + (i + note) % 9) +
                    "\" string=\"" + std::to_string(1 + (i + note) % 6) + "\"/>";
        }
        bars += "</Bar>";
    }
    return head + bars + tail;
}

// The process that owns `name` on the fixture's bus; 0 when none does.
inline pid_t owner_pid(const testing::DaemonFixture& daemon,
                       const std::string& name = "org.vibscore.Haptics1") {
    const auto status = daemon.busctl({"status", "--no-pager", name});
    std::istringstream lines(status.out);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("PID=", 0) == 0) {
            return static_cast<pid_t>(std::stol(line.substr(4)));
        }
    }
    return 0;
}

// A process's user + system CPU time in seconds, from /proc.
inline double cpu_seconds(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto close = text.rfind(')');
    if (close == std::string::npos) {
        return 0;
    }
    std::istringstream fields(text.substr(close + 2));
    std::string field;
    double ticks = 0;
    for (int index = 3; fields >> field; ++index) {
        if (index == 14 || index == 15) {
            ticks += std::stod(field);
        }
    }
    return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// A /proc/PID/status value in KiB ("VmHWM"); -1 when absent.
inline long status_kib(pid_t pid, const std::string& key) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind(key + ":", 0) == 0) {
            return std::stol(line.substr(key.size() + 1));
        }
    }
    return -1;
}

}  // namespace vibscore::bench
