// libFuzzer target: the Android readers, VibrationEffect.createWaveform's JSON and the XML
// VibrationEffect.parseFromXml reads (waveforms, envelopes, repeating effects), onto the grid.
// Any text must end in a score or a DocumentError from each.
#include <cstddef>
#include <cstdint>

#include "client/formats/android.hpp"
#include "fuzz/fuzz_clef.hpp"
#include "fuzz/fuzz_support.hpp"
#include "score/document_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    const auto text = fuzz::as_text(data, size);
    try {
        formats::read_android_json(text, "fuzz.json", fuzz::chosen_clef());
    } catch (const DocumentError&) {
    }
    try {
        formats::read_android_xml(text, "fuzz.xml", fuzz::chosen_clef());
    } catch (const DocumentError&) {
    }
    return 0;
}
