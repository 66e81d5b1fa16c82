// The AHAP, Android and RTTTL readers and writers, and how imports become scores.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "client/formats/ahap.hpp"
#include "client/formats/android.hpp"
#include "client/formats/grid_fit.hpp"
#include "client/formats/rtttl.hpp"
#include "client/formats/score_builder.hpp"
#include "client/formats/sound_events.hpp"
#include "daemon/render/performance.hpp"
#include "score/clef_xml.hpp"
#include "score/limits.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::notes_in;

using formats::ChosenClef;
using formats::GridNote;
using ::testing::HasSubstr;
using ::testing::Not;

ChosenClef lra_phone() {
    const auto path =
        std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) / "lra-phone.clef.xml";
    return {"lra-phone", load_clef_file(path)};
}

template <typename F>
std::string first_error(F&& read) {
    const auto diagnostic = testing::first_diagnostic(read);
    return format(diagnostic);
}

// --- score builder ---------------------------------------------------------------------------

TEST(ScoreBuilder, SplitsTicksIntoTheFewestLengths) {
    using enum Length;
    EXPECT_EQ(formats::lengths_for(8), std::vector<Length>{quarter});
    EXPECT_EQ(formats::lengths_for(10), (std::vector<Length>{quarter, sixteenth}));
    EXPECT_EQ(formats::lengths_for(72), (std::vector<Length>{whole, whole, quarter}));
    EXPECT_EQ(formats::lengths_for(3), std::vector<Length>{sixteenth_dot});
}

TEST(ScoreBuilder, FillsBarsOfFourBeatsTiesLongNotesAndSplitsRestsAtBarLines) {
    const auto chosen = lra_phone();
    // A dotted half, a 9-beat note (tied: whole, whole, quarter), then rest to 20 beats.
    const std::vector<GridNote> notes{{0, 24, 2, 5}, {24, 72, 3, 7}};
    const auto imported = formats::build_score(notes, {{0, 0.2}}, 160, chosen, "t", "t");
    ASSERT_EQ(imported.clefs.size(), 1u);
    EXPECT_FALSE(imported.clefs[0].retimed);
    const auto& bars = imported.score.bars;
    ASSERT_EQ(bars.size(), 6u);
    // The whole note does not fit after the dotted half: that bar closes early.
    EXPECT_EQ(Score::beat_count(bars[0]), 3.0);
    EXPECT_EQ(Score::beat_count(bars[1]), 4.0);
    EXPECT_EQ(Score::beat_count(bars[2]), 4.0);
    const auto written = notes_in(imported.score);
    ASSERT_EQ(written.size(), 4u);
    EXPECT_EQ(written[1].legato, written[2].legato);
    EXPECT_EQ(written[2].legato, written[3].legato);
    EXPECT_NE(written[1].legato, 0);
    EXPECT_EQ(written[0].legato, 0);
    // 12 beats of notes, then 8 of rest: the last quarter's bar is filled up, one more bar.
    EXPECT_EQ(Score::beat_count(bars[3]), 4.0);
    EXPECT_EQ(Score::beat_count(bars[4]), 4.0);
}

TEST(ScoreBuilder, ATempoChangeStartsABarOnAClefOfThatTempo) {
    const auto chosen = lra_phone();
    const std::vector<GridNote> notes{{0, 8, 1, 1}, {8, 8, 1, 1}, {16, 8, 1, 1}};
    const auto imported = formats::build_score(notes, {{0, 0.2}, {16, 0.5}}, 24, chosen, "t", "t");
    ASSERT_EQ(imported.score.bars.size(), 2u);
    EXPECT_EQ(imported.score.bars[0].clef, "lra-phone");
    EXPECT_EQ(imported.score.bars[1].clef, "lra-phone-120bpm");
    ASSERT_EQ(imported.clefs.size(), 2u);
    EXPECT_TRUE(imported.clefs[1].retimed);
    EXPECT_EQ(imported.clefs[1].clef.tempo, 0.5);
}

// Each limit of a score at its edge: the last value allowed and the first refused, with the
// limit named in the message.
TEST(ScoreBuilder, TakesTenThousandBarsAndRefusesOneMoreNamingTheBarLimit) {
    const auto whole_notes = [](std::int64_t count, std::int64_t ticks) {
        std::vector<GridNote> notes;
        for (std::int64_t i = 0; i < count; ++i) {
            notes.push_back({i * ticks, ticks, 1, 1});
        }
        return notes;
    };
    const auto build = [](const std::vector<GridNote>& notes) {
        const auto end = notes.back().start + notes.back().length;
        return formats::build_score(notes, {{0, 0.001}}, end, lra_phone(), "", "big");
    };
    EXPECT_EQ(build(whole_notes(10'000, 32)).score.bars.size(), 10'000u);
    // Refused for its length before any of it is laid out...
    EXPECT_EQ(first_error([&] { build(whole_notes(10'001, 32)); }),
              "big: too long for a score: it lasts 40004 beats, more than fit in 10000 bars of "
              "four; a score holds at most 10000 bars");
    // ... or, when bars close early, for the bars it was laid out in.
    EXPECT_EQ(build(whole_notes(10'000, 24)).score.bars.size(), 10'000u);
    EXPECT_EQ(first_error([&] { build(whole_notes(10'001, 24)); }),
              "big: too long for a score: 10001 bars; a score holds at most 10000 bars");
}

TEST(ScoreBuilder, TakesAHundredThousandSymbolsAndRefusesOneMore) {
    // `notes` 32nds, one every `step` 32nds, and the piece `total` 32nds long.
    const auto build = [](std::int64_t notes, std::int64_t step, std::int64_t total) {
        std::vector<GridNote> grid;
        for (std::int64_t i = 0; i < notes; ++i) {
            grid.push_back({i * step, 1, 1, 1});
        }
        return formats::build_score(grid, {{0, 0.001}}, total, lra_phone(), "", "big");
    };
    const auto symbols = [](const formats::ImportedScore& imported) {
        std::size_t count = 0;
        for (const auto& bar : imported.score.bars) {
            count += bar.symbols.size();
        }
        return count;
    };
    // Touching 32nds, one symbol each: refused for their count before the layout.
    EXPECT_EQ(symbols(build(100'000, 1, 100'000)), 100'000u);
    EXPECT_EQ(first_error([&] { build(100'001, 1, 100'001); }),
              "big: too long for a score: 100001 notes; a score holds at most 100000 symbols");
    // Notes are counted in the one voice: a chord's notes are one.
    std::vector<GridNote> chords;
    for (std::int64_t i = 0; i < 100'000; ++i) {
        chords.push_back({i, 1, 1, 1});
        chords.push_back({i, 1, 2, 1});
    }
    EXPECT_EQ(symbols(formats::build_score(chords, {{0, 0.001}}, 100'000, lra_phone(), "", "c")),
              100'000u);
    // A 32nd rest after each 32nd note: the rests take the laid-out score past the limit.
    EXPECT_EQ(symbols(build(50'000, 2, 100'000)), 100'000u);
    EXPECT_EQ(first_error([&] { build(50'001, 2, 100'001); }),
              "big: too long for a score: 100001 symbols (notes, tied parts and rests); a score "
              "holds at most 100000 symbols");
}

TEST(ScoreBuilder, TakesAnHourAndRefusesA32ndMore) {
    const auto build = [](std::int64_t ticks) {
        return formats::build_score({{0, ticks, 1, 1}}, {{0, 0.5}}, ticks, lra_phone(), "", "long");
    };
    // At 0.5 s a quarter an hour is 7200 quarters: 57600 32nds.
    EXPECT_EQ(build(57'600).score.bars.size(), 1800u);
    EXPECT_EQ(first_error([&] { build(57'601); }),
              "long: too long for a score: it lasts 3600.062 s; a score lasts at most 3600 s");
}

TEST(ScoreBuilder, TakesThirtyTwoTemposAndRefusesTheThirtyThirdNamingTheClefLimit) {
    // A ritardando: a quarter note per bar, each bar slower.
    const auto ritardando = [](int bars) {
        std::vector<GridNote> notes;
        std::vector<formats::TempoChange> tempi;
        for (int i = 0; i < bars; ++i) {
            notes.push_back({i * 8, 8, 1, 1});
            tempi.push_back({i * 8, 0.5 + 0.01 * i});
        }
        return formats::build_score(notes, tempi, bars * 8, lra_phone(), "", "rit.mid");
    };
    EXPECT_EQ(ritardando(32).clefs.size(), 32u);
    EXPECT_EQ(first_error([&] { ritardando(33); }),
              "rit.mid: too many tempos for a score: 33, each on a clef of its own; a score "
              "declares at most 32 clefs");
}

TEST(GridFit, KeepsTheClefsTempoWhenTheTimesSitOnItsGrid) {
    // lra-phone: a quarter is 0.2 s. Two 8ths with the default silence, then one after a rest.
    std::vector<formats::SoundEvent> events(3);
    events[0] = {0.0, 0.075, 0, 0.5, 0.5, 0, 0};
    events[1] = {0.1, 0.1, 0, 0.5, 0.5, 0, 0};
    events[2] = {0.4, 0.2, 0, 1.0, 1.0, 0, 0};
    const auto placed = formats::place_on_grid(events, 0.0, lra_phone().clef,
                                               [](const formats::SoundEvent&) { return 2; });
    EXPECT_EQ(placed.tempo, 0.2);
    ASSERT_EQ(placed.notes.size(), 3u);
    EXPECT_EQ(placed.notes[0].length, 4);  // the 25 ms gap is the default silence, no rest
    EXPECT_EQ(placed.notes[0].tie_to_next, GridNote::Tie::none);
    EXPECT_EQ(placed.notes[1].length, 4);  // then a real rest of an 8th
    EXPECT_EQ(placed.notes[2].start, 16);
    EXPECT_EQ(placed.notes[2].number, 9);
}

TEST(GridFit, FindsATempoWhereTheClefsDoesNotFit) {
    std::vector<formats::SoundEvent> events;
    for (int i = 0; i < 4; ++i) {
        events.push_back({i * 0.33, 0.33, 0, 0.6, 0.6, 0, 0});  // touching: legato quarters
    }
    const auto placed = formats::place_on_grid(events, 0.0, lra_phone().clef,
                                               [](const formats::SoundEvent&) { return 1; });
    EXPECT_DOUBLE_EQ(placed.tempo, 0.33);
    ASSERT_EQ(placed.notes.size(), 4u);
    EXPECT_EQ(placed.notes[0].length, 8);
    EXPECT_EQ(placed.notes[0].tie_to_next, GridNote::Tie::legato);
    EXPECT_EQ(placed.notes[3].tie_to_next, GridNote::Tie::none);
}

TEST(GridFit, ReadsRampsAsHairpinsAndGlidesIntoTheNextNoteAsPortamento) {
    std::vector<formats::SoundEvent> events(3);
    events[0] = {0.0, 0.2, 0, 0.0, 0.8, 0.2, 0.2};  // rises from silence: crescendo to 8
    events[1] = {0.2, 0.2, 0, 0.8, 0.5, 0.2, 1.0};  // glides on, pitch and strength
    events[2] = {0.4, 0.2, 0, 0.5, 0.0, 1.0, 1.0};  // falls to silence: decrescendo from 5
    const auto placed = formats::place_on_grid(
        events, 0.0, lra_phone().clef,
        [](const formats::SoundEvent& e) { return formats::string_at(e.pitch_start, 6); });
    ASSERT_EQ(placed.notes.size(), 3u);
    EXPECT_EQ(placed.notes[0].dynamics, Dynamics::crescendo);
    EXPECT_EQ(placed.notes[0].number, 7);  // 0.8 of lra-phone's 1.0 is its number 7
    EXPECT_EQ(placed.notes[0].tie_to_next, GridNote::Tie::legato);
    EXPECT_EQ(placed.notes[1].dynamics, Dynamics::none);
    EXPECT_EQ(placed.notes[1].tie_to_next, GridNote::Tie::portamento);
    EXPECT_EQ(placed.notes[1].string, 2);
    EXPECT_EQ(placed.notes[2].dynamics, Dynamics::decrescendo);
    EXPECT_EQ(placed.notes[2].number, 4);
    EXPECT_EQ(placed.notes[2].string, 6);
}

TEST(PitchToString, KeepsTheContourOfUpToSixPitchesAndBandsMore) {
    EXPECT_EQ(formats::strings_by_contour({67, 60, 62, 64, 65, 55}, 6),
              (std::vector<int>{6, 2, 3, 4, 5, 1}));
    EXPECT_EQ(formats::strings_by_contour({60, 72, 60}, 6), (std::vector<int>{1, 6, 1}));
    const auto banded = formats::strings_by_contour({48, 50, 52, 53, 55, 57, 59, 60, 72}, 6);
    EXPECT_EQ(banded.front(), 1);
    EXPECT_EQ(banded.back(), 6);
    EXPECT_TRUE(std::is_sorted(banded.begin(), banded.end()));
}

// --- AHAP ------------------------------------------------------------------------------------

TEST(Ahap, ExportsOfEveryShippedScorePassTheSchemaFromApplesDocumentation) {
    testing::TempDir dir;
    std::vector<std::string> argv{
        "/usr/bin/python3", testing::required_env("VIBSCORE_TEST_DATA") + "/check_json_schema.py",
        testing::required_env("VIBSCORE_TEST_DATA") + "/ahap.schema.json"};
    for (const auto& entry :
         std::filesystem::directory_iterator(testing::required_env("VIBSCORE_CLEFS"))) {
        const auto name = entry.path().filename().string();
        if (name.ends_with(".score.xml")) {
            const auto ahap =
                formats::write_ahap(formats::sound_track(load_score_file(entry.path())));
            argv.push_back(dir.write(name + ".ahap", ahap).string());
        }
    }
    ASSERT_GT(argv.size(), 20u);
    const auto result = testing::run_command(argv);
    EXPECT_EQ(result.exit_code, 0) << result.out << result.err;
    // The check itself fails on what Apple forbids.
    const auto bad = dir.write("bad.ahap", R"({"Pattern": [{"Event": {"Time": 0,
        "EventType": "HapticContinuous", "EventDuration": 31}}]})");
    const auto refused = testing::run_command({argv[0], argv[1], argv[2], bad.string()});
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_THAT(refused.out, HasSubstr("31 is greater than the maximum of 30"));
}

TEST(Ahap, AHairpinIsAnIntensityCurveThatEndsBackAtNeutral) {
    formats::SoundTrack track;
    track.events.push_back({0.0, 0.4, 1.0, 0.0, 1.0, 0.4, 0.4, 0, 0});  // crescendo
    track.events.push_back({0.5, 0.2, 0.5, 0.5, 0.5, 0.4, 0.4, 0, 0});
    const auto json = nlohmann::json::parse(formats::write_ahap(track));
    const auto& pattern = json.at("Pattern");
    ASSERT_EQ(pattern.size(), 3u);
    EXPECT_EQ(pattern[0].at("Event").at("EventParameters")[0].at("ParameterValue"), 1.0);
    const auto& curve = pattern[1].at("ParameterCurve");
    EXPECT_EQ(curve.at("ParameterID"), "HapticIntensityControl");
    const auto& points = curve.at("ParameterCurveControlPoints");
    ASSERT_EQ(points.size(), 3u);
    EXPECT_EQ(points[0].at("ParameterValue"), 0.0);
    EXPECT_EQ(points[1].at("Time"), 0.4);
    EXPECT_EQ(points[1].at("ParameterValue"), 1.0);
    EXPECT_EQ(points[2].at("Time"), 0.5);  // neutral again at the next onset
    EXPECT_EQ(points[2].at("ParameterValue"), 1.0);
}

TEST(Ahap, ReadsTransientsContinuousEventsAndCurvesOfAnAppleStylePattern) {
    const std::string text = R"({
  "Version": 1.0,
  "Metadata": {"Project": "Boing", "Created": "2019"},
  "Pattern": [
    {"Event": {"Time": 0.0, "EventType": "HapticTransient",
               "EventParameters": [{"ParameterID": "HapticIntensity", "ParameterValue": 0.8},
                                   {"ParameterID": "HapticSharpness", "ParameterValue": 0.4}]}},
    {"Event": {"Time": 0.2, "EventType": "HapticContinuous", "EventDuration": 0.4,
               "EventParameters": [{"ParameterID": "HapticIntensity", "ParameterValue": 1.0},
                                   {"ParameterID": "HapticSharpness", "ParameterValue": 1.0}]}},
    {"ParameterCurve": {"ParameterID": "HapticIntensityControl", "Time": 0.2,
                        "ParameterCurveControlPoints": [{"Time": 0, "ParameterValue": 1.0},
                                                        {"Time": 0.4, "ParameterValue": 0.0}]}},
    {"Event": {"Time": 0.0, "EventType": "AudioCustom", "EventWaveformPath": "boing.wav"}}
  ]
})";
    const auto imported = formats::read_ahap(text, "boing.ahap", lra_phone());
    EXPECT_EQ(imported.score.title, "Boing");
    const auto notes = notes_in(imported.score);
    ASSERT_EQ(notes.size(), 2u);                        // the audio event has no place in a score
    EXPECT_EQ(notes[0].string, 3);                      // sharpness 0.4 is staff position 2 of 0..5
    EXPECT_EQ(notes[0].length, Length::thirty_second);  // a tap
    EXPECT_EQ(notes[1].string, 6);
    EXPECT_EQ(notes[1].number, 9);
    EXPECT_EQ(notes[1].dynamics, Dynamics::decrescendo);
    EXPECT_EQ(notes[1].length, Length::half);
}

TEST(Ahap, NamesTheLineAndColumnOfWhatIsWrong) {
    const auto read = [](const std::string& text) {
        return first_error([&] { formats::read_ahap(text, "p.ahap", lra_phone()); });
    };
    EXPECT_EQ(read("{\n  \"Pattern\": [\n    {\"Event\": {\"Time\": 0,,}}\n  ]\n}"),
              "p.ahap:3:26: not JSON: syntax error while parsing object key - unexpected ','; "
              "expected string literal");
    EXPECT_EQ(read("{\"Pattern\": [],\n \"Tempo\": 3}"),
              "p.ahap:2:2: unknown key \"Tempo\" in the AHAP file (expected Version, Metadata, "
              "Pattern)");
    EXPECT_EQ(read("{\"Pattern\": [\n {\"Event\": {\"Time\": 0, \"EventType\": \"HapticTransient\","
                   "\n  \"EventParameters\": [{\"ParameterID\": \"HapticIntensity\", "
                   "\"ParameterValue\": \"loud\"}]}}]}"),
              "p.ahap:3:76: HapticIntensity must be a number, not a string");
    EXPECT_EQ(
        read("{\"Pattern\": [{\"Event\": {\"Time\": 0, \"EventType\": \"HapticContinuous\"}}]}"),
        "p.ahap:1:24: a HapticContinuous event needs an EventDuration");
    EXPECT_EQ(read("{\"Pattern\": [{\"Event\": {\"Time\": 0, \"EventType\": \"HapticContinuous\", "
                   "\"EventDuration\": 40}}]}"),
              "p.ahap:1:86: EventDuration 40 is out of range (0 to 30)");
    EXPECT_EQ(read("[1, 2]"), "p.ahap:1:1: an AHAP file must be an object, not an array");
    EXPECT_EQ(read("{\"Pattern\": [], \"Pattern\": []}"),
              "p.ahap:1:17: key \"Pattern\" appears twice in one object");
    EXPECT_EQ(read("{\"Pattern\": []}"), "p.ahap: holds no notes or rests to make a score of");
}

// Issue 27: 8 of Apple's 21 sample AHAP files (from its Unity plug-in) were refused, 7 for a
// trailing comma and 1 for HapticSharpness -1. Apple's parser takes both: commas before a
// closing bracket or brace, and parameters out of range, clamped. Read them so, and say so.
TEST(Ahap, ReadsApplesSampleShapesTrailingCommasAndParametersOutOfRangeClampedWithWarnings) {
    const std::string sample = R"({
    "Version": 1.0,
    "Metadata": {
        "Project" : "Basis",
        "Created" : "1 June 2020",
    },
    "Pattern":
    [
        {
            "Event":
            {
                "Time": 0.0,
                "EventType": "HapticTransient",
                "EventParameters":
                [
                    { "ParameterID": "HapticIntensity", "ParameterValue": 1.0 },
                    { "ParameterID": "HapticSharpness", "ParameterValue": -1 },
                ]
            }
        },
        {
            "ParameterCurve":
            {
                "ParameterID": "HapticIntensityControl",
                "Time": 0.2,
                "ParameterCurveControlPoints": [
                    { "Time": 0, "ParameterValue": 1.5 },
                ]
            }
        },
    ]
})";
    const auto imported = formats::read_ahap(sample, "Basis.ahap", lra_phone());
    EXPECT_EQ(imported.score.title, "Basis");
    const auto notes = notes_in(imported.score);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0].string, 1);  // sharpness -1 read as 0: string 1
    EXPECT_EQ(notes[0].number, 9);
    std::vector<std::string> warnings;
    for (const auto& warning : imported.warnings) {
        warnings.push_back(format(warning));
    }
    const std::string comma =
        ": a trailing comma, which JSON does not allow; Apple's parser (and Apple's own sample "
        "files) take it, and so does vibscore";
    EXPECT_EQ(warnings,
              (std::vector<std::string>{
                  "Basis.ahap:5:34" + comma, "Basis.ahap:17:79" + comma, "Basis.ahap:27:57" + comma,
                  "Basis.ahap:30:10" + comma,
                  "Basis.ahap:17:75: HapticSharpness -1 is out of range (0 to 1): read as 0, as "
                  "Core Haptics clamps it",
                  "Basis.ahap:27:52: HapticIntensityControl value 1.5 is out of range (0 to 1): "
                  "read as 1, as Core Haptics clamps it"}));
    // At the edges of the range a value is read as it is, with no warning.
    const auto edges = formats::read_ahap(
        R"({"Pattern": [{"Event": {"Time": 0, "EventType": "HapticTransient", "EventParameters": [
        {"ParameterID": "HapticIntensity", "ParameterValue": 0},
        {"ParameterID": "HapticSharpness", "ParameterValue": 1}]}}]})",
        "e.ahap", lra_phone());
    EXPECT_TRUE(edges.warnings.empty());
    EXPECT_EQ(notes_in(edges.score).at(0).string, 6);
}

TEST(Ahap, SaysFiftyWarningsAndCountsTheRest) {
    const auto loud = [](int events) {
        std::string text = R"({"Pattern": [)";
        for (int i = 0; i < events; ++i) {
            text += std::string(i ? "," : "") + R"({"Event": {"Time": )" + std::to_string(i) +
                    R"(, "EventType": "HapticTransient", "EventParameters": [)" +
                    R"({"ParameterID": "HapticIntensity", "ParameterValue": 2}]}})";
        }
        return formats::read_ahap(text + "]}", "l.ahap", lra_phone()).warnings;
    };
    EXPECT_EQ(loud(50).size(), 50u);
    const auto more = loud(52);
    ASSERT_EQ(more.size(), 51u);
    EXPECT_EQ(format(more.back()), "l.ahap: 2 more like these");
}

// The length of an imported score in seconds, as its clefs play it.
double seconds_of(const formats::ImportedScore& imported) {
    double seconds = 0.0;
    for (const auto& bar : imported.score.bars) {
        for (const auto& clef : imported.clefs) {
            if (clef.id == bar.clef) {
                seconds += Score::beat_count(bar) * clef.clef.tempo;
            }
        }
    }
    return seconds;
}

// Issue 25: a looping ringtone exported to AHAP lost its closing rest (3.2 s became 2.8 s).
// Core Haptics counts a pattern's length to its last event's end or its last parameter's start,
// so a neutral intensity curve where the piece ends keeps the period.
TEST(Ahap, APatternEndsWithANeutralCurveWhereThePieceEndsSoALoopKeepsItsPeriod) {
    formats::SoundTrack track;
    track.duration = 3.2;
    track.tempo = 0.2;
    track.events.push_back({0.0, 0.4, 1.0, 1.0, 1.0, 0.2, 0.2, 0, 0});
    track.events.push_back({2.4, 0.4, 1.0, 1.0, 1.0, 0.2, 0.2, 0, 0});
    const auto text = formats::write_ahap(track);
    const auto json = nlohmann::json::parse(text);
    EXPECT_EQ(json.at("Metadata").at("Tempo"), 0.2);
    const auto& last = json.at("Pattern").back().at("ParameterCurve");
    EXPECT_EQ(last.at("ParameterID"), "HapticIntensityControl");
    EXPECT_EQ(last.at("Time"), 3.2);
    EXPECT_EQ(last.at("ParameterCurveControlPoints"),
              nlohmann::json::parse(R"([{"Time": 0.0, "ParameterValue": 1.0}])"));
    EXPECT_DOUBLE_EQ(seconds_of(formats::read_ahap(text, "r.ahap", lra_phone())), 3.2);
    // A piece that ends with its last note needs no such curve.
    track.duration = 2.8;
    EXPECT_TRUE(
        nlohmann::json::parse(formats::write_ahap(track)).at("Pattern").back().contains("Event"));
}

TEST(Ahap, APatternLastsToItsLastEventsEndOrItsLastParametersStartWhicheverIsLater) {
    const auto pattern = [](const std::string& parameter_time) {
        return R"({"Pattern": [
  {"Event": {"Time": 0, "EventType": "HapticContinuous", "EventDuration": 0.4}},
  {"Parameter": {"ParameterID": "HapticIntensityControl", "Time": )" +
               parameter_time + R"(, "ParameterValue": 1.0}}]})";
    };
    EXPECT_DOUBLE_EQ(seconds_of(formats::read_ahap(pattern("1.6"), "p.ahap", lra_phone())), 1.6);
    EXPECT_DOUBLE_EQ(seconds_of(formats::read_ahap(pattern("0.2"), "p.ahap", lra_phone())), 0.4);
}

TEST(Ahap, AnEventEndingOnTheHourIsReadAndOneEndingLaterIsRefusedWhereItIs) {
    const auto pattern = [](const std::string& time) {
        return "{\"Pattern\": [\n {\"Event\": {\"Time\": " + time +
               ", \"EventType\": \"HapticContinuous\", \"EventDuration\": 30}}]}";
    };
    EXPECT_EQ(notes_in(formats::read_ahap(pattern("3570"), "p.ahap", lra_phone()).score).size(),
              38u);  // 30 s as tied whole notes of 0.8 s: 37 and a half
    EXPECT_EQ(first_error([&] { formats::read_ahap(pattern("3570.5"), "p.ahap", lra_phone()); }),
              "p.ahap:2:12: too long for a score: the event ends at 3600.5 s; a score lasts at "
              "most 3600 s");
}

TEST(Formats, EveryReaderRefusesATextLargerThanAScoreDocument) {
    // At the limit the text is read (and found wanting for what it holds); a byte more and it
    // is refused for its size.
    const std::string at_limit(limits::document_bytes, ' ');
    const std::string over(limits::document_bytes + 1, ' ');
    const auto readers = std::vector<std::function<void(const std::string&)>>{
        [](const std::string& t) { formats::read_ahap(t, "f", lra_phone()); },
        [](const std::string& t) { formats::read_android_json(t, "f", lra_phone()); },
        [](const std::string& t) { formats::read_android_xml(t, "f", lra_phone()); },
        [](const std::string& t) { formats::read_rtttl(t, "f", lra_phone()); },
    };
    for (const auto& read : readers) {
        EXPECT_THAT(first_error([&] { read(at_limit); }), Not(HasSubstr("larger than")));
        EXPECT_EQ(first_error([&] { read(over); }),
                  "f: larger than the 1048576-byte limit for a document");
    }
}

// --- Android ---------------------------------------------------------------------------------

// Each note's onset and length in seconds, as the score's clefs play it; the tied parts of a
// note too long for one symbol (which touch) as one.
std::vector<std::pair<double, double>> played_notes(const formats::ImportedScore& imported) {
    ParsedScore parsed{imported.score, {}};
    parsed.where.clefs.resize(imported.score.clefs.size());
    for (const auto& bar : imported.score.bars) {
        parsed.where.bars.emplace_back();
        parsed.where.symbols.emplace_back(bar.symbols.size());
    }
    const auto bundle = bind_clefs(
        std::move(parsed), "imported", [&](const ClefDeclaration& declaration, const auto&) {
            for (const auto& clef : imported.clefs) {
                if (clef.id == declaration.id) {
                    return clef.clef;
                }
            }
            throw DocumentError({"imported"}, "no clef " + declaration.id);
        });
    std::vector<std::pair<double, double>> notes;
    const render::Performance performance(bundle);
    for (const auto& timing : performance.timeline()) {
        if (!timing.is_note) {
            continue;
        }
        if (!notes.empty() &&
            std::abs(notes.back().first + notes.back().second - timing.onset) < 1e-9) {
            notes.back().second += timing.length;
        } else {
            notes.emplace_back(timing.onset, timing.length);
        }
    }
    return notes;
}

// Issue 27: Android waveforms' 10-12 ms steps came back as 25-33 ms notes. Lengths are kept to
// the millisecond: on the coarsest grid that holds them, here 1 ms.
TEST(Android, StepsOfTenToTwelveMillisecondsKeepTheirLengths) {
    const auto imported = formats::read_android_json(
        R"({"timings": [0, 12, 188, 10, 190, 11, 189, 10, 190]})", "v.json", lra_phone());
    const auto notes = played_notes(imported);
    constexpr double kOnsets[] = {0.0, 0.2, 0.4, 0.6};
    constexpr double kLengths[] = {0.012, 0.010, 0.011, 0.010};
    ASSERT_EQ(notes.size(), 4u);
    for (std::size_t i = 0; i < notes.size(); ++i) {
        EXPECT_NEAR(notes[i].first, kOnsets[i], 1e-9) << "note " << i + 1;
        EXPECT_NEAR(notes[i].second, kLengths[i], 1e-9) << "note " << i + 1;
    }
    EXPECT_NEAR(seconds_of(imported), 0.8, 1e-9);
    // 10 ms steps alone sit on a 10 ms grid: a 32nd note at 80 ms a quarter.
    const auto tens =
        formats::read_android_json(R"({"timings": [0, 10, 190, 10, 190]})", "v.json", lra_phone());
    EXPECT_DOUBLE_EQ(tens.clefs.at(0).clef.tempo, 0.08);
    const auto ten_notes = notes_in(tens.score);
    ASSERT_EQ(ten_notes.size(), 2u);
    EXPECT_EQ(ten_notes[0].length, Length::thirty_second);
}

TEST(Android, AWaveformOfAnHourIsReadAndAMillisecondMoreIsRefusedAtItsStep) {
    EXPECT_FALSE(
        notes_in(
            formats::read_android_json(R"({"timings": [0, 3600000]})", "v.json", lra_phone()).score)
            .empty());
    EXPECT_EQ(first_error([&] {
                  formats::read_android_json(R"({"timings": [0, 3600000, 1]})", "v.json",
                                             lra_phone());
              }),
              "v.json:1:26: too long for a score: the pattern reaches 3600001 ms at this step; a "
              "score lasts at most 3600000 ms (3600 s)");
    const auto entries = [](const std::string& last) {
        return "<vibration-effect><waveform-effect>\n"
               "<waveform-entry durationMs=\"3600000\" amplitude=\"255\"/>\n" +
               last + "</waveform-effect></vibration-effect>";
    };
    EXPECT_FALSE(
        notes_in(formats::read_android_xml(entries(""), "v.xml", lra_phone()).score).empty());
    EXPECT_EQ(first_error([&] {
                  formats::read_android_xml(
                      entries("<waveform-entry durationMs=\"1\" amplitude=\"0\"/>"), "v.xml",
                      lra_phone());
              }),
              "v.xml:3:1: too long for a score: the pattern reaches 3600001 ms at this step; a "
              "score lasts at most 3600000 ms (3600 s)");
}

TEST(Android, AHundredThousandStepsAreReadAndOneMoreIsRefusedAtItsStep) {
    const auto steps = [](int count) {
        std::string text = "{\"timings\": [";
        for (int i = 0; i < count; ++i) {
            text += i == 0 ? "25" : ",25";
        }
        return text + "]}";
    };
    EXPECT_EQ(
        notes_in(formats::read_android_json(steps(100'000), "v.json", lra_phone()).score).size(),
        50'000u);
    EXPECT_EQ(
        first_error([&] { formats::read_android_json(steps(100'001), "v.json", lra_phone()); }),
        "v.json:1:300014: too long for a score: more than 100000 steps; a score holds at "
        "most 100000 symbols");
}

TEST(Android, TheWaveformStepsAddUpToThePieceAtEachNotesOwnStrength) {
    formats::SoundTrack track;
    track.duration = 1.0;
    track.events.push_back({0.1, 0.2, 1.0, 0.0, 1.0, 0, 0, 0, 0});  // a crescendo: flat at 255
    track.events.push_back({0.3, 0.1, 0.5, 0.5, 0.5, 0, 0, 0, 0});  // tied on
    const auto json = nlohmann::json::parse(formats::write_android_json(track, {}));
    EXPECT_EQ(json.at("timings"), (std::vector<int>{100, 200, 100, 600}));
    EXPECT_EQ(json.at("amplitudes"), (std::vector<int>{0, 255, 128, 0}));
    EXPECT_EQ(json.at("repeat"), -1);
    const auto looped = nlohmann::json::parse(formats::write_android_json(track, {true}));
    EXPECT_EQ(looped.at("repeat"), 0);
    const auto xml = formats::write_android_xml(track, {true});
    EXPECT_THAT(xml, HasSubstr("<vibration-effect>\n  <waveform-effect>\n    <repeating>\n"
                               "      <waveform-entry durationMs=\"100\" amplitude=\"0\" />"));
}

TEST(Android, ReadsTimingsAloneAsOffOnAndTheDefaultAmplitudeAsFull) {
    const auto off_on =
        formats::read_android_json(R"({"timings": [0, 200, 200, 400]})", "v.json", lra_phone());
    auto notes = notes_in(off_on.score);
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_EQ(notes[0].length, Length::quarter);
    EXPECT_EQ(notes[1].length, Length::half);
    EXPECT_EQ(notes[1].number, 9);
    const auto defaults = formats::read_android_json(
        R"({"timings": [100, 100], "amplitudes": [-1, 0], "repeat": 0})", "v.json", lra_phone());
    notes = notes_in(defaults.score);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0].number, 9);
    EXPECT_EQ(notes[0].string, 1);  // a waveform has no pitch
}

TEST(Android, ReadsAnEnvelopesRampsAsHairpinsAndItsFrequenciesAsStrings) {
    const std::string text = R"(<vibration-effect>
  <waveform-envelope-effect initialFrequencyHz="155">
    <control-point amplitude="1.0" frequencyHz="155" durationMs="200"/>
    <control-point amplitude="1.0" frequencyHz="235" durationMs="200"/>
    <control-point amplitude="0.0" frequencyHz="235" durationMs="400"/>
  </waveform-envelope-effect>
</vibration-effect>)";
    const auto imported = formats::read_android_xml(text, "e.xml", lra_phone());
    const auto notes = notes_in(imported.score);
    ASSERT_EQ(notes.size(), 3u);
    EXPECT_EQ(notes[0].dynamics, Dynamics::crescendo);
    EXPECT_EQ(notes[0].string, 1);
    EXPECT_NE(notes[1].portamento, 0);  // the frequency glides 155 -> 235 Hz
    EXPECT_EQ(notes[1].portamento, notes[2].portamento);
    EXPECT_EQ(notes[2].string, 6);
    EXPECT_EQ(notes[2].dynamics, Dynamics::decrescendo);
    EXPECT_EQ(notes[2].length, Length::half);
}

TEST(Android, AnEnvelopesReleaseAtThePiecesEndIsTheLastNotesEndNotARest) {
    // At 140 bpm a quarter is 428.57 ms: the piece's end falls between two milliseconds.
    const double quarter = 60.0 / 140.0;
    formats::SoundTrack track;
    track.duration = 3 * quarter;  // 1285.71 ms: written as 1286, and a release after it
    track.events.push_back({0.0, quarter - 0.03, 1.0, 1.0, 1.0, 0.0, 0.0, 155, 155});
    track.events.push_back({quarter, 2 * quarter, 1.0, 1.0, 1.0, 0.0, 0.0, 155, 155});
    const auto xml = formats::write_android_envelope(track, {});
    auto chosen = lra_phone();
    chosen.clef.tempo = quarter;
    const auto imported = formats::read_android_xml(xml, "e.xml", chosen);
    EXPECT_FALSE(imported.clefs[0].retimed);
    const auto notes = notes_in(imported.score);
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_EQ(notes[1].length, Length::half);
    ASSERT_EQ(imported.score.bars.size(), 1u);
    EXPECT_EQ(imported.score.bars[0].symbols.size(), 2u);  // no rest after the last note
}

TEST(Android, TheEnvelopeFormNeedsSineClefs) {
    formats::SoundTrack track;
    track.events.push_back({0.0, 0.2, 1.0, 1.0, 1.0, 0, 0, 0, 0});  // a curve clef's note
    EXPECT_THROW(formats::write_android_envelope(track, {}), std::invalid_argument);
}

TEST(Android, NamesTheLineAndColumnOfWhatIsWrong) {
    const auto json = [](const std::string& text) {
        return first_error([&] { formats::read_android_json(text, "v.json", lra_phone()); });
    };
    EXPECT_EQ(json("{\"timings\": [100, -5]}"),
              "v.json:1:19: a timing -5 is out of range (0 to 3600000)");
    EXPECT_EQ(json("{\"timings\": [100],\n \"amplitudes\": [1, 2]}"),
              "v.json:2:16: amplitudes has 2 values for 1 timings");
    EXPECT_EQ(json("{\"timings\": [1.5]}"),
              "v.json:1:14: a timing must be a whole number, not 1.5");
    EXPECT_EQ(json("{\"timings\": [100], \"amplitudes\": [300]}"),
              "v.json:1:35: an amplitude 300 is out of range (-1 to 255)");
    EXPECT_EQ(json("{\"timings\": [100] \"repeat\": 0}"),
              "v.json:1:19: not JSON: syntax error while parsing object - unexpected string "
              "literal; expected '}'");
    const auto xml = [](const std::string& text) {
        return first_error([&] { formats::read_android_xml(text, "v.xml", lra_phone()); });
    };
    EXPECT_EQ(xml("<vibration-effect>\n  <predefined-effect name=\"click\"/>\n</vibration-effect>"),
              "v.xml:2:3: <predefined-effect> is a device's own effect with no timing to turn "
              "into notes; vibscore reads waveforms and envelopes");
    EXPECT_EQ(xml("<vibration-effect><waveform-effect>\n<waveform-entry durationMs=\"10\" "
                  "amplitude=\"loud\"/></waveform-effect></vibration-effect>"),
              "v.xml:2:1: amplitude \"loud\" is not a whole number");
    EXPECT_EQ(xml("<vibration-effect><waveform-envelope-effect>\n"
                  "<control-point amplitude=\"0.5\" frequencyHz=\"100\" durationMs=\"0\"/>"
                  "</waveform-envelope-effect></vibration-effect>"),
              "v.xml:2:1: durationMs \"0\" is out of range (1 to 3600000)");
}

// --- RTTTL -----------------------------------------------------------------------------------

TEST(Rtttl, ReadsLengthsDotsPausesOctavesAndTheTempo) {
    const auto imported =
        formats::read_rtttl("Test:d=4,o=5,b=120:8c,8d,4e.,p,2c6,16g#4", "t.rtttl", lra_phone());
    EXPECT_EQ(imported.score.title, "Test");
    ASSERT_EQ(imported.clefs.size(), 1u);
    EXPECT_EQ(imported.clefs[0].id, "lra-phone-120bpm");
    EXPECT_EQ(imported.clefs[0].clef.tempo, 0.5);
    const auto notes = notes_in(imported.score);
    ASSERT_EQ(notes.size(), 5u);
    EXPECT_EQ(notes[0].length, Length::eighth);
    EXPECT_EQ(notes[2].length, Length::quarter_dot);
    EXPECT_EQ(notes[3].length, Length::half);
    EXPECT_EQ(notes[4].length, Length::sixteenth);
    // Five distinct pitches, G#4 < C5 < D5 < E5 < C6, spread over the six strings.
    EXPECT_EQ(notes[4].string, 1);
    EXPECT_EQ(notes[0].string, 2);
    EXPECT_EQ(notes[3].string, 6);
    EXPECT_EQ(notes[0].number, 9);  // RTTTL has no volume: the clef's strongest number
    const auto& first_bar = imported.score.bars[0].symbols;
    ASSERT_GE(first_bar.size(), 4u);
    EXPECT_TRUE(std::holds_alternative<Rest>(first_bar[3]));  // the pause
}

TEST(Rtttl, KeepsTheClefWhenTheBpmMatchesItsTempo) {
    const auto imported = formats::read_rtttl("x:b=300:c,d", "x.rtttl", lra_phone());
    ASSERT_EQ(imported.clefs.size(), 1u);
    EXPECT_EQ(imported.clefs[0].id, "lra-phone");
    EXPECT_FALSE(imported.clefs[0].retimed);
}

// What real collections hold besides plain RTTTL (issue 27): RTX's s= (style) and l= (loops),
// control pairs with no "=" ("B715", "SS"), "_" for a flat, and the dot on either side of the
// octave.
TEST(Rtttl, ReadsFlatsAndTheDotOnEitherSideOfTheOctave) {
    const auto imported =
        formats::read_rtttl("t:d=4,o=5,b=120:a_5,a,8a#5,8a_.5,8a_5.", "t.rtttl", lra_phone());
    const auto notes = notes_in(imported.score);
    ASSERT_EQ(notes.size(), 5u);
    // A flat 5 < A5 < A sharp 5: three pitches spread over the staff.
    EXPECT_EQ(notes[0].string, 1);
    EXPECT_EQ(notes[1].string, 4);
    EXPECT_EQ(notes[2].string, 6);
    EXPECT_EQ(notes[3].string, 1);
    EXPECT_EQ(notes[3].length, Length::eighth_dot);
    EXPECT_EQ(notes[4].length, Length::eighth_dot);
    EXPECT_EQ(first_error([&] { formats::read_rtttl("t:d=4:p_", "r.rtttl", lra_phone()); }),
              "r.rtttl:1:7: note \"p_\": a pause cannot be flat");
}

TEST(Rtttl, ReadsRtxStylesAsTiesOrStaccatoAndAcceptsLoopsUpToFifteen) {
    // Continuous: notes that touch are tied by legato; a pause ends the tie.
    const auto continuous =
        formats::read_rtttl("t:d=8,o=5,b=120,s=C:c,d,p,e", "t.rtttl", lra_phone());
    auto notes = notes_in(continuous.score);
    ASSERT_EQ(notes.size(), 3u);
    EXPECT_NE(notes[0].legato, 0);
    EXPECT_EQ(notes[0].legato, notes[1].legato);
    EXPECT_EQ(notes[2].legato, 0);
    // Staccato from "SS" on, among the notes: each note half its length, a rest the other half;
    // a 32nd, the grid's finest, stays one.
    const auto staccato = formats::read_rtttl("t:d=4,o=5,b=120:c,SS,d,32e", "t.rtttl", lra_phone());
    const auto& symbols = staccato.score.bars.at(0).symbols;
    ASSERT_EQ(symbols.size(), 4u);
    EXPECT_EQ(std::get<Note>(symbols[0]).length, Length::quarter);
    EXPECT_EQ(std::get<Note>(symbols[1]).length, Length::eighth);
    EXPECT_EQ(std::get<Rest>(symbols[2]).length, Length::eighth);
    EXPECT_EQ(std::get<Note>(symbols[3]).length, Length::thirty_second);
    // A loop count is how the tune is played, not part of it: one pass is the score.
    EXPECT_EQ(notes_in(formats::read_rtttl("t:l=15:c", "t.rtttl", lra_phone()).score).size(), 1u);
    EXPECT_EQ(first_error([&] { formats::read_rtttl("t:l=16:c", "r.rtttl", lra_phone()); }),
              "r.rtttl:1:3: \"l=16\" is out of range (d: 1, 2, 4, 8, 16, 32; o: 0 to 9; b: 1 to "
              "900; l: 0 to 15)");
    EXPECT_EQ(first_error([&] { formats::read_rtttl("t:s=X:c", "r.rtttl", lra_phone()); }),
              "r.rtttl:1:3: \"s=X\": the style is N (natural), C (continuous) or S (staccato)");
}

TEST(Rtttl, ReadsControlPairsWithoutEqualsAndTempoChangesAmongTheNotes) {
    // "B715": RTX's "=" is optional. An unknown control name is ignored, as RTX asks.
    const auto alert = formats::read_rtttl("Alert:B715,x=3:32C,32P", "a.rtttl", lra_phone());
    ASSERT_EQ(alert.clefs.size(), 1u);
    EXPECT_DOUBLE_EQ(alert.clefs[0].clef.tempo, 60.0 / 715);
    // b= among the notes: the bar from there on is on a clef of that tempo.
    const auto slower = formats::read_rtttl("t:d=4,o=5,b=120:c,b=60,d", "t.rtttl", lra_phone());
    ASSERT_EQ(slower.score.bars.size(), 2u);
    EXPECT_EQ(slower.score.bars[0].clef, "lra-phone-120bpm");
    EXPECT_EQ(slower.score.bars[1].clef, "lra-phone-60bpm");
    EXPECT_EQ(first_error([&] { formats::read_rtttl("t:d=4:c,d=8,e", "r.rtttl", lra_phone()); }),
              "r.rtttl:1:9: \"d=8\": among the notes only o=, b= and s= may change");
}

TEST(Rtttl, ATuneOfAnHourIsReadAndANoteMoreIsRefusedWhereItIs) {
    // At 1 bpm a whole note lasts 240 s: fifteen of them are an hour.
    const auto wholes = [](int count, int bpm) {
        std::string text = "t:d=1,o=5,b=" + std::to_string(bpm) + ":c";
        for (int i = 1; i < count; ++i) {
            text += ",c";
        }
        return text;
    };
    EXPECT_EQ(notes_in(formats::read_rtttl(wholes(15, 1), "r.rtttl", lra_phone()).score).size(),
              15u);
    EXPECT_EQ(first_error([&] { formats::read_rtttl(wholes(16, 1), "r.rtttl", lra_phone()); }),
              "r.rtttl:1:45: too long for a score: the tune passes 3600 s here; a score lasts at "
              "most 3600 s");
    // At 900 bpm ten thousand bars of whole notes take 2667 s: the bars bind first.
    EXPECT_EQ(
        notes_in(formats::read_rtttl(wholes(10'000, 900), "r.rtttl", lra_phone()).score).size(),
        10'000u);
    EXPECT_EQ(
        first_error([&] { formats::read_rtttl(wholes(10'001, 900), "r.rtttl", lra_phone()); }),
        "r.rtttl:1:20017: too long for a score: the tune passes 40000 beats here; a score holds "
        "at most 10000 bars of four beats");
}

TEST(Rtttl, AHundredThousandNotesAreReadAndOneMoreIsRefusedWhereItIs) {
    const auto notes = [](int count) {
        std::string text = "t:d=32,o=5,b=900:c";
        for (int i = 1; i < count; ++i) {
            text += ",c";
        }
        return text;
    };
    EXPECT_EQ(notes_in(formats::read_rtttl(notes(100'000), "r.rtttl", lra_phone()).score).size(),
              100'000u);
    EXPECT_EQ(first_error([&] { formats::read_rtttl(notes(100'001), "r.rtttl", lra_phone()); }),
              "r.rtttl:1:200018: too long for a score: more than 100000 notes and pauses; a "
              "score holds at most 100000 symbols");
}

TEST(Rtttl, NamesTheLineAndColumnOfWhatIsWrong) {
    const auto read = [](const std::string& text) {
        return first_error([&] { formats::read_rtttl(text, "r.rtttl", lra_phone()); });
    };
    EXPECT_EQ(read("tune:d=4,o=5,b=120:c,x,e"),
              "r.rtttl:1:22: note \"x\": the note letter is a to g, or p for a pause");
    EXPECT_EQ(read("tune:d=4,o=5,b=120:\n  c, 3d"),
              "r.rtttl:2:6: note \"3d\": the duration is 1, 2, 4, 8, 16 or 32");
    EXPECT_EQ(read("tune:d=4,o=5,b=1200:c"),
              "r.rtttl:1:14: \"b=1200\" is out of range (d: 1, 2, 4, 8, 16, 32; o: 0 to 9; b: 1 "
              "to 900; l: 0 to 15)");
    EXPECT_EQ(read("tune:c,d"),
              "r.rtttl:1:1: an RTTTL text is NAME:DEFAULTS:NOTES, e.g. tune:d=4,o=5,b=120:c,e,g");
    EXPECT_EQ(read("t:d=4:32c."),
              "r.rtttl:1:7: note \"32c.\": a dotted 32nd lasts 3/16 of a beat, finer than a "
              "score's 32nd-note grid");
    EXPECT_EQ(read("t:d=4:p#"), "r.rtttl:1:7: note \"p#\": a pause cannot be sharp");
}

}  // namespace
}  // namespace vibscore
