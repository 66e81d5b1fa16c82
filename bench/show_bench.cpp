// `vibscore show SCORE --svg FILE` in-process: generated scores of 1,000 to 8,000 notes and one
// of the largest size the reader takes (1 MiB of XML), each read from its file, laid out as a
// staff and written as an SVG, as the verb does. Prints a table and one JSON line; asserts
// nothing (docs/performance.md, "Pictures").
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/report.hpp"
#include "client/pictures/staff_picture.hpp"
#include "score/limits.hpp"
#include "score/score_xml.hpp"

namespace {

using namespace vibscore;
namespace fs = std::filesystem;

// One bar of four beats with every mark the staff draws: legato arcs, portamento lines, a
// crescendo and a decrescendo hairpin, dotted and flagged notes, rests, on all six strings.
// Serials are per bar, so each tie stays inside it.
Bar bench_bar(std::size_t index) {
    const auto serial = static_cast<std::int64_t>(index + 1);
    const auto note = [&](Length length, int i) {
        Note note;
        note.length = length;
        note.number = 1 + static_cast<int>((index + static_cast<std::size_t>(i)) % 9);
        note.string = 1 + static_cast<int>((index * 7 + static_cast<std::size_t>(i)) % 6);
        return note;
    };
    Bar bar;
    bar.clef = "c";
    Note legato = note(Length::eighth, 0);
    legato.legato = serial;
    bar.symbols.emplace_back(legato);
    legato.number = 1 + legato.number % 9;
    bar.symbols.emplace_back(legato);
    Note glide = note(Length::eighth, 2);
    glide.portamento = serial;
    bar.symbols.emplace_back(glide);
    glide.string = 1 + glide.string % 6;
    bar.symbols.emplace_back(glide);
    Note swell = note(Length::eighth_dot, 4);
    swell.dynamics = Dynamics::crescendo;
    bar.symbols.emplace_back(swell);
    swell.length = Length::sixteenth;
    bar.symbols.emplace_back(swell);
    bar.symbols.emplace_back(Rest{Length::sixteenth});
    Note fade = note(Length::eighth, 6);
    fade.dynamics = Dynamics::decrescendo;
    bar.symbols.emplace_back(fade);
    bar.symbols.emplace_back(note(Length::thirty_second, 7));
    bar.symbols.emplace_back(note(Length::thirty_second, 8));
    bar.symbols.emplace_back(Rest{Length::sixteenth});
    return bar;
}

std::size_t notes_in(const Bar& bar) {
    std::size_t count = 0;
    for (const auto& symbol : bar.symbols) {
        count += std::holds_alternative<Note>(symbol) ? 1 : 0;
    }
    return count;
}

Score score_base() {
    Score score;
    score.title = "show bench";
    score.clefs.push_back({"c", "lra-phone.clef.xml"});
    return score;
}

// Exactly `notes` notes (the last bar cut short).
Score score_of_notes(std::size_t notes) {
    Score score = score_base();
    std::size_t count = 0;
    for (std::size_t b = 0; count < notes; ++b) {
        Bar bar = bench_bar(b);
        while (count + notes_in(bar) > notes) {
            bar.symbols.pop_back();
        }
        count += notes_in(bar);
        score.bars.push_back(std::move(bar));
    }
    return score;
}

// As many bars as fit in the reader's 1 MiB.
std::string largest_score_text() {
    Score score = score_base();
    std::string text = write_score(score);
    for (std::size_t b = 0;; ++b) {
        score.bars.push_back(bench_bar(b));
        std::string longer = write_score(score);
        if (longer.size() > limits::document_bytes) {
            return text;
        }
        text = std::move(longer);
    }
}

struct Case {
    std::string name;
    std::size_t notes = 0, bytes = 0;
    double seconds = 0.0;
    double svg_mib = 0.0;
};

// What `vibscore show FILE --svg OUT` does for a score file, timed from reading the file to the
// SVG on disk.
Case time_show(const std::string& name, const fs::path& file, const fs::path& svg) {
    const auto start = std::chrono::steady_clock::now();
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const ParsedScore parsed = read_score(text.str(), file.string());
    const pictures::StaffPicture picture(parsed.score);
    pictures::write_picture(picture, svg);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::size_t notes = 0;
    for (const auto& bar : parsed.score.bars) {
        notes += notes_in(bar);
    }
    return {name, notes, static_cast<std::size_t>(fs::file_size(file)), seconds,
            static_cast<double>(fs::file_size(svg)) / (1024.0 * 1024.0)};
}

}  // namespace

int main(int argc, char** argv) {
    bool with_largest = true;
    fs::path keep;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--no-mib") {
            with_largest = false;
        } else if (arg == "--keep" && i + 1 < argc) {
            keep = argv[++i];
        } else {
            std::printf(
                "usage: %s [--no-mib] [--keep DIR]\n"
                "Times `vibscore show SCORE --svg FILE` in-process on generated scores of 1,000,\n"
                "2,000, 4,000 and 8,000 notes and on a 1 MiB score (--no-mib leaves that out),\n"
                "then prints one JSON line. --keep DIR keeps the scores and pictures there.\n",
                argv[0]);
            return arg == "--help" ? 0 : 2;
        }
    }
    const fs::path folder =
        keep.empty() ? fs::temp_directory_path() / ("show_bench." + std::to_string(getpid()))
                     : keep;
    fs::create_directories(folder);

    std::vector<std::pair<std::string, std::string>> scores;
    for (const std::size_t notes : {1000, 2000, 4000, 8000}) {
        scores.emplace_back(std::to_string(notes) + " notes", write_score(score_of_notes(notes)));
    }
    if (with_largest) {
        scores.emplace_back("1 MiB", largest_score_text());
    }
    std::vector<Case> cases;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        const fs::path file = folder / ("score" + std::to_string(i) + ".vibscore.xml");
        std::ofstream(file, std::ios::binary) << scores[i].second;
        cases.push_back(
            time_show(scores[i].first, file, folder / ("score" + std::to_string(i) + ".svg")));
    }
    if (keep.empty()) {
        fs::remove_all(folder);
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;

    std::printf("vibscore show --svg, in-process (%s)\n", bench::cpu_model().c_str());
    std::printf("  %-12s %8s %10s %10s %10s\n", "score", "notes", "XML bytes", "seconds",
                "SVG MiB");
    for (const auto& c : cases) {
        std::printf("  %-12s %8zu %10zu %10.3f %10.1f\n", c.name.c_str(), c.notes, c.bytes,
                    c.seconds, c.svg_mib);
    }
    std::printf("  peak resident memory of the run: %.1f MiB\n", peak_mib);
    std::string json = "{\"benchmark\":\"show_bench\",\"cpu\":\"" +
                       bench::json_escape(bench::cpu_model()) + "\",\"cases\":[";
    for (std::size_t i = 0; i < cases.size(); ++i) {
        char item[256];
        std::snprintf(item, sizeof item,
                      "%s{\"score\":\"%s\",\"notes\":%zu,\"bytes\":%zu,\"seconds\":%.4f,"
                      "\"svg_mib\":%.2f}",
                      i == 0 ? "" : ",", cases[i].name.c_str(), cases[i].notes, cases[i].bytes,
                      cases[i].seconds, cases[i].svg_mib);
        json += item;
    }
    char tail[64];
    std::snprintf(tail, sizeof tail, "],\"peak_rss_mib\":%.1f}", peak_mib);
    std::printf("%s%s\n", json.c_str(), tail);
    return 0;
}
