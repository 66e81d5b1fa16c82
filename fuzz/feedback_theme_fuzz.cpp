// libFuzzer target: vibscore-feedback's theme reader (the shared JSON reader with its nesting
// and number limits, then either theme format). Any text must end in a theme or a
// DocumentError, within the reader's bounds: the seed deep-theme.json, nested 10,000 deep,
// took 14.9 s and 1.7 GB before the reader was shared and capped.
#include <cstddef>
#include <cstdint>

#include "feedback/feedbackd_theme.hpp"
#include "feedback/theme.hpp"
#include "fuzz/fuzz_support.hpp"
#include "json/json_document.hpp"
#include "score/document_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    if (size > max_json_file_bytes) {
        return 0;  // read_json_file refuses it before parsing
    }
    // Parent themes are looked for nowhere, so that no input reads a file.
    static const feedback::ThemeSearch nowhere{{}, {}, {}, "/nonexistent/feedbackd/themes"};
    try {
        feedback::parse_theme(JsonDocument(fuzz::as_text(data, size), "fuzz.json"), nowhere);
    } catch (const DocumentError&) {
    }
    return 0;
}
