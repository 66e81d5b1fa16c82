// libFuzzer target: the Standard MIDI File reader and the MIDI import on top of it. Any input
// must end in a score or a DocumentError; anything else (a crash, another exception, a
// sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "client/formats/midi.hpp"
#include "client/formats/midi_file.hpp"
#include "fuzz/fuzz_clef.hpp"
#include "score/document_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const auto file = formats::midi::read(bytes, "fuzz.mid");
        // What was read writes back out and reads again.
        formats::midi::read(formats::midi::write(file), "rewritten.mid");
        formats::read_midi(bytes, "fuzz.mid", fuzz::chosen_clef(), std::nullopt);
    } catch (const DocumentError&) {
    }
    return 0;
}
