#include <gtest/gtest.h>

#include <algorithm>

#include "daemon/render/cue_schedule.hpp"
#include "tests/support/support.hpp"

namespace vibscore::render {
namespace {

using testing::bundle_from;
using testing::one_clef_score;
using testing::sine_clef;

std::vector<Cue> cues_for(const std::string& symbols, const std::string& clef) {
    const Performance performance(
        bundle_from(one_clef_score("<Bar clef=\"c\">" + symbols + "</Bar>"), {{"c.xml", clef}}));
    return cue_schedule(performance);
}

std::vector<Cue> drives(const std::vector<Cue>& cues) {
    std::vector<Cue> only;
    std::copy_if(cues.begin(), cues.end(), std::back_inserter(only),
                 [](const Cue& cue) { return cue.kind == Cue::Kind::drive; });
    return only;
}

TEST(CueSchedule, SteadyNotesDriveAtOnsetAndStopAtTheirEnd) {
    const auto cues = cues_for(
        "<Note length=\"quarter\" number=\"2\" string=\"1\"/><Rest length=\"quarter\"/>"
        "<Note length=\"quarter\" number=\"1\" string=\"2\"/>",
        sine_clef(1.0, {150, 200}, {0.5, 0.8}));
    ASSERT_EQ(cues.size(), 7u);
    EXPECT_EQ(cues[0].kind, Cue::Kind::drive);  // the actuator first: it is what people feel
    EXPECT_EQ(cues[0].at, 0.0);
    EXPECT_EQ(cues[0].amplitude, 0.8);
    EXPECT_EQ(cues[0].frequency_hz, 150.0);
    EXPECT_EQ(cues[1].kind, Cue::Kind::position);
    EXPECT_EQ(cues[1].symbol, 0u);
    EXPECT_EQ(cues[2].at, 1.0);  // off at the end of the note, before the rest's position
    EXPECT_EQ(cues[2].amplitude, 0.0);
    EXPECT_EQ(cues[3].kind, Cue::Kind::position);
    EXPECT_EQ(cues[3].symbol, 1u);
    EXPECT_EQ(cues[4].at, 2.0);
    EXPECT_EQ(cues[4].frequency_hz, 200.0);
    EXPECT_EQ(cues[6].at, 3.0);
    EXPECT_EQ(cues[6].amplitude, 0.0);
}

TEST(CueSchedule, TheDefaultSilenceTurnsTheActuatorOff) {
    const auto cues =
        drives(cues_for("<Note length=\"quarter\" number=\"1\" string=\"1\"/>"
                        "<Note length=\"quarter\" number=\"1\" string=\"1\"/>",
                        sine_clef(1.0, {150}, {1})));
    ASSERT_EQ(cues.size(), 4u);
    EXPECT_DOUBLE_EQ(cues[1].at, 0.97);
    EXPECT_EQ(cues[1].amplitude, 0.0);
    EXPECT_EQ(cues[2].at, 1.0);
    EXPECT_EQ(cues[2].amplitude, 1.0);
}

TEST(CueSchedule, LegatoNotesChangeWithoutGoingOff) {
    const auto cues =
        drives(cues_for("<Note length=\"quarter\" number=\"1\" string=\"1\" legato=\"1\"/>"
                        "<Note length=\"quarter\" number=\"1\" string=\"2\" legato=\"1\"/>",
                        sine_clef(1.0, {150, 200}, {1})));
    ASSERT_EQ(cues.size(), 3u);
    EXPECT_EQ(cues[1].at, 1.0);
    EXPECT_EQ(cues[1].frequency_hz, 200.0);
    EXPECT_EQ(cues[2].amplitude, 0.0);
}

TEST(CueSchedule, EachNotesFirstDriveSaysItStartsANoteAndNoStepWithinItDoes) {
    // A legato line of a crescendo into a steady note: the drive at each note's onset starts a
    // note, tied or not; the crescendo's steps and the silence after do not.
    const auto cues =
        drives(cues_for("<Note length=\"quarter\" number=\"2\" string=\"1\" legato=\"1\" "
                        "dynamics=\"crescendo\"/>"
                        "<Note length=\"quarter\" number=\"1\" string=\"2\" legato=\"1\"/>",
                        sine_clef(1.0, {150, 200}, {0.5, 1.0})));
    ASSERT_GE(cues.size(), 4u);
    std::vector<double> starts;
    for (const Cue& cue : cues) {
        if (cue.starts_note) {
            starts.push_back(cue.at);
        }
    }
    EXPECT_EQ(starts, (std::vector<double>{0.0, 1.0}));
    EXPECT_EQ(cues.back().amplitude, 0.0);
}

TEST(CueSchedule, RampsAreFollowedInSmallSteps) {
    const auto cues = drives(
        cues_for("<Note length=\"quarter\" number=\"2\" string=\"1\" dynamics=\"crescendo\"/>",
                 sine_clef(1.0, {150}, {0.5, 1.0})));
    ASSERT_GE(cues.size(), 200u);  // at least 100 updates per second
    for (std::size_t i = 1; i + 1 < cues.size(); ++i) {
        EXPECT_GT(cues[i].amplitude, cues[i - 1].amplitude);
        EXPECT_LE(cues[i].at - cues[i - 1].at, 0.005 + 1e-12);
        EXPECT_NEAR(cues[i].amplitude, cues[i].at, 1e-9);  // 0 -> 1 over 1 s
    }
    EXPECT_EQ(cues.back().amplitude, 0.0);
}

TEST(CueSchedule, PortamentoGlidesTheFrequency) {
    const auto cues =
        drives(cues_for("<Note length=\"quarter\" number=\"1\" string=\"1\" portamento=\"1\"/>"
                        "<Note length=\"quarter\" number=\"1\" string=\"2\" portamento=\"1\"/>",
                        sine_clef(1.0, {100, 400}, {1})));
    const auto half_way =
        std::find_if(cues.begin(), cues.end(), [](const Cue& cue) { return cue.at >= 0.5 - 1e-9; });
    ASSERT_NE(half_way, cues.end());
    EXPECT_NEAR(half_way->frequency_hz, 200.0, 1e-6);
}

TEST(CueSchedule, SquareWaveStepsFallExactlyOnItsPoints) {
    const std::string square =
        "<VibClef type=\"line\"><Tempo>0.1</Tempo><Number>1</Number><Strings><String>"
        "<Point time=\"0\" level=\"1\"/><Point time=\"0.3\" level=\"1\"/>"
        "<Point time=\"0.3\" level=\"0\"/><Point time=\"1\" level=\"0\"/>"
        "</String></Strings></VibClef>";
    const auto cues = drives(cues_for("<Note length=\"half\" number=\"1\" string=\"1\"/>", square));
    ASSERT_EQ(cues.size(), 4u);
    EXPECT_EQ(cues[0].amplitude, 1.0);
    EXPECT_DOUBLE_EQ(cues[1].at, 0.03);
    EXPECT_EQ(cues[1].amplitude, 0.0);
    EXPECT_DOUBLE_EQ(cues[2].at, 0.1);
    EXPECT_EQ(cues[2].amplitude, 1.0);
    EXPECT_DOUBLE_EQ(cues[3].at, 0.13);
    EXPECT_EQ(cues[3].amplitude, 0.0);
}

TEST(CueSchedule, CuesAreInTimeOrder) {
    const auto cues = cues_for(
        "<Note length=\"8th\" number=\"1\" string=\"1\" dynamics=\"crescendo\"/>"
        "<Note length=\"8th\" number=\"2\" string=\"2\" portamento=\"3\"/>"
        "<Note length=\"8th\" number=\"1\" string=\"1\" portamento=\"3\"/>"
        "<Rest length=\"16th\"/><Blank/><Note length=\"32th\" number=\"2\" string=\"2\"/>",
        sine_clef(0.2, {150, 190}, {0.5, 1}));
    for (std::size_t i = 1; i < cues.size(); ++i) {
        EXPECT_GE(cues[i].at, cues[i - 1].at);
    }
    EXPECT_EQ(std::count_if(cues.begin(), cues.end(),
                            [](const Cue& c) { return c.kind == Cue::Kind::position; }),
              5);
}

}  // namespace
}  // namespace vibscore::render
