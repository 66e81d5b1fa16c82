// Every document in clefs/ loads, validates, survives a write/read round trip and renders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "daemon/render/performance.hpp"
#include "daemon/render/sampler.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"
#include "tests/support/run_command.hpp"

namespace vibscore {
namespace {

std::filesystem::path shipped_dir() {
    return testing::required_env("VIBSCORE_CLEFS");
}

std::vector<std::filesystem::path> shipped(const char* suffix) {
    std::vector<std::filesystem::path> found;
    for (const auto& entry : std::filesystem::directory_iterator(shipped_dir())) {
        const auto name = entry.path().filename().string();
        if (name.ends_with(suffix)) {
            found.push_back(entry.path());
        }
    }
    std::sort(found.begin(), found.end());
    return found;
}

TEST(ShippedDocuments, EveryXmlFileIsAScoreOrAClefNamedForItsKind) {
    for (const auto& entry : std::filesystem::directory_iterator(shipped_dir())) {
        const auto name = entry.path().filename().string();
        if (entry.path().extension() != ".xml") {
            continue;
        }
        const auto kind = document_kind(read_document_file(entry.path()), name);
        EXPECT_TRUE(kind == DocumentKind::clef ? name.ends_with(".clef.xml")
                                               : name.ends_with(".score.xml"))
            << name;
    }
}

TEST(ShippedDocuments, EveryClefRoundTrips) {
    const auto clefs = shipped(".clef.xml");
    ASSERT_GE(clefs.size(), 5u);
    for (const auto& path : clefs) {
        const Clef clef = load_clef_file(path);
        EXPECT_EQ(read_clef(write_clef(clef), "written"), clef) << path;
    }
}

TEST(ShippedDocuments, EveryScoreRoundTripsAndRendersAFiniteAudibleSignal) {
    const auto scores = shipped(".score.xml");
    ASSERT_GE(scores.size(), 20u);
    for (const auto& path : scores) {
        SCOPED_TRACE(path.string());
        const auto bundle = load_score_file(path);
        EXPECT_FALSE(bundle.score.title.empty());
        EXPECT_EQ(read_score(write_score(bundle.score), "written").score, bundle.score);
        const render::Performance performance(bundle);
        EXPECT_GT(performance.duration(), 0.0);
        EXPECT_GT(performance.peak_amplitude(), 0.0);
        std::vector<double> samples(render::sample_index_at(performance.duration(), 8000));
        render::render_signal(performance, 8000, 0, samples);
        double peak = 0.0;
        for (const double y : samples) {
            ASSERT_TRUE(std::isfinite(y));
            peak = std::max(peak, std::abs(y));
        }
        EXPECT_GT(peak, 0.0);
    }
}

TEST(ShippedDocuments, TheNamedTactonsAndPiecesAreThere) {
    for (const char* name : {"create",
                             "delete",
                             "file",
                             "folder",
                             "create-file",
                             "create-folder",
                             "delete-file",
                             "delete-folder",
                             "call",
                             "message",
                             "call-high-priority",
                             "notification-message",
                             "notification-mail",
                             "notification-calendar",
                             "alarm",
                             "ringtone",
                             "success",
                             "failure",
                             "touch-tick",
                             "touch-click",
                             "ode-to-joy",
                             "twinkle-twinkle"}) {
        EXPECT_TRUE(std::filesystem::exists(shipped_dir() / (std::string(name) + ".score.xml")))
            << name;
    }
}

TEST(ShippedDocuments, Figure51bClefsHaveTheThesisNumbers) {
    const Clef low = load_clef_file(shipped_dir() / "shaker-sine-low.clef.xml");
    const Clef high = load_clef_file(shipped_dir() / "shaker-sine-high.clef.xml");
    const std::vector<double> low_numbers{0.0027, 0.0039, 0.0055, 0.0078, 0.0110,
                                          0.0156, 0.0222, 0.0315, 0.0447};
    const std::vector<double> high_numbers{0.0447, 0.0634, 0.0900, 0.1277, 0.1813,
                                           0.2572, 0.3650, 0.5180, 0.7351};
    EXPECT_EQ(low.numbers, low_numbers);
    EXPECT_EQ(high.numbers, high_numbers);
    for (const Clef* clef : {&low, &high}) {
        EXPECT_EQ(clef->type, ClefType::sine);
        EXPECT_EQ(clef->tempo, 0.15);
        ASSERT_EQ(clef->strings.size(), 6u);
        for (std::size_t s = 0; s < 6; ++s) {
            EXPECT_EQ(clef->strings[s].frequency, 50.0 * static_cast<double>(s + 1));
        }
    }
}

TEST(ShippedDocuments, Figure52bClefIsASquareWaveFrom120msOnString1To20msOnString6) {
    const Clef rough = load_clef_file(shipped_dir() / "erm-rough.clef.xml");
    ASSERT_EQ(rough.strings.size(), 6u);
    const double periods_ms[] = {120, 100, 80, 60, 40, 20};
    for (std::size_t s = 0; s < 6; ++s) {
        const render::Waveform wave(rough.type, rough.strings[s].points);
        const double period = periods_ms[s] / 1000.0 / rough.tempo;  // in quarter notes
        // On for the first half of every period, off for the second.
        for (double at : {0.1, 0.4, 0.6, 0.9}) {
            const double tau = period * (2.0 + at);
            EXPECT_DOUBLE_EQ(wave.level(tau), at < 0.5 ? 1.0 : 0.0) << "string " << s + 1;
        }
    }
}

TEST(ShippedDocuments, HigherStringsAreHigherPitchedInEverySineClef) {
    for (const auto& path : shipped(".clef.xml")) {
        const Clef clef = load_clef_file(path);
        if (clef.type != ClefType::sine) {
            continue;
        }
        for (std::size_t s = 1; s < clef.strings.size(); ++s) {
            EXPECT_GT(clef.strings[s].frequency, clef.strings[s - 1].frequency) << path;
        }
    }
}

}  // namespace
}  // namespace vibscore
