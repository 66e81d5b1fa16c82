// The clef reader on any input up to the daemon's 1 MiB limit: it either reads a clef or throws
// DocumentError, and a clef it reads is written and read back equal.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.hpp"
#include "score/clef_xml.hpp"
#include "score/document_error.hpp"
#include "score/limits.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    if (size > limits::document_bytes) {
        return 0;
    }
    Clef clef;
    try {
        clef = read_clef(fuzz::as_text(data, size), "fuzz.clef.xml");
    } catch (const DocumentError&) {
        return 0;
    }
    try {
        if (!(read_clef(write_clef(clef), "written.clef.xml") == clef)) {
            fuzz::invariant_broken("write_clef then read_clef changed the clef");
        }
    } catch (const DocumentError&) {
        fuzz::invariant_broken("read_clef refused what write_clef wrote");
    }
    return 0;
}
