// The daemons' log: journal fields under systemd, the sd-daemon prefix into files and pipes, and
// plain text on a terminal.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/log.hpp"

namespace vibscore::log {
namespace {

using detail::journal_fields;
using detail::names_stream;
using detail::stream_line;
using ::testing::ElementsAre;

TEST(LogSink, TheJournalIsUsedOnlyWhenJournalStreamNamesStderrItself) {
    EXPECT_TRUE(names_stream("8:1234", 8, 1234));
    EXPECT_FALSE(names_stream("8:1234", 8, 1235));  // stderr was redirected since systemd set it
    EXPECT_FALSE(names_stream("8:1234", 9, 1234));
    EXPECT_FALSE(names_stream(nullptr, 8, 1234));
    EXPECT_FALSE(names_stream("", 8, 1234));
    EXPECT_FALSE(names_stream("8", 8, 1234));
    EXPECT_FALSE(names_stream("8:", 8, 0));
    EXPECT_FALSE(names_stream("8:1234x", 8, 1234));
    EXPECT_FALSE(names_stream(":1234", 0, 1234));
}

TEST(JournalFields, MessagePriorityAndTheLinesOwnFields) {
    EXPECT_THAT(
        journal_fields(6, "playback 7 finished: completed",
                       {{"PLAYBACK_ID", "7"}, {"CALLER_UID", "1000"}, {"REASON", "completed"}}),
        ElementsAre("MESSAGE=playback 7 finished: completed", "PRIORITY=6", "PLAYBACK_ID=7",
                    "CALLER_UID=1000", "REASON=completed"));
}

// journald drops a whole entry with a bad field name: such a field is left out instead.
TEST(JournalFields, ANameJournaldWouldRefuseIsDroppedNotTheEntry) {
    const std::string longest(64, 'A');
    const std::string too_long(65, 'A');
    EXPECT_THAT(journal_fields(4, "m",
                               {{longest, "1"},
                                {too_long, "2"},
                                {"_PID", "3"},
                                {"usage", "4"},
                                {"9LIVES", "5"},
                                {"", "6"},
                                {"USAGE_2", "7"}}),
                ElementsAre("MESSAGE=m", "PRIORITY=4", longest + "=1", "USAGE_2=7"));
}

TEST(StreamLine, FilesAndPipesKeepTheSdDaemonPrefixAndShowTheFields) {
    EXPECT_EQ(stream_line(Sink::stream, 6, "vibscored ready", {}), "<6>vibscored ready\n");
    EXPECT_EQ(stream_line(Sink::stream, 3, "playback 7 failed",
                          {{"PLAYBACK_ID", "7"}, {"REASON", "device-error"}}),
              "<3>playback 7 failed (PLAYBACK_ID=7, REASON=device-error)\n");
}

TEST(StreamLine, ATerminalShowsPlainTextWithTheLevelInWordsForProblemsOnly) {
    EXPECT_EQ(stream_line(Sink::terminal, 6, "vibscored ready", {}), "vibscored ready\n");
    EXPECT_EQ(stream_line(Sink::terminal, 7, "detail", {}), "detail\n");
    EXPECT_EQ(stream_line(Sink::terminal, 4, "driver = auto found no actuator", {}),
              "warning: driver = auto found no actuator\n");
    EXPECT_EQ(stream_line(Sink::terminal, 3, "cannot open", {{"USAGE", "touch"}}),
              "error: cannot open (USAGE=touch)\n");
    EXPECT_EQ(stream_line(Sink::terminal, 2, "critical", {}), "error: critical\n");
}

}  // namespace
}  // namespace vibscore::log
