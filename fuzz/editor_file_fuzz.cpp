// The editor's file loader on any file up to 1 MiB: a score or DocumentError. A score it opens
// is saved and reopened equal, and its registry form (what it sends vibscored) reads back.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "client/editor/documents.hpp"
#include "fuzz/fuzz_support.hpp"
#include "score/document_error.hpp"
#include "score/limits.hpp"
#include "score/score_xml.hpp"

namespace {

// A file in this process's own scratch directory.
std::filesystem::path scratch(const char* name) {
    static const auto dir = [] {
        auto path = std::filesystem::temp_directory_path() /
                    ("vibscore-editor-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(path);
        return path;
    }();
    return dir / name;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace vibscore;
    if (size > limits::document_bytes) {
        return 0;
    }
    const auto file = scratch("input.score.xml");
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    Score score;
    try {
        score = editor::read_score_file(file);
    } catch (const DocumentError&) {
        return 0;
    }
    const auto saved = scratch("saved.score.xml");
    editor::write_score_file(saved, score);
    try {
        if (!(editor::read_score_file(saved) == score)) {
            fuzz::invariant_broken("saving then opening changed the score");
        }
        read_score(editor::registry_document(score), "registry.score.xml");
    } catch (const DocumentError&) {
        fuzz::invariant_broken("a score the editor opened does not read back");
    }
    return 0;
}
