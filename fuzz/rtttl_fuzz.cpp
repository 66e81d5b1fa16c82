// libFuzzer target: the RTTTL reader. Any text must end in a score or a DocumentError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "client/formats/rtttl.hpp"
#include "fuzz/fuzz_clef.hpp"
#include "score/document_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    try {
        formats::read_rtttl(std::string_view(reinterpret_cast<const char*>(data), size),
                            "fuzz.rtttl", fuzz::chosen_clef());
    } catch (const DocumentError&) {
    }
    return 0;
}
