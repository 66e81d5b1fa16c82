// A flooder for the admission tests (issue 33, row 1): N connections of whoever runs it, each
// calling Play with an inline score of just under 1 MiB (bench/flood.hpp) as fast as the daemon
// answers, until killed. Prints one line the first time each answer occurs ("admitted", or the
// error's name and the start of its message), so a test can wait for the refusal it expects.
#include <sdbus-c++/sdbus-c++.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "bench/flood.hpp"
#include "dbus/sdbus_compat.hpp"

int main(int argc, char** argv) {
    const int connections = argc > 1 ? std::atoi(argv[1]) : 1;
    const std::string score = vibscore::bench::inline_score_of(1u << 20);
    std::mutex mutex;
    std::set<std::string> seen;
    const auto report = [&](const std::string& line) {
        const std::lock_guard lock(mutex);
        if (seen.insert(line).second) {
            std::printf("%s\n", line.c_str());
            std::fflush(stdout);
        }
    };
    std::vector<std::thread> threads;
    for (int i = 0; i < connections; ++i) {
        threads.emplace_back([&] {
            try {
                auto connection = sdbus::createSystemBusConnection();
                auto proxy = vibscore::dbus::create_proxy(*connection, "org.vibscore.Haptics1",
                                                          "/org/vibscore/Haptics1");
                const std::map<std::string, sdbus::Variant> options;
                for (;;) {
                    try {
                        std::uint64_t id = 0;
                        proxy->callMethod("Play")
                            .onInterface("org.vibscore.Haptics1")
                            .withArguments(score, options)
                            .storeResultsTo(id);
                        report("admitted");
                    } catch (const sdbus::Error& error) {
                        report(error.getName() + ": " + error.getMessage().substr(0, 80));
                    }
                }
            } catch (const std::exception& error) {
                report(std::string("flood_client: ") + error.what());
            }
        });
    }
    for (auto& thread : threads) {
        thread.join();
    }
    return 0;
}
