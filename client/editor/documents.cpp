#include "client/editor/documents.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "score/bundle.hpp"
#include "score/registry_names.hpp"
#include "score/score_xml.hpp"

namespace vibscore::editor {

ScoreSource classify_source(const std::string& argument) {
    std::error_code ignored;
    const bool looks_like_path = argument.find('/') != std::string::npos ||
                                 argument.ends_with(".xml") ||
                                 std::filesystem::is_regular_file(argument, ignored);
    return {looks_like_path ? ScoreSource::Kind::file : ScoreSource::Kind::registry, argument};
}

Score read_score_file(const std::filesystem::path& path) {
    return read_score(read_document_file(path), path.string()).score;
}

void write_score_file(const std::filesystem::path& path, const Score& score) {
    write_document_file(path, write_score(score));
}

void write_document_file(const std::filesystem::path& path, const std::string& text) {
    const auto temporary = std::filesystem::path(path.string() + ".tmp");
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) {
            throw std::runtime_error(temporary.string() +
                                     ": cannot write: " + std::strerror(errno));
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw std::runtime_error(path.string() + ": cannot replace: " + error.message());
    }
}

std::vector<ClefDeclaration> clefs_beside(const std::filesystem::path& score_file) {
    std::vector<ClefDeclaration> clefs;
    const auto directory = score_file.has_parent_path() ? score_file.parent_path() : ".";
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
        const std::string name = entry.path().filename().string();
        if (name.size() > kClefSuffix.size() && name.ends_with(kClefSuffix)) {
            clefs.push_back({name.substr(0, name.size() - kClefSuffix.size()), name});
        }
    }
    std::sort(clefs.begin(), clefs.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    return clefs;
}

std::vector<ClefDeclaration> registry_clefs(const std::vector<std::string>& names) {
    std::vector<ClefDeclaration> clefs;
    for (const auto& name : names) {
        clefs.push_back({name, name + std::string(kClefSuffix)});
    }
    return clefs;
}

std::string registry_document(Score score) {
    for (auto& clef : score.clefs) {
        // "lra-phone.clef.xml/" names lra-phone.clef.xml too: its file name alone is empty,
        // which no score may have (the fuzzer found it). An href with no name at all ("/") is
        // left as it is, for vibscored to refuse by name.
        std::string_view href = clef.href;
        while (href.ends_with('/')) {
            href.remove_suffix(1);
        }
        const std::string name = std::filesystem::path(href).filename().string();
        if (!name.empty()) {
            clef.href = name;
        }
    }
    return write_score(score);
}

}  // namespace vibscore::editor
