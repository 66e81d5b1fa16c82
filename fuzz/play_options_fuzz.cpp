// Play's options dictionary (a{sv}) as a caller may send it: keys Play knows and any others,
// each with a value of any basic type. parse_play_options answers with options or RequestError.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "daemon/play_request.hpp"
#include "daemon/request_error.hpp"
#include "fuzz/fuzz_support.hpp"

namespace {

sdbus::Variant any_value(FuzzedDataProvider& input) {
    switch (input.ConsumeIntegralInRange(0, 6)) {
        case 0:
            return sdbus::Variant(input.ConsumeRandomLengthString(64));
        case 1:
            return sdbus::Variant(input.ConsumeIntegral<std::int32_t>());
        case 2:
            return sdbus::Variant(input.ConsumeIntegral<std::uint32_t>());
        case 3:
            return sdbus::Variant(input.ConsumeFloatingPoint<double>());
        case 4:
            return sdbus::Variant(input.ConsumeBool());
        case 5:
            return sdbus::Variant(input.ConsumeIntegral<std::uint64_t>());
        default:
            return sdbus::Variant(input.ConsumeIntegral<std::int16_t>());
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    static const char* const kKeys[] = {"usage", "repeat", "intensity", "clef", "start-bar"};
    FuzzedDataProvider input(data, size);
    std::map<std::string, sdbus::Variant> options;
    const int count = input.ConsumeIntegralInRange(0, 8);
    try {
        for (int i = 0; i < count && input.remaining_bytes() > 0; ++i) {
            const std::string key = input.ConsumeBool() ? std::string(input.PickValueInArray(kKeys))
                                                        : input.ConsumeRandomLengthString(16);
            options[key] = any_value(input);
        }
    } catch (const sdbus::Error&) {
        return 0;  // a string that is not UTF-8: no bus message can carry it to the daemon
    }
    try {
        const auto parsed = daemon::parse_play_options(options);
        if (parsed.intensity < 0.0 || parsed.intensity > 1.0 || parsed.repeat < -1) {
            fuzz::invariant_broken("accepted options outside their documented ranges");
        }
    } catch (const daemon::RequestError&) {
    }
    return 0;
}
