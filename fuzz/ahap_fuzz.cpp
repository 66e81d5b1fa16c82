// libFuzzer target: the AHAP reader (JSON parsing, line and column of errors, curves and
// events onto the grid). Any text must end in a score or a DocumentError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "client/formats/ahap.hpp"
#include "fuzz/fuzz_clef.hpp"
#include "score/document_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    try {
        formats::read_ahap(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ahap",
                           fuzz::chosen_clef());
    } catch (const DocumentError&) {
    }
    return 0;
}
