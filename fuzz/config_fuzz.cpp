// vibscored.conf's parser on any text: a configuration or ConfigError, nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "daemon/config.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    try {
        const auto config =
            daemon::parse_config(std::string(fuzz::as_text(data, size)), "fuzz.conf");
        if (config.driver.empty()) {
            fuzz::invariant_broken("a configuration without a driver");
        }
    } catch (const daemon::ConfigError&) {
    }
    return 0;
}
