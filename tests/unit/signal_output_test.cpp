// The signal files `vibscore render --out` writes: a CSV is held to the 4 GiB a WAV can hold,
// refused before a byte is written, with its size worked out without writing it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "client/signal_output.hpp"
#include "daemon/render/sampler.hpp"
#include "tests/support/support.hpp"

namespace vibscore::client {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

// Thesis Fig. 2.3's first measure: 4 s of sine tones and a rest.
render::Performance figure_2_3() {
    return render::Performance(testing::bundle_from(
        testing::one_clef_score("<Bar clef=\"c\"><Note length=\"8th\" number=\"1\" string=\"2\" "
                                "legato=\"1\"/><Note length=\"quarter\" number=\"2\" string=\"3\" "
                                "legato=\"1\"/><Rest length=\"8th\"/><Note length=\"half\" "
                                "number=\"2\" string=\"1\"/></Bar>"),
        {{"c.xml", testing::sine_clef(1.0, {100, 150, 200}, {1, 2})}}));
}

TEST(SignalOutput, TheCountedSizeOfACsvIsTheSizeWritten) {
    TempDir dir;
    const auto performance = figure_2_3();
    for (const std::uint32_t rate : {1000u, 8000u, 44100u}) {
        const auto csv = dir.path() / ("out" + std::to_string(rate) + ".csv");
        write_signal(performance, rate, csv);
        EXPECT_EQ(csv_size(performance, rate), std::filesystem::file_size(csv)) << rate;
    }
}

TEST(SignalOutput, ACsvOfExactlyTheLimitIsWrittenAndOneByteMoreIsRefusedBeforeWriting) {
    TempDir dir;
    const auto performance = figure_2_3();
    const auto bytes = csv_size(performance, 1000);
    // The count is needed: the rows are between their shortest and longest.
    ASSERT_LT(csv_size_bounds(4000).least, bytes);
    ASSERT_GT(csv_size_bounds(4000).most, bytes);

    const auto fits = dir.path() / "fits.csv";
    EXPECT_EQ(write_signal(performance, 1000, fits, bytes), 4000u);
    EXPECT_EQ(std::filesystem::file_size(fits), bytes);

    const auto refused = dir.path() / "refused.csv";
    try {
        write_signal(performance, 1000, refused, bytes - 1);
        ADD_FAILURE() << "a CSV one byte over the limit was written";
    } catch (const SignalTooLarge& error) {
        EXPECT_EQ(std::string(error.what()),
                  refused.string() + " would take " + std::to_string(bytes) +
                      " bytes, more than the " + std::to_string(bytes - 1) +
                      " bytes a signal file may take; use a lower --rate than 1000 Hz");
    }
    EXPECT_FALSE(std::filesystem::exists(refused));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "refused.csv.partial"));
}

TEST(SignalOutput, ACsvWhoseShortestRowsPassTheLimitIsRefusedWithoutRendering) {
    // "t,y\n" and 4 bytes a row at least ("0,0\n"): 1,073,741,823 rows may still fit in 4 GiB,
    // one more cannot.
    EXPECT_EQ(kMaxSignalFileBytes, 4294967296u);
    EXPECT_EQ(csv_size_bounds(1'073'741'823).least, kMaxSignalFileBytes);
    EXPECT_EQ(csv_size_bounds(1'073'741'824).least, kMaxSignalFileBytes + 4);
    EXPECT_EQ(csv_size_bounds(10).most, 4u + 10 * 50);

    TempDir dir;
    const auto out = dir.path() / "out.csv";
    // 4 s at 4,000,000 Hz: 16 M rows, at least 64 MB, against a limit of 1 MB.
    try {
        write_signal(figure_2_3(), 4'000'000, out, 1'000'000);
        ADD_FAILURE() << "written";
    } catch (const SignalTooLarge& error) {
        EXPECT_THAT(error.what(), HasSubstr(" would take at least 64000004 bytes, more than the "
                                            "1000000 bytes a signal file may take"));
    }
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SignalOutput, AWavIsHeldToTheSameLimit) {
    TempDir dir;
    const auto performance = figure_2_3();
    const auto wav = dir.path() / "out.wav";
    // 58 bytes of header and 4 a sample.
    const std::uint64_t bytes = 58 + 4 * 4000;
    EXPECT_EQ(write_signal(performance, 1000, wav, bytes), 4000u);
    EXPECT_EQ(std::filesystem::file_size(wav), bytes);
    const auto refused = dir.path() / "refused.wav";
    EXPECT_THROW(write_signal(performance, 1000, refused, bytes - 1), SignalTooLarge);
    EXPECT_FALSE(std::filesystem::exists(refused));
}

}  // namespace
}  // namespace vibscore::client
