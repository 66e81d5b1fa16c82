// Clefs fitted to the actuator are fitted once per (clef name and content, declaration) and kept
// (issue 30, item 5); another declaration or a clear() (a reload, a clef composed) fits again.
#include "daemon/clef_fit_cache.hpp"

#include <gtest/gtest.h>

#include "daemon/config.hpp"
#include "daemon/play_request.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

Clef sine(double tempo) {
    Clef clef;
    clef.tempo = tempo;
    clef.numbers = {0.5, 1.0};
    clef.strings = {ClefString{150.0, {}}};
    return clef;
}

actuator::Declaration declared(double rated_drive) {
    actuator::Declaration declaration;
    declaration.rated_drive = rated_drive;
    return declaration;
}

// A stand-in fit that is recognisable and counts its calls (the real one is clef_fit_test's).
struct CountingFit {
    int calls = 0;
    Clef operator()(const Clef& written) {
        ++calls;
        Clef fitted = written;
        fitted.tempo = written.tempo * 2;
        return fitted;
    }
};

TEST(ClefFitCache, AClefIsFittedOnceForTheSameNameContentAndDeclaration) {
    ClefFitCache cache;
    CountingFit fit;
    const auto fitter = [&](const Clef& clef) { return fit(clef); };
    EXPECT_EQ(cache.fitted("lra-phone", sine(1.0), declared(0.7), fitter).tempo, 2.0);
    EXPECT_EQ(cache.fitted("lra-phone", sine(1.0), declared(0.7), fitter).tempo, 2.0);
    EXPECT_EQ(fit.calls, 1);
    EXPECT_EQ(cache.size(), 1u);
}

TEST(ClefFitCache, AnotherContentUnderTheSameNameOrAnotherNameIsFittedAgain) {
    ClefFitCache cache;
    CountingFit fit;
    const auto fitter = [&](const Clef& clef) { return fit(clef); };
    cache.fitted("lra-phone", sine(1.0), declared(0.7), fitter);
    EXPECT_EQ(cache.fitted("lra-phone", sine(0.5), declared(0.7), fitter).tempo, 1.0);
    cache.fitted("erm", sine(1.0), declared(0.7), fitter);
    EXPECT_EQ(fit.calls, 3);
    EXPECT_EQ(cache.size(), 3u);
}

TEST(ClefFitCache, AnotherDeclarationEmptiesItAndClearDoesToo) {
    ClefFitCache cache;
    CountingFit fit;
    const auto fitter = [&](const Clef& clef) { return fit(clef); };
    cache.fitted("lra-phone", sine(1.0), declared(0.7), fitter);
    cache.fitted("lra-phone", sine(1.0), declared(0.8), fitter);
    EXPECT_EQ(fit.calls, 2);
    EXPECT_EQ(cache.size(), 1u);  // only the new declaration's
    cache.fitted("lra-phone", sine(1.0), declared(0.7), fitter);
    EXPECT_EQ(fit.calls, 3);
    cache.clear();
    EXPECT_EQ(cache.size(), 0u);
    cache.fitted("lra-phone", sine(1.0), declared(0.7), fitter);
    EXPECT_EQ(fit.calls, 4);
}

TEST(ClefFitCache, HoldsItsBoundOfEntriesAndIsEmptiedBeforeTheNextOne) {
    ClefFitCache cache;
    CountingFit fit;
    const auto fitter = [&](const Clef& clef) { return fit(clef); };
    for (std::size_t i = 0; i < ClefFitCache::kMaxEntries; ++i) {
        cache.fitted("clef-" + std::to_string(i), sine(1.0), declared(0.7), fitter);
    }
    EXPECT_EQ(cache.size(), ClefFitCache::kMaxEntries);  // the last one kept
    cache.fitted("one-more", sine(1.0), declared(0.7), fitter);
    EXPECT_EQ(cache.size(), 1u);
    cache.fitted("one-more", sine(1.0), declared(0.7), fitter);
    EXPECT_EQ(fit.calls, static_cast<int>(ClefFitCache::kMaxEntries) + 1);
}

TEST(ClefFitCache, WhatTheFitThrowsIsNotKept) {
    ClefFitCache cache;
    int calls = 0;
    const auto failing = [&](const Clef&) -> Clef {
        ++calls;
        throw std::runtime_error("cannot fit");
    };
    EXPECT_THROW(cache.fitted("x", sine(1.0), declared(0.7), failing), std::runtime_error);
    EXPECT_THROW(cache.fitted("x", sine(1.0), declared(0.7), failing), std::runtime_error);
    EXPECT_EQ(calls, 2);
    EXPECT_EQ(cache.size(), 0u);
}

// Through Play's own path: the shipped "success" (written for lra-phone) played twice on an LRA
// with fit = auto fits lra-phone once, and plays the same clef as without the cache.
TEST(ClefFitCache, AScorePlayedTwiceThroughAFittedClefFitsItOnce) {
    vibscore::testing::TempDir store;
    const Registry registry{
        std::filesystem::path(vibscore::testing::required_env("VIBSCORE_CLEFS")), store.path()};
    const auto map = parse_config(
                         "[actuator]\nkind = lra\nresonance-hz = 175\nq = 15\nrated-drive = 0.7\n"
                         "[clefs]\nfit = auto\n",
                         "test.conf")
                         .device_clefs;
    ASSERT_TRUE(map.fit_to);
    ClefFitCache cache;
    const auto first = find_score_to_play(registry, "success", {}, map, &cache);
    const auto second = find_score_to_play(registry, "success", {}, map, &cache);
    EXPECT_EQ(cache.fits(), 1u);
    const auto uncached = find_score_to_play(registry, "success", {}, map);
    EXPECT_EQ(first.bundle.clefs, uncached.bundle.clefs);
    EXPECT_EQ(second.bundle.clefs, uncached.bundle.clefs);
}

}  // namespace
}  // namespace vibscore::daemon
