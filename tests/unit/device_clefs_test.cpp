// Device clefs (thesis §4.4): vibscored.conf's [clefs] maps the clefs a score was written for
// onto this device's clefs; Play uses them unless the caller names a clef.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "daemon/config.hpp"
#include "daemon/device_clefs.hpp"
#include "daemon/play_request.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/fitting/clef_fit.hpp"
#include "score/clef_xml.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using Timing = std::tuple<double, int, double, double, std::size_t, std::size_t>;

std::vector<Timing> timings(const std::vector<render::Cue>& cues) {
    std::vector<Timing> result;
    for (const auto& cue : cues) {
        result.emplace_back(cue.at, static_cast<int>(cue.kind), cue.amplitude, cue.frequency_hz,
                            cue.bar, cue.symbol);
    }
    return result;
}

// Play's options with a clef override, or none.
PlayOptions with_clef(const std::string& clef = "") {
    PlayOptions options;
    options.clef = clef;
    return options;
}

// One pass of a request's cues, as the player reads them.
std::vector<Timing> cue_timings(const PlaybackRequest& request) {
    return timings(render::collect(*request.cues->pass()));
}

DeviceClefs clef_map(const std::string& lines) {
    return parse_config("[clefs]\n" + lines, "test.conf").device_clefs;
}

class DeviceClefsTest : public ::testing::Test {
  protected:
    std::filesystem::path shipped{vibscore::testing::required_env("VIBSCORE_CLEFS")};
    vibscore::testing::TempDir store;
    Registry registry{shipped, store.path()};

    // The cues Play makes of `score` on a device with `map`.
    std::vector<Timing> played(const std::string& score, const DeviceClefs& map) const {
        return cue_timings(make_playback_request(
            find_score_to_play(registry, score, with_clef(), map), {}, 0.030));
    }
    // The cues of the shipped score `name` rewritten with other clef hrefs, replaced in turn:
    // what a composer writing for those clefs would have sent.
    std::vector<Timing> rewritten(const std::string& name,
                                  const std::vector<std::pair<std::string, std::string>>& hrefs) {
        auto text = vibscore::testing::read_file(shipped / (name + ".score.xml"));
        for (const auto& [from, to] : hrefs) {
            const std::string old_href = "href=\"" + from + ".clef.xml\"";
            for (auto at = text.find(old_href); at != std::string::npos; at = text.find(old_href)) {
                text.replace(at, old_href.size(), "href=\"" + to + ".clef.xml\"");
            }
        }
        return cue_timings(
            make_playback_request(find_score_to_play(registry, text, with_clef()), {}, 0.030));
    }
};

TEST_F(DeviceClefsTest, TheSameShippedScoreThroughTwoMapsGivesEachMapsCueSchedule) {
    const auto erm = clef_map("lra-phone = erm-phone\n");
    const auto shapes = clef_map("* = soft-shapes\n");
    const auto on_erm = played("success", erm);
    const auto on_shapes = played("success", shapes);
    EXPECT_EQ(on_erm, rewritten("success", {{"lra-phone", "erm-phone"}}));
    EXPECT_EQ(on_shapes, rewritten("success", {{"lra-phone", "soft-shapes"}}));
    EXPECT_NE(on_erm, on_shapes);
    EXPECT_NE(on_erm, played("success", {}));
}

TEST_F(DeviceClefsTest, AMapReplacesOnlyTheClefsItNamesUnlessItHasADefault) {
    const auto high_only = clef_map("shaker-sine-high = shaker-sine-low\n");
    EXPECT_EQ(played("delete-folder", high_only),
              rewritten("delete-folder", {{"shaker-sine-high", "shaker-sine-low"}}));
    const auto with_default = clef_map("shaker-sine-high = shaker-sine-low\n* = erm-phone\n");
    EXPECT_EQ(played("delete-folder", with_default),
              rewritten("delete-folder", {{"shaker-sine-low", "erm-phone"},
                                          {"shaker-sine-high", "shaker-sine-low"}}));
}

TEST_F(DeviceClefsTest, ACallersClefWinsOverTheMap) {
    const auto map = clef_map("* = erm-phone\n");
    const auto chosen = find_score_to_play(registry, "success", with_clef("soft-shapes"), map);
    EXPECT_EQ(chosen.bundle.clefs.at("lra").type, registry.clef("soft-shapes").type);
}

TEST_F(DeviceClefsTest, AClefSentAlongWithTheScorePlaysAsSentWhileItsRegistryClefsAreMapped) {
    const auto mine = vibscore::testing::sine_clef(0.5, {60, 80, 100, 120, 140, 160},
                                                   {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9});
    auto score = vibscore::testing::read_file(shipped / "delete-folder.score.xml");
    const std::string high = "href=\"shaker-sine-high.clef.xml\"";
    score.replace(score.find(high), high.size(), "href=\"clefs/mine.clef.xml\"");
    PlayOptions options;
    options.clef_documents["clefs/mine.clef.xml"] = mine;
    const auto found = find_score_to_play(registry, score, options, clef_map("* = erm-phone\n"));
    const auto bars = found.bundle.score.bars;
    ASSERT_GE(bars.size(), 2u);
    EXPECT_EQ(found.bundle.clef_of(bars[0]).tempo, 0.5);
    EXPECT_EQ(found.bundle.clef_of(bars[1]).type, registry.clef("erm-phone").type);
    EXPECT_EQ(found.bundle.clef_of(bars[1]).tempo, registry.clef("erm-phone").tempo);
}

TEST_F(DeviceClefsTest, EachBarShowsTheClefItNamesAndTheOneItPlaysThroughHere) {
    const auto map = clef_map("shaker-sine-high = erm-phone\n");
    const auto bars = bar_clefs(registry.score("delete-folder"), map);
    ASSERT_GE(bars.size(), 2u);
    EXPECT_EQ(bars[0], (BarClef{"shaker-sine-high", "erm-phone"}));
    EXPECT_EQ(bars[1], (BarClef{"shaker-sine-low", "shaker-sine-low"}));
    for (const auto& bar : bar_clefs(registry.score("success"), {})) {
        EXPECT_EQ(bar, (BarClef{"lra-phone", "lra-phone"}));
    }
}

TEST_F(DeviceClefsTest, ADeviceClefMissingFromTheRegistryIsNotFoundNamingTheMapping) {
    try {
        find_score_to_play(registry, "success", with_clef(),
                           clef_map("lra-phone = my-board-erm\n"));
        FAIL() << "no error";
    } catch (const RegistryError& error) {
        EXPECT_EQ(error.code(), RegistryError::Code::not_found);
        EXPECT_EQ(std::string(error.what()),
                  "no clef \"my-board-erm\" in the registry: vibscored.conf's [clefs] plays clef "
                  "\"lra-phone\" through it");
    }
}

TEST_F(DeviceClefsTest, AMappedClefTheRegistryLacksIsAWarningNamingItsLineAtStart) {
    const auto config = parse_config(
        "[clefs]\nlra-phone = erm-phone\nshaker = my-board-erm\n* = no-such-clef\n", "test.conf");
    EXPECT_EQ(
        missing_device_clefs(config, registry),
        (std::vector<std::string>{
            "test.conf:3: [clefs] shaker = \"my-board-erm\": the registry has no clef "
            "\"my-board-erm\", so Play refuses every score this maps until one is composed",
            "test.conf:4: [clefs] * = \"no-such-clef\": the registry has no clef "
            "\"no-such-clef\", so Play refuses every score this maps until one is composed"}));
    EXPECT_TRUE(
        missing_device_clefs(parse_config("[clefs]\n* = erm-phone\n", "t"), registry).empty());
}

TEST(DeviceClefsConfig, TheClefsSectionTakesRegistryNamesAndStarForAnyOther) {
    const auto map = clef_map("lra-phone = my-board-erm\n* = my-board-default\n");
    EXPECT_EQ(map.for_written("lra-phone"), "my-board-erm");
    EXPECT_EQ(map.for_written("erm-phone"), "my-board-default");
    EXPECT_EQ(DeviceClefs{}.for_written("erm-phone"), "erm-phone");
    EXPECT_THROW(clef_map("lra-phone = ../etc/passwd\n"), ConfigError);
    EXPECT_THROW(clef_map("Lra Phone = erm-phone\n"), ConfigError);
    try {
        clef_map("lra-phone = My-Clef\n");
    } catch (const ConfigError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "test.conf:2: [clefs] lra-phone = \"My-Clef\" is not a registry clef name "
                  "(a-z 0-9 . _ -)");
    }
}

// --- fit = auto ---

const char* const kLra =
    "[actuator]\nkind = lra\nresonance-hz = 175\nq = 15\nrated-drive = 0.7\nbrake = reverse\n";
const char* const kErm =
    "[actuator]\nkind = erm\nspin-up-ms = 40\nspin-down-ms = 80\nrated-drive = 0.7\n"
    "brake = reverse\n";

DeviceClefs fitting(const std::string& actuator, const std::string& lines = "") {
    return parse_config(actuator + "[clefs]\nfit = auto\n" + lines, "test.conf").device_clefs;
}

TEST_F(DeviceClefsTest, FitAutoPlaysEachWrittenClefFittedToTheDeclaredActuator) {
    const auto map = fitting(kLra);
    ASSERT_TRUE(map.fit_to);
    const auto found = find_score_to_play(registry, "success", with_clef(), map);
    const Clef expected = render::fit_clef(registry.clef("lra-phone"), *map.fit_to).clef;
    EXPECT_EQ(found.bundle.clefs.at("lra"), expected);
    EXPECT_EQ(expected.type, ClefType::line);  // the LRA's band is too narrow: roughness
    for (const auto& bar : bar_clefs(registry.score("success"), map)) {
        EXPECT_EQ(bar, (BarClef{"lra-phone", "lra-phone (fitted)"}));
    }
    EXPECT_EQ(describe(map), "fit = auto (every other clef fitted to the actuator)");
}

TEST_F(DeviceClefsTest, AnExplicitMapWinsOverFitting) {
    const auto map = fitting(kLra, "lra-phone = erm-phone\n");
    const auto found = find_score_to_play(registry, "success", with_clef(), map);
    EXPECT_EQ(found.bundle.clefs.at("lra"), registry.clef("erm-phone"));
    EXPECT_EQ(bar_clefs(registry.score("success"), map).at(0), (BarClef{"lra-phone", "erm-phone"}));
    // Another clef of the same score is still fitted.
    const auto other = bar_clefs(registry.score("delete-folder"), map);
    EXPECT_EQ(other.at(0), (BarClef{"shaker-sine-high", "shaker-sine-high (fitted)"}));
    const auto star = fitting(kLra, "* = erm-phone\n");
    EXPECT_FALSE(star.fits("lra-phone"));
    EXPECT_EQ(find_score_to_play(registry, "success", with_clef(), star).bundle.clefs.at("lra"),
              registry.clef("erm-phone"));
}

TEST_F(DeviceClefsTest, AClefSentAlongIsFittedToo) {
    const auto mine = vibscore::testing::sine_clef(0.5, {60, 80, 100, 120, 140, 160},
                                                   {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9});
    auto score = vibscore::testing::read_file(shipped / "delete-folder.score.xml");
    const std::string high = "href=\"shaker-sine-high.clef.xml\"";
    score.replace(score.find(high), high.size(), "href=\"clefs/mine.clef.xml\"");
    PlayOptions options;
    options.clef_documents["clefs/mine.clef.xml"] = mine;
    const auto map = fitting(kErm);
    const auto found = find_score_to_play(registry, score, options, map);
    EXPECT_EQ(found.bundle.clef_of(found.bundle.score.bars[0]),
              render::fit_clef(read_clef(mine, "mine"), *map.fit_to).clef);
}

TEST(DeviceClefsConfig, FitTakesAutoOrOffAndNeedsADeclaredActuator) {
    EXPECT_FALSE(
        parse_config(std::string(kLra) + "[clefs]\nfit = off\n", "t.conf").device_clefs.fit_to);
    EXPECT_FALSE(parse_config(kLra, "t.conf").device_clefs.fit_to);
    try {
        parse_config(std::string(kLra) + "[clefs]\nfit = yes\n", "t.conf");
        FAIL() << "accepted";
    } catch (const ConfigError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "t.conf:8: [clefs] fit = \"yes\" is neither auto nor off");
    }
    try {
        parse_config("[clefs]\nfit = auto\n", "t.conf");
        FAIL() << "accepted";
    } catch (const ConfigError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "t.conf:2: [clefs] fit = auto needs an [actuator] section to fit to");
    }
    // The [actuator] section may come after [clefs].
    EXPECT_TRUE(
        parse_config("[clefs]\nfit = auto\n" + std::string(kErm), "t.conf").device_clefs.fit_to);
}

TEST_F(DeviceClefsTest, AReloadedActuatorRefitsTheClefs) {
    DaemonConfig running = parse_config(std::string(kLra) + "[clefs]\nfit = auto\n", "a.conf");
    const auto on_lra = find_score_to_play(registry, "success", with_clef(), running.device_clefs);
    const DaemonConfig fresh = parse_config(std::string(kErm) + "[clefs]\nfit = auto\n", "a.conf");
    EXPECT_NE(fresh.device_clefs, running.device_clefs);
    running = fresh;
    const auto on_erm = find_score_to_play(registry, "success", with_clef(), running.device_clefs);
    EXPECT_NE(on_lra.bundle.clefs.at("lra"), on_erm.bundle.clefs.at("lra"));
    EXPECT_EQ(on_erm.bundle.clefs.at("lra"),
              render::fit_clef(registry.clef("lra-phone"), *running.actuator).clef);
}

}  // namespace
}  // namespace vibscore::daemon
