// Runs the real vibscore binary's offline verbs and checks what a user sees and gets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::required_env;
using testing::run_command;
using testing::TempDir;

std::string vibscore() {
    return required_env("VIBSCORE");
}
std::string shipped(const std::string& name) {
    return required_env("VIBSCORE_CLEFS") + "/" + name;
}

// Thesis Fig. 2.3's first measure on disk.
std::filesystem::path write_figure_2_3(const TempDir& dir) {
    dir.write("c.xml", testing::sine_clef(1.0, {100, 150, 200}, {1, 2}));
    return dir.write(
        "fig23.xml",
        "<VibScore><Title>Fig 2.3</Title><Clef id=\"c\" href=\"c.xml\"/><Bar clef=\"c\">"
        "<Note length=\"8th\" number=\"1\" string=\"2\" legato=\"1\"/>"
        "<Note length=\"quarter\" number=\"2\" string=\"3\" legato=\"1\"/>"
        "<Rest length=\"8th\"/><Note length=\"half\" number=\"2\" string=\"1\"/>"
        "</Bar></VibScore>");
}

TEST(ClientOffline, HelpOnTheProgramAndEveryVerb) {
    for (const std::vector<std::string>& args : {std::vector<std::string>{"--help"},
                                                 {"check", "--help"},
                                                 {"render", "--help"},
                                                 {"convert", "--help"},
                                                 {"info", "--help"}}) {
        std::vector<std::string> argv{vibscore()};
        argv.insert(argv.end(), args.begin(), args.end());
        const auto result = run_command(argv);
        EXPECT_EQ(result.exit_code, 0) << args[0];
        EXPECT_NE(result.out.find("Usage"), std::string::npos) << result.out;
    }
}

TEST(ClientOffline, UsageErrorsExitTwo) {
    EXPECT_EQ(run_command({vibscore()}).exit_code, 2);
    EXPECT_EQ(run_command({vibscore(), "frobnicate"}).exit_code, 2);
    EXPECT_EQ(run_command({vibscore(), "check"}).exit_code, 2);
    const auto rate = run_command({vibscore(), "render", "x.xml", "--rate", "0", "--out", "a.csv"});
    EXPECT_EQ(rate.exit_code, 2);
    const auto format =
        run_command({vibscore(), "render", shipped("create.score.xml"), "--out", "/tmp/out.mp3"});
    EXPECT_EQ(format.exit_code, 2);
    EXPECT_NE(format.err.find("name it .csv or .wav"), std::string::npos) << format.err;
}

TEST(ClientOffline, CheckAcceptsEveryShippedDocument) {
    std::vector<std::string> argv{vibscore(), "check"};
    for (const auto& entry : std::filesystem::directory_iterator(required_env("VIBSCORE_CLEFS"))) {
        if (entry.path().extension() == ".xml") {
            argv.push_back(entry.path().string());
        }
    }
    ASSERT_GT(argv.size(), 20u);
    const auto result = run_command(argv);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err, "");
}

TEST(ClientOffline, CheckListsEveryProblemWithFileLineColumnAndExitsOne) {
    TempDir dir;
    dir.write("c.xml", testing::sine_clef(1.0, {100}, {1}));
    const auto bad =
        dir.write("bad.xml",
                  "<VibScore><Clef id=\"c\" href=\"c.xml\"/>\n<Bar clef=\"c\">\n"
                  "  <Note length=\"9th\" number=\"1\" string=\"1\"/>\n"
                  "  <Note length=\"8th\" number=\"1\" string=\"2\"/>\n</Bar></VibScore>");
    const auto good = dir.write(
        "good.xml", "<VibScore><Clef id=\"c\" href=\"c.xml\"/><Bar clef=\"c\"/></VibScore>");
    const auto result = run_command({vibscore(), "check", good.string(), bad.string()});
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.out.find(good.string() + ": ok"), std::string::npos);
    EXPECT_NE(result.err.find(bad.string() + ":3:3: unknown length \"9th\""), std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("1 of 2 documents are invalid"), std::string::npos);
}

TEST(ClientOffline, CheckNamesANoteBeyondItsClef) {
    TempDir dir;
    dir.write("c.xml", testing::sine_clef(1.0, {100}, {1}));
    const auto bad =
        dir.write("bad.xml",
                  "<VibScore><Clef id=\"c\" href=\"c.xml\"/>\n<Bar clef=\"c\">\n"
                  "  <Note length=\"8th\" number=\"1\" string=\"2\"/>\n</Bar></VibScore>");
    const auto result = run_command({vibscore(), "check", bad.string()});
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.err.find(":3:3: string 2 is beyond clef \"c\""), std::string::npos)
        << result.err;
}

TEST(ClientOffline, RenderCsvHasHeaderAndOneRowPerSampleOfTheSignal) {
    TempDir dir;
    const auto score = write_figure_2_3(dir);
    const auto csv = dir.path() / "out.csv";
    const auto result = run_command(
        {vibscore(), "render", score.string(), "--rate", "1000", "--out", csv.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("4000 samples at 1000 Hz"), std::string::npos) << result.out;
    std::istringstream lines(testing::read_file(csv));
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, "t,y");
    int rows = 0;
    while (std::getline(lines, line)) {
        double t = 0, y = 0;
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf", &t, &y), 2) << line;
        EXPECT_DOUBLE_EQ(t, rows / 1000.0);
        const double expected = t < 0.5   ? std::sin(2 * M_PI * 150 * t)
                                : t < 1.5 ? 2 * std::sin(2 * M_PI * 200 * t)
                                : t < 2.0 ? 0.0
                                          : 2 * std::sin(2 * M_PI * 100 * t);
        EXPECT_NEAR(y, expected, 1e-9) << line;
        ++rows;
    }
    EXPECT_EQ(rows, 4000);
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out.csv.partial"));
}

TEST(ClientOffline, RenderWavIsMonoFloatAtTheRateWithEverySample) {
    TempDir dir;
    const auto score = write_figure_2_3(dir);
    const auto wav = dir.path() / "out.wav";
    const auto result = run_command(
        {vibscore(), "render", score.string(), "--rate", "8000", "--out", wav.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const std::string bytes = testing::read_file(wav);
    const auto u16 = [&](std::size_t at) {
        return static_cast<unsigned>(static_cast<unsigned char>(bytes[at]) |
                                     static_cast<unsigned char>(bytes[at + 1]) << 8);
    };
    const auto u32 = [&](std::size_t at) { return u16(at) | u16(at + 2) << 16; };
    ASSERT_GE(bytes.size(), 58u);
    EXPECT_EQ(bytes.substr(0, 4), "RIFF");
    EXPECT_EQ(u32(4), bytes.size() - 8);
    EXPECT_EQ(bytes.substr(8, 8), "WAVEfmt ");
    EXPECT_EQ(u16(20), 3u);  // IEEE float
    EXPECT_EQ(u16(22), 1u);  // mono
    EXPECT_EQ(u32(24), 8000u);
    EXPECT_EQ(u16(34), 32u);
    EXPECT_EQ(bytes.substr(38, 4), "fact");
    EXPECT_EQ(u32(46), 32000u);
    EXPECT_EQ(bytes.substr(50, 4), "data");
    EXPECT_EQ(u32(54), 32000u * 4);
    // Sample 2000 + 1/4 of a 100 Hz cycle at 8 kHz: t = 2.0025 s, y = 2 sin(pi/2) = 2.
    float sample = 0;
    std::memcpy(&sample, bytes.data() + 58 + 4 * 16020, 4);
    EXPECT_NEAR(sample, 2.0f, 1e-6);
}

TEST(ClientOffline, RenderOfABrokenScoreLeavesNoFileBehind) {
    TempDir dir;
    const auto score = dir.write("broken.xml", "<VibScore><Bar clef=\"x\"/></VibScore>");
    const auto out = dir.path() / "out.csv";
    const auto result = run_command({vibscore(), "render", score.string(), "--out", out.string()});
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.err.find("uses clef \"x\", which no <Clef> declares"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ClientOffline, RenderIntoAMissingDirectoryFailsNamingThePath) {
    const auto result = run_command(
        {vibscore(), "render", shipped("create.score.xml"), "--out", "/nonexistent/dir/out.csv"});
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.err.find("/nonexistent/dir/out.csv.partial: cannot create"), std::string::npos)
        << result.err;
}

TEST(ClientOffline, RenderRefusesACsvAboveFourGibBeforeWritingAByte) {
    // Issue 33: 14 whole notes on a tempo-60 clef (56 minutes) at 384 kHz is 1.29 G rows, at
    // least 5.2 GB of CSV: refused at once, naming the size and the limit, as the WAV is.
    TempDir dir;
    dir.write("slow.xml", testing::sine_clef(60.0, {100}, {1}));
    std::string notes;
    for (int i = 0; i < 14; ++i) {
        notes += "<Note length=\"whole\" number=\"1\" string=\"1\"/>";
    }
    const auto score =
        dir.write("hour.xml", "<VibScore><Clef id=\"c\" href=\"slow.xml\"/><Bar clef=\"c\">" +
                                  notes + "</Bar></VibScore>");
    for (const char* name : {"x.csv", "x.wav"}) {
        const auto out = dir.path() / name;
        const auto result = run_command(
            {vibscore(), "render", score.string(), "--rate", "384000", "--out", out.string()});
        EXPECT_EQ(result.exit_code, 1) << name;
        EXPECT_NE(result.err.find(out.string() + " would take "), std::string::npos) << result.err;
        EXPECT_NE(result.err.find("more than the 4294967296 bytes (4 GiB) a signal file may take; "
                                  "use a lower --rate than 384000 Hz"),
                  std::string::npos)
            << result.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << name;
        EXPECT_FALSE(std::filesystem::exists(out.string() + ".partial")) << name;
    }
}

TEST(ClientOffline, RenderActuatorRefusesADeclarationWhoseModelIsNotFiniteAndWritesNoNan) {
    // Issue 33: rated-drive = 5e-324 was taken, and 26,399 of 28,000 rows were NaN.
    TempDir dir;
    const auto score = write_figure_2_3(dir);
    const auto out = dir.path() / "r.csv";
    const auto render = [&](const std::string& kind, const std::string& rated_drive) {
        const auto declaration = dir.write(
            "a.conf", "[actuator]\nkind = " + kind + "\nrated-drive = " + rated_drive + "\n");
        return run_command({vibscore(), "render", score.string(), "--rate", "1000", "--actuator",
                            declaration.string(), "--out", out.string()});
    };
    for (const char* refused : {"5e-324", "7.458340731096626e-155"}) {
        const auto result = render("erm", refused);
        EXPECT_EQ(result.exit_code, 2) << refused;
        EXPECT_NE(
            result.err.find("a.conf:3: [actuator] rated-drive = \"" + std::string(refused) + "\""),
            std::string::npos)
            << result.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << refused;
    }
    // The smallest each kind takes: every row finite.
    for (const auto& [kind, smallest] :
         {std::pair<std::string, std::string>{"erm", "7.458340731096627e-155"},
          {"lra", "7.458340731200207e-155"}}) {
        const auto result = render(kind, smallest);
        ASSERT_EQ(result.exit_code, 0) << kind << ": " << result.err;
        const std::string csv = testing::read_file(out);
        EXPECT_NE(csv.find("\n3.999,"), std::string::npos) << kind;
        for (const char* bad : {"nan", "inf"}) {
            EXPECT_EQ(csv.find(bad), std::string::npos) << kind << ": " << bad;
        }
        std::filesystem::remove(out);
    }
}

TEST(ClientOffline, RenderPlotDrawsTheStrength) {
    const auto result = run_command({vibscore(), "render", shipped("create.score.xml"), "--plot"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("create"), std::string::npos);
    EXPECT_NE(result.out.find("█"), std::string::npos);
    EXPECT_NE(result.out.find("1 s"), std::string::npos) << result.out;
}

TEST(ClientOffline, RenderRefusesAClef) {
    const auto result =
        run_command({vibscore(), "render", shipped("lra-phone.clef.xml"), "--plot"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("is a clef"), std::string::npos);
}

TEST(ClientOffline, InfoShowsTitleDurationBarsAndClefs) {
    TempDir dir;
    const auto score = write_figure_2_3(dir);
    const auto result = run_command({vibscore(), "info", score.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("title:    Fig 2.3"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("duration: 4.000 s (1 bar, 3 notes, 1 rest)"), std::string::npos)
        << result.out;
    EXPECT_NE(result.out.find("c  c.xml  sine, tempo 1 s, 3 strings, 2 numbers"),
              std::string::npos);
    // The second time is the bar's length, and says so.
    EXPECT_NE(result.out.find("1  clef c  4 beats  at 0.000 s, 4.000 s long\n"), std::string::npos)
        << result.out;
}

// A tempo copy made for 140 bpm holds 3/7 s, whose shortest exact decimal has 17 digits.
TEST(ClientOffline, InfoAndCheckPrintTempoAtSixDigitsAndAClefsBeatsPerMinute) {
    TempDir dir;
    const double three_sevenths = 3.0 / 7.0;
    dir.write("slow.clef.xml", testing::sine_clef(three_sevenths, {100, 150, 200}, {1, 2}));
    const auto score =
        dir.write("slow.score.xml",
                  "<VibScore><Clef id=\"c\" href=\"slow.clef.xml\"/><Bar clef=\"c\">"
                  "<Note length=\"whole\" number=\"1\" string=\"2\"/></Bar></VibScore>");
    const auto clef = run_command({vibscore(), "info", (dir.path() / "slow.clef.xml").string()});
    EXPECT_NE(clef.out.find("tempo:    0.428571 s per quarter note (140 bpm)\n"), std::string::npos)
        << clef.out;
    const auto info = run_command({vibscore(), "info", score.string()});
    EXPECT_NE(info.out.find("sine, tempo 0.428571 s, 3 strings"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("at 0.000 s, 1.714 s long\n"), std::string::npos) << info.out;
    const auto checked =
        run_command({vibscore(), "check", (dir.path() / "slow.clef.xml").string()});
    EXPECT_NE(checked.out.find("(clef: sine, tempo 0.428571 s, 3 strings, 2 numbers)"),
              std::string::npos)
        << checked.out;
    EXPECT_EQ(info.out.find("0.42857142857142855"), std::string::npos) << info.out;
}

TEST(ClientOffline, InfoShowsAClefsMapping) {
    const auto result = run_command({vibscore(), "info", shipped("shaker-sine-low.clef.xml")});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("tempo:    0.15 s per quarter note"), std::string::npos);
    EXPECT_NE(result.out.find("1=0.0027"), std::string::npos);
    EXPECT_NE(result.out.find("6  300 Hz"), std::string::npos) << result.out;
}

}  // namespace
}  // namespace vibscore
