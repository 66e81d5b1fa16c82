#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "daemon/config.hpp"
#include "daemon/playback_limits.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr std::uint64_t kStart = 5'000'000;   // a playback's start on the injected clock
constexpr std::uint64_t kLimit = 30'000'000;  // 30 s

std::string error_of(PlaybackLimits& limits, const std::string& key, const std::string& value) {
    try {
        limits.set(key, value);
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    return "(accepted)";
}

TEST(MaxOnTime, EveryNonUrgentUsageIsLimitedTo30SecondsByDefaultAndTheUrgentOnesAreNot) {
    const PlaybackLimits limits;
    for (const auto usage : {Usage::notification, Usage::communication, Usage::accessibility,
                             Usage::hardware_feedback, Usage::touch, Usage::media}) {
        EXPECT_EQ(limits.max_on_time(usage), 30.0) << to_string(usage);
    }
    EXPECT_EQ(limits.max_on_time(Usage::ringtone), std::nullopt);
    EXPECT_EQ(limits.max_on_time(Usage::alarm), std::nullopt);
    EXPECT_EQ(limits.cool_down_s(), 10.0);
}

TEST(MaxOnTime, APerUsageKeyWinsOverTheCommonOneInWhateverOrderTheyCome) {
    PlaybackLimits limits;
    limits.set("max-on-time-media", "600");
    limits.set("max-on-time", "5");
    limits.set("max-on-time-alarm", "120");
    limits.set("max-on-time-touch", "none");
    EXPECT_EQ(limits.max_on_time(Usage::media), 600.0);
    EXPECT_EQ(limits.max_on_time(Usage::notification), 5.0);
    EXPECT_EQ(limits.max_on_time(Usage::alarm), 120.0);
    EXPECT_EQ(limits.max_on_time(Usage::ringtone), std::nullopt);
    EXPECT_EQ(limits.max_on_time(Usage::touch), std::nullopt);
}

TEST(MaxOnTime, NoneLiftsTheCommonLimit) {
    PlaybackLimits limits;
    limits.set("max-on-time", "none");
    EXPECT_EQ(limits.max_on_time(Usage::notification), std::nullopt);
}

TEST(MaxOnTime, ValuesAreRefusedAtTheirEdgesNamingKeyAndValue) {
    PlaybackLimits limits;
    EXPECT_EQ(error_of(limits, "max-on-time", "86400"), "(accepted)");
    EXPECT_THAT(error_of(limits, "max-on-time", "86400.001"),
                StartsWith("max-on-time = \"86400.001\" is neither \"none\" nor seconds"));
    EXPECT_EQ(error_of(limits, "max-on-time", "0.000001"), "(accepted)");
    EXPECT_THAT(error_of(limits, "max-on-time", "0"), StartsWith("max-on-time = \"0\""));
    EXPECT_THAT(error_of(limits, "max-on-time", "5e-324"), StartsWith("max-on-time = \"5e-324\""));
    EXPECT_THAT(error_of(limits, "max-on-time", "nan"), StartsWith("max-on-time = \"nan\""));
    EXPECT_EQ(error_of(limits, "cool-down", "0"), "(accepted)");
    EXPECT_EQ(error_of(limits, "cool-down", "3600"), "(accepted)");
    EXPECT_THAT(error_of(limits, "cool-down", "3600.5"), StartsWith("cool-down = \"3600.5\""));
    EXPECT_THAT(error_of(limits, "cool-down", "-1"), StartsWith("cool-down = \"-1\""));
    EXPECT_THAT(error_of(limits, "max-on-time-buzz", "3"),
                AllOf(HasSubstr("unknown key \"max-on-time-buzz\" in [limits]"),
                      HasSubstr("notification")));
}

TEST(MaxOnTime, TheConfigurationReadsLimitsAndNamesTheLineOfAWrongValue) {
    const auto config =
        parse_config("[limits]\nmax-on-time = 12\ncool-down = 4\nmax-on-time-media = 90\n", "t");
    EXPECT_EQ(config.limits.max_on_time(Usage::notification), 12.0);
    EXPECT_EQ(config.limits.max_on_time(Usage::media), 90.0);
    EXPECT_EQ(config.limits.cool_down_s(), 4.0);
    EXPECT_TRUE(unknown_sections(config, {}).empty()) << "[limits] is a service section";
    try {
        parse_config("[limits]\n\ncool-down = soon\n", "t.conf");
        ADD_FAILURE() << "accepted";
    } catch (const ConfigError& error) {
        EXPECT_THAT(error.what(), StartsWith("t.conf:3: cool-down = \"soon\""));
    }
}

TEST(MaxOnTime, IsCountedFromTheStartAcrossRepeats) {
    EXPECT_EQ(max_on_time_deadline_us(kStart, 30.0), kStart + kLimit);
    EXPECT_EQ(max_on_time_deadline_us(kStart, std::nullopt), std::nullopt);
}

TEST(MaxOnTime, TheLastMicrosecondBeforeTheLimitStillPlaysAndTheLimitEndsThePlayback) {
    const auto deadline = max_on_time_deadline_us(kStart, 30.0);
    const std::uint64_t next_cue = kStart + kLimit + 250'000;  // the next pass, after the limit
    const auto before = next_step(kStart + kLimit - 1, next_cue, deadline);
    EXPECT_EQ(before.kind, NextStep::Kind::wait);
    EXPECT_EQ(before.wake_us, kStart + kLimit) << "woken at the limit, not at the next cue";
    EXPECT_EQ(next_step(kStart + kLimit, next_cue, deadline).kind, NextStep::Kind::end_over_limit);
}

TEST(MaxOnTime, ACueDueAtTheLimitStillRunsSoAScoreExactlyAsLongAsTheLimitCompletes) {
    const auto deadline = max_on_time_deadline_us(kStart, 30.0);
    EXPECT_EQ(next_step(kStart + kLimit, kStart + kLimit, deadline).kind, NextStep::Kind::run_cue);
    EXPECT_EQ(next_step(kStart + kLimit, kStart + kLimit + 1, deadline).kind,
              NextStep::Kind::end_over_limit)
        << "the first microsecond over";
}

TEST(MaxOnTime, WithoutALimitAPlaybackWaitsForItsNextCueHoweverLate) {
    const auto step = next_step(kStart + 3'600'000'000, kStart + 3'700'000'000, std::nullopt);
    EXPECT_EQ(step.kind, NextStep::Kind::wait);
    EXPECT_EQ(step.wake_us, kStart + 3'700'000'000);
}

TEST(MaxOnTime, ItsReasonIsALimitExceededThatCanBeToldFromTheCueRateOne) {
    EXPECT_EQ(over_on_time_reason(30.0),
              "limit-exceeded: played for its maximum on-time of 30 s ([limits] max-on-time)");
    EXPECT_TRUE(is_over_on_time(over_on_time_reason(0.5)));
    EXPECT_FALSE(
        is_over_on_time("limit-exceeded: the score asks for more than 1000 actuator "
                        "commands and positions a second"));
}

constexpr std::uint64_t kCutOff = 100'000'000;
constexpr double kCoolDown_s = 10.0;

TEST(CoolDown, TheLastMicrosecondIsRefusedAndTheCoolDownsEndIsAllowed) {
    CoolDowns cool_downs;
    cool_downs.cut_off(1000, kCutOff);
    EXPECT_EQ(cool_downs.wait_us(1000, Usage::notification, -1, kCoolDown_s, kCutOff), 10'000'000u);
    EXPECT_EQ(
        cool_downs.wait_us(1000, Usage::notification, -1, kCoolDown_s, kCutOff + 10'000'000 - 1),
        1u);
    EXPECT_EQ(cool_downs.wait_us(1000, Usage::notification, -1, kCoolDown_s, kCutOff + 10'000'000),
              0u);
}

TEST(CoolDown, IsRefusedWithANamedErrorSayingHowLongIsLeft) {
    CoolDowns cool_downs;
    cool_downs.cut_off(1000, kCutOff);
    try {
        cool_downs.check(1000, Usage::touch, 3, kCoolDown_s, kCutOff + 7'500'000);
        ADD_FAILURE() << "allowed";
    } catch (const CoolingDown& error) {
        EXPECT_THAT(error.what(), HasSubstr("uid 1000"));
        EXPECT_THAT(error.what(), HasSubstr("repeating touch playback for another 2.5 s"));
        EXPECT_THAT(error.what(), HasSubstr("[limits] cool-down = 10 s"));
    }
    EXPECT_NO_THROW(cool_downs.check(1000, Usage::touch, 3, kCoolDown_s, kCutOff + 10'000'000));
}

TEST(CoolDown, BindsOnlyRepeatingNonUrgentPlaybacksOfTheUserCutOff) {
    CoolDowns cool_downs;
    cool_downs.cut_off(1000, kCutOff);
    const auto now = kCutOff + 1;
    for (const auto usage : {Usage::notification, Usage::communication, Usage::accessibility,
                             Usage::hardware_feedback, Usage::touch, Usage::media}) {
        EXPECT_GT(cool_downs.wait_us(1000, usage, 1, kCoolDown_s, now), 0u) << to_string(usage);
        EXPECT_EQ(cool_downs.wait_us(1000, usage, 0, kCoolDown_s, now), 0u)
            << to_string(usage) << ": a one-shot";
    }
    EXPECT_EQ(cool_downs.wait_us(1000, Usage::ringtone, -1, kCoolDown_s, now), 0u);
    EXPECT_EQ(cool_downs.wait_us(1000, Usage::alarm, -1, kCoolDown_s, now), 0u);
    EXPECT_EQ(cool_downs.wait_us(1001, Usage::notification, -1, kCoolDown_s, now), 0u)
        << "another user";
}

TEST(CoolDown, ZeroMeansNone) {
    CoolDowns cool_downs;
    cool_downs.cut_off(1000, kCutOff);
    EXPECT_EQ(cool_downs.wait_us(1000, Usage::notification, -1, 0.0, kCutOff), 0u);
}

TEST(CoolDown, WhoWasCutOffLongerThanTheLongestCoolDownAgoIsForgotten) {
    CoolDowns cool_downs;
    cool_downs.cut_off(1000, kCutOff);
    cool_downs.cut_off(1001, kCutOff + 3'600'000'000 - 1);
    EXPECT_EQ(cool_downs.remembered(), 2u) << "1000's hour is not yet over";
    cool_downs.cut_off(1002, kCutOff + 3'600'000'000);
    EXPECT_EQ(cool_downs.remembered(), 2u) << "1000 forgotten";
}

}  // namespace
}  // namespace vibscore::daemon
