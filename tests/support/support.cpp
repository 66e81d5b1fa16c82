#include "tests/support/support.hpp"

#include <algorithm>
#include <fstream>
#include <random>

#include "score/xml_support.hpp"

namespace vibscore::testing {

TempDir::TempDir() {
    std::random_device random;
    path_ = std::filesystem::temp_directory_path() /
            ("vibscore-test-" + std::to_string(random()) + std::to_string(random()));
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

std::filesystem::path TempDir::write(const std::string& name, const std::string& text) const {
    const auto file = path_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> file_names(const std::filesystem::path& directory) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) {
        names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

ScoreBundle bundle_from(const std::string& score_xml,
                        const std::map<std::string, std::string>& clefs_by_href) {
    return bind_clefs(read_score(score_xml, "score.xml"), "score.xml",
                      [&](const ClefDeclaration& declaration, const SourceLocation& where) {
                          const auto found = clefs_by_href.find(declaration.href);
                          if (found == clefs_by_href.end()) {
                              throw DocumentError(where, "no clef at " + declaration.href);
                          }
                          return read_clef(found->second, declaration.href);
                      });
}

std::string sine_clef(double tempo, const std::vector<double>& frequencies,
                      const std::vector<double>& amplitudes) {
    std::string text = "<VibClef type=\"sine\" version=\"1.0\"><Tempo>" +
                       xml::format_number(tempo) + "</Tempo><Numbers>";
    for (const double amplitude : amplitudes) {
        text += "<Number>" + xml::format_number(amplitude) + "</Number>";
    }
    text += "</Numbers><Strings>";
    for (const double frequency : frequencies) {
        text += "<String>" + xml::format_number(frequency) + "</String>";
    }
    return text + "</Strings></VibClef>";
}

std::vector<Note> notes_in(const Score& score) {
    std::vector<Note> notes;
    for (const auto& bar : score.bars) {
        for (const auto& symbol : bar.symbols) {
            if (const auto* note = std::get_if<Note>(&symbol)) {
                notes.push_back(*note);
            }
        }
    }
    return notes;
}

std::string one_clef_score(const std::string& bars_xml) {
    return "<VibScore version=\"1.0\"><Title>t</Title><Clef id=\"c\" href=\"c.xml\"/>" + bars_xml +
           "</VibScore>";
}

}  // namespace vibscore::testing
