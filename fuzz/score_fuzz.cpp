// The score reader on any input up to the daemon's 1 MiB limit: it either reads a score or
// throws DocumentError. A score it reads is written and read back equal (round trip), and
// binding its clefs either succeeds with a clef for every bar or throws DocumentError.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/limits.hpp"
#include "score/score_xml.hpp"

namespace {

const char* const kSineClef =
    "<VibClef type=\"sine\" version=\"1.0\"><Tempo>0.2</Tempo><Numbers><Number>0.2</Number>"
    "<Number>0.5</Number><Number>1.0</Number></Numbers><Strings><String>155</String>"
    "<String>200</String></Strings></VibClef>";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    if (size > limits::document_bytes) {
        return 0;
    }
    ParsedScore parsed;
    try {
        parsed = read_score(fuzz::as_text(data, size), "fuzz.score.xml");
    } catch (const DocumentError&) {
        return 0;
    }
    const std::string written = write_score(parsed.score);
    try {
        if (!(read_score(written, "written.score.xml").score == parsed.score)) {
            fuzz::invariant_broken("write_score then read_score changed the score");
        }
    } catch (const DocumentError&) {
        fuzz::invariant_broken("read_score refused what write_score wrote");
    }
    static const Clef clef = read_clef(kSineClef, "fuzz.clef.xml");
    try {
        const ScoreBundle bundle =
            bind_clefs(parsed, "fuzz.score.xml",
                       [](const ClefDeclaration&, const SourceLocation&) { return clef; });
        for (const auto& bar : bundle.score.bars) {
            if (bundle.clefs.find(bar.clef) == bundle.clefs.end()) {
                fuzz::invariant_broken("a bound score has a bar without its clef");
            }
        }
    } catch (const DocumentError&) {
    }
    return 0;
}
