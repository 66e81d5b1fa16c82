#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"

namespace vibscore::testing {

// A fresh directory under the system temporary directory, removed with everything in it.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path write(const std::string& name, const std::string& text) const;

  private:
    std::filesystem::path path_;
};

// The whole content of a file ("" if it cannot be read).
std::string read_file(const std::filesystem::path& path);

// The names of the entries of a directory, sorted.
std::vector<std::string> file_names(const std::filesystem::path& directory);

// A score bound to in-memory clef documents, keyed by href.
ScoreBundle bundle_from(const std::string& score_xml,
                        const std::map<std::string, std::string>& clefs_by_href);

// A sine clef document: the given tempo, frequencies for strings 1.., amplitudes for numbers 1..
std::string sine_clef(double tempo, const std::vector<double>& frequencies,
                      const std::vector<double>& amplitudes);

// The score's notes in order, rests left out.
std::vector<Note> notes_in(const Score& score);

// Wraps bar contents (Note/Rest elements) into a one-clef score using clef "c" at "c.xml".
std::string one_clef_score(const std::string& bars_xml);

// The message of the first diagnostic, and its line, from a DocumentError thrown by f.
template <typename F>
Diagnostic first_diagnostic(F&& f) {
    try {
        f();
    } catch (const DocumentError& error) {
        return error.diagnostics().at(0);
    }
    return {{}, "<no error thrown>"};
}

}  // namespace vibscore::testing
