#include "daemon/drivers/sim_actuator.hpp"

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "daemon/drivers/driver_settings.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using vibscore::testing::TempDir;

// A clock the test advances by hand.
struct FakeClock {
    std::int64_t now_ns = 1'000'000'000;
    MonotonicClock function() {
        return [this] { return now_ns; };
    }
};

struct TraceLine {
    std::int64_t time_ns;
    double amplitude;
    double frequency_hz;
    double response;
};

std::vector<std::string> lines_of(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

TraceLine parse(const std::string& line) {
    TraceLine parsed{};
    char comma = 0;
    std::istringstream in(line);
    in >> parsed.time_ns >> comma >> parsed.amplitude >> comma >> parsed.frequency_hz >> comma >>
        parsed.response;
    EXPECT_TRUE(in) << line;
    return parsed;
}

// Everything written to a pipe's write end by f, read once f has returned (and closed up).
template <typename F>
std::string pipe_output(F&& f) {
    int fds[2];
    EXPECT_EQ(::pipe(fds), 0);
    f(fds[1]);
    ::close(fds[1]);
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) {
        text.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fds[0]);
    return text;
}

TEST(SimActuator, NameAndCapabilities) {
    SimActuator sim({});
    EXPECT_EQ(sim.driver_name(), "sim");
    const auto capabilities = sim.capabilities();
    EXPECT_TRUE(capabilities.amplitude_control);
    EXPECT_TRUE(capabilities.frequency_control);
    EXPECT_FALSE(capabilities.effect_memory);
}

TEST(SimActuator, FeedsTheModelAndCountsCommands) {
    FakeClock clock;
    SimSettings settings;
    settings.actuator.kind = actuator::Kind::erm;
    SimActuator sim(settings, clock.function());
    sim.apply({0.5, 0.0});
    EXPECT_EQ(sim.command_count(), 1u);
    EXPECT_DOUBLE_EQ(sim.model().target(), 0.5);
    // One spin-up time constant later (the declaration's default, 40 ms; the sim's own was 50).
    clock.now_ns += 40'000'000;
    EXPECT_NEAR(sim.model().response_at(1.040), 0.5 * (1.0 - std::exp(-1.0)), 1e-9);
    sim.off();
    EXPECT_EQ(sim.command_count(), 2u);
    EXPECT_EQ(sim.model().target(), 0.0);
}

TEST(SimActuator, ClampsAmplitude) {
    SimActuator sim({});
    sim.apply({1.7, 0.0});
    EXPECT_DOUBLE_EQ(sim.model().target(), 1.0);
    sim.apply({-0.2, 0.0});  // no reverse without a declared brake
    EXPECT_DOUBLE_EQ(sim.model().target(), 0.0);
    sim.apply({NAN, 0.0});
    EXPECT_DOUBLE_EQ(sim.model().target(), 0.0);
}

// The declared actuator: its rated drive, and reverse drive where the board brakes.
SimSettings declared(actuator::Kind kind, actuator::Brake brake) {
    SimSettings settings;
    settings.actuator.kind = kind;
    settings.actuator.rated_drive = 0.7;
    settings.actuator.spin_up_s = 0.040;
    settings.actuator.spin_down_s = 0.080;
    settings.actuator.q = 15.0;
    settings.actuator.brake = brake;
    settings.declared = true;
    return settings;
}

TEST(SimActuator, SimulatesTheDeclaredErmDrivenBackwards) {
    FakeClock clock;
    SimActuator sim(declared(actuator::Kind::erm, actuator::Brake::reverse), clock.function());
    EXPECT_TRUE(sim.capabilities().reverse);
    sim.apply({0.7, 0.0});
    clock.now_ns += 1'000'000'000;  // spun up to strength 1
    sim.apply({-1.0, 0.0});
    const double t = 2.0 + 0.040 * std::log((1.0 + 1.0 / 0.7) / (1.0 / 0.7));
    EXPECT_NEAR(sim.model().response_at(t), 0.0, 1e-6);  // stopped by the reverse drive
    EXPECT_EQ(sim.model().drive().amplitude, -1.0);
}

TEST(SimActuator, SimulatesTheDeclaredLraPushedDownInAntiPhase) {
    FakeClock clock;
    SimActuator sim(declared(actuator::Kind::lra, actuator::Brake::reverse), clock.function());
    const double tau = actuator::lra_time_constant_s(175.0, 15.0);
    sim.apply({0.7, 175.0});
    clock.now_ns += 2'000'000'000;
    sim.apply({-0.7, 175.0});
    EXPECT_NEAR(sim.model().response_at(3.0 + tau * std::log(2.0)), 0.0, 1e-9);
}

// A reload that changes only the declared numbers: the sim takes them in place (what plays goes
// on, now on the new physics); another kind or brake would change what the player planned with.
TEST(SimActuator, TakesANewDeclarationOfTheSameKindAndBrakeInPlace) {
    FakeClock clock;
    SimActuator sim(declared(actuator::Kind::lra, actuator::Brake::reverse), clock.function());
    sim.apply({0.7, 175.0});
    auto retuned = declared(actuator::Kind::lra, actuator::Brake::reverse).actuator;
    retuned.resonance_hz = 160.0;
    ASSERT_TRUE(sim.take_declaration(retuned));
    EXPECT_EQ(sim.model().physics().declaration().resonance_hz, 160.0);
    EXPECT_EQ(sim.model().drive(), (actuator::Drive{0.7, 175.0})) << "the drive in force goes on";
    EXPECT_TRUE(sim.capabilities().reverse);

    auto unbraked = retuned;
    unbraked.brake = actuator::Brake::none;
    EXPECT_FALSE(sim.take_declaration(unbraked));  // the reverse capability would go
    auto erm = retuned;
    erm.kind = actuator::Kind::erm;
    EXPECT_FALSE(sim.take_declaration(erm));
    EXPECT_EQ(sim.model().physics().declaration().resonance_hz, 160.0) << "refused: unchanged";
}

TEST(SimActuator, ASimOfItsOwnModelIsReopenedForADeclaration) {
    SimActuator sim(SimSettings{});
    EXPECT_FALSE(
        sim.take_declaration(declared(actuator::Kind::lra, actuator::Brake::none).actuator));
}

TEST(SimActuator, WithoutADeclaredBrakeItHasNoReverse) {
    SimActuator sim(declared(actuator::Kind::erm, actuator::Brake::none));
    EXPECT_FALSE(sim.capabilities().reverse);
    sim.apply({-1.0, 0.0});
    EXPECT_EQ(sim.model().drive().amplitude, 0.0);
}

TEST(SimActuator, TraceRecordsEveryDriveAsSentReverseIncluded) {
    TempDir dir;
    FakeClock clock;
    SimSettings settings = declared(actuator::Kind::lra, actuator::Brake::reverse);
    settings.trace = dir.path() / "trace.csv";
    {
        SimActuator sim(settings, clock.function());
        sim.apply({1.0, 172.5});
        clock.now_ns += 20'000'000;
        sim.apply({-1.0, 172.5});
        clock.now_ns += 5'000'000;
        sim.off();
    }
    const auto lines = lines_of(*settings.trace);
    ASSERT_EQ(lines.size(), 4u);
    const TraceLine braking = parse(lines[2]);
    EXPECT_EQ(braking.amplitude, -1.0);
    EXPECT_EQ(braking.frequency_hz, 172.5);
    EXPECT_GT(braking.response, 0.5);
    EXPECT_EQ(parse(lines[3]).amplitude, 0.0);
}

TEST(SimActuator, TraceHasAHeaderAndOneLinePerCommand) {
    TempDir dir;
    FakeClock clock;
    SimSettings settings;
    settings.trace = dir.path() / "trace.csv";
    SimActuator sim(settings, clock.function());

    sim.apply({0.8, 175.0});
    clock.now_ns += 20'000'000;
    sim.apply({1.5, 350.0});  // clamped
    clock.now_ns += 10'000'000;
    sim.off();

    // Read while the actuator is still alive: every line is already in the file.
    const auto lines = lines_of(*settings.trace);
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], "time_ns,amplitude,frequency_hz,response");
    const TraceLine first = parse(lines[1]);
    const TraceLine second = parse(lines[2]);
    const TraceLine last = parse(lines[3]);

    EXPECT_EQ(first.time_ns, 1'000'000'000);
    EXPECT_EQ(second.time_ns, 1'020'000'000);
    EXPECT_EQ(last.time_ns, 1'030'000'000);
    EXPECT_LT(first.time_ns, second.time_ns);
    EXPECT_LT(second.time_ns, last.time_ns);

    EXPECT_EQ(first.amplitude, 0.8);
    EXPECT_EQ(first.frequency_hz, 175.0);
    EXPECT_EQ(first.response, 0.0);  // nothing moved before the first command

    // The undeclared sim's Q is the declaration's default, 15 (the sim's own was 8).
    const double tau = actuator::lra_time_constant_s(175.0, 15.0);
    EXPECT_EQ(second.amplitude, 1.0);
    EXPECT_EQ(second.frequency_hz, 350.0);
    EXPECT_NEAR(second.response, 0.8 * (1.0 - std::exp(-0.020 / tau)), 1e-12);

    EXPECT_EQ(last.amplitude, 0.0);
    EXPECT_EQ(last.frequency_hz, 0.0);
    EXPECT_NEAR(last.response, sim.model().response_at(1.030), 1e-15);
}

TEST(SimActuator, OffAfterApplyTracesAZeroLine) {
    TempDir dir;
    SimSettings settings;
    settings.trace = dir.path() / "t.csv";
    SimActuator sim(settings);
    sim.apply({0.6, 0.0});
    sim.off();
    const auto lines = lines_of(*settings.trace);
    ASSERT_EQ(lines.size(), 3u);
    const TraceLine on = parse(lines[1]);
    const TraceLine off = parse(lines[2]);
    EXPECT_EQ(off.amplitude, 0.0);
    EXPECT_LE(on.time_ns, off.time_ns);  // the real monotonic clock
}

// vibscored --safe-off after a crash, and the daemon restarted after it, open the trace again.
TEST(SimActuator, AnotherActuatorOnTheSameTraceAppendsKeepingTheRecordBeforeIt) {
    TempDir dir;
    SimSettings settings;
    settings.trace = dir.path() / "t.csv";
    {
        SimActuator crashed(settings);
        crashed.apply({0.6, 0.0});
    }
    SimActuator safe_off(settings);
    safe_off.off();
    const auto lines = lines_of(*settings.trace);
    ASSERT_EQ(lines.size(), 3u) << "one header, both runs' lines";
    EXPECT_EQ(lines[0], "time_ns,amplitude,frequency_hz,response");
    EXPECT_EQ(parse(lines[1]).amplitude, 0.6);
    EXPECT_EQ(parse(lines[2]).amplitude, 0.0);
    EXPECT_LE(parse(lines[1]).time_ns, parse(lines[2]).time_ns);
}

TEST(SimActuator, UnwritableTracePathThrowsNamingIt) {
    TempDir dir;
    SimSettings settings;
    settings.trace = dir.path() / "missing" / "trace.csv";
    try {
        SimActuator sim(settings);
        FAIL() << "no exception";
    } catch (const std::runtime_error& error) {
        EXPECT_THAT(error.what(), HasSubstr(settings.trace->string()));
        EXPECT_THAT(error.what(), HasSubstr("No such file or directory"));
    }
}

TEST(SimActuator, TraceWriteFailureThrowsFromApplyAndIsLoggedOnceFromOff) {
    // A FIFO whose reader has gone makes every write fail with EPIPE.
    TempDir dir;
    const auto fifo = dir.path() / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0);
    SimSettings settings;
    settings.trace = fifo;
    SimActuator sim(settings);
    ::close(reader);
    struct sigaction ignore {};
    struct sigaction previous {};
    ignore.sa_handler = SIG_IGN;
    ::sigaction(SIGPIPE, &ignore, &previous);

    try {
        sim.apply({0.5, 0.0});
        ADD_FAILURE() << "no exception";
    } catch (const DeviceError& error) {
        EXPECT_THAT(error.what(), HasSubstr(fifo.string()));
        EXPECT_THAT(error.what(), HasSubstr("Broken pipe"));
    }

    // Capture stderr, where vibscore::log writes, around two failing off() calls.
    const std::string log = pipe_output([&](int fd) {
        const int saved = ::dup(STDERR_FILENO);
        ::dup2(fd, STDERR_FILENO);
        sim.off();
        sim.off();
        ::dup2(saved, STDERR_FILENO);
        ::close(saved);
    });
    ::sigaction(SIGPIPE, &previous, nullptr);

    EXPECT_EQ(sim.command_count(), 3u);
    EXPECT_THAT(log, HasSubstr(fifo.string()));
    EXPECT_EQ(log.find(fifo.string()), log.rfind(fifo.string())) << log;
}

TEST(TerminalMeter, DrawsBarValueAndFrequencyInPlace) {
    const std::string text = pipe_output([](int fd) {
        TerminalMeter meter(fd, "sim lra", TerminalMeter::Glyphs::unicode);
        meter.show(0.5, 180.0);
        meter.show(1.0, 175.0);
    });
    EXPECT_THAT(text, HasSubstr("\rsim lra  ▕██████████          ▏ 0.50   180 Hz"));
    EXPECT_THAT(text, HasSubstr("\rsim lra  ▕████████████████████▏ 1.00   175 Hz"));
    EXPECT_EQ(text.back(), '\n');
}

TEST(TerminalMeter, AsciiFallbackAndPartialCells) {
    const TerminalMeter ascii(-1, "sim erm", TerminalMeter::Glyphs::ascii);
    EXPECT_EQ(ascii.line(0.25, -1.0), "sim erm  [#####               ] 0.25         ");
    const TerminalMeter unicode(-1, "sim lra", TerminalMeter::Glyphs::unicode);
    // 0.52 of 20 cells = 10.4 cells: ten full blocks and three eighths.
    EXPECT_THAT(unicode.line(0.52, 180.0), HasSubstr("▕██████████▍         ▏ 0.52   180 Hz"));
}

TEST(TerminalMeter, EveryLineHasTheSameWidthSoRedrawsOverwrite) {
    const TerminalMeter ascii(-1, "sim lra", TerminalMeter::Glyphs::ascii);
    EXPECT_EQ(ascii.line(0.0, 0.0).size(), ascii.line(1.0, 1000.0).size());
    EXPECT_EQ(ascii.line(0.3, -1.0).size(), ascii.line(1.0, 1000.0).size());
}

TEST(TerminalMeter, UnusedMeterWritesNothing) {
    const std::string text = pipe_output(
        [](int fd) { TerminalMeter meter(fd, "sim lra", TerminalMeter::Glyphs::unicode); });
    EXPECT_EQ(text, "");
}

TEST(SimActuator, MeterShowsWhereTheActuatorIsHeading) {
    const std::string text = pipe_output([](int fd) {
        SimSettings settings;
        settings.meter = true;
        settings.meter_fd = fd;
        SimActuator sim(settings);
        sim.apply({0.52, 0.0});
    });
    EXPECT_THAT(text, HasSubstr("sim lra"));
    EXPECT_THAT(text, HasSubstr(" 0.52   175 Hz"));
    EXPECT_TRUE(text.find("▕") != std::string::npos || text.find('[') != std::string::npos);
    EXPECT_EQ(text.back(), '\n');
}

// The undeclared sim is the declaration's defaults (issue 30: one set of numbers). It used to be
// Q 8 and an ERM spin-up of 50 ms, numbers of its own that [actuator] never defaulted to.
TEST(MakeSimActuator, DefaultsToAnLraWithTheDeclarationsNumbersWithoutTraceOrMeter) {
    const auto actuator = make_sim_actuator({});
    const auto& sim = dynamic_cast<const SimActuator&>(*actuator);
    const auto& model = sim.model().physics().declaration();
    const actuator::Declaration defaults;
    EXPECT_EQ(model.kind, actuator::Kind::lra);
    EXPECT_EQ(model.resonance_hz, defaults.resonance_hz);
    EXPECT_EQ(model.q, defaults.q);
    EXPECT_EQ(model.q, 15.0);
    EXPECT_EQ(model.rated_drive, 1.0);
    EXPECT_FALSE(sim.capabilities().reverse);
    const auto erm = make_sim_actuator({{"model", "erm"}});
    const auto& erm_model = dynamic_cast<const SimActuator&>(*erm).model().physics().declaration();
    EXPECT_EQ(erm_model.spin_up_s, defaults.spin_up_s);
    EXPECT_EQ(erm_model.spin_up_s, 0.040);
    EXPECT_EQ(erm_model.spin_down_s, defaults.spin_down_s);
}

// [sim]'s model keys are [actuator]'s: its limits, first value allowed and first refused.
TEST(MakeSimActuator, TheModelKeysHaveTheDeclarationsLimits) {
    const auto model_of = [](const std::map<std::string, std::string>& settings) {
        const auto made = make_sim_actuator(settings);
        return dynamic_cast<const SimActuator&>(*made).model().physics().declaration();
    };
    EXPECT_EQ(model_of({{"resonance-hz", "10"}}).resonance_hz, 10.0);
    EXPECT_EQ(model_of({{"resonance-hz", "1000"}}).resonance_hz, 1000.0);
    EXPECT_EQ(model_of({{"q", "1"}}).q, 1.0);
    EXPECT_EQ(model_of({{"q", "500"}}).q, 500.0);
    EXPECT_EQ(model_of({{"model", "erm"}, {"spin-up-ms", "1"}}).spin_up_s, 0.001);
    EXPECT_EQ(model_of({{"model", "erm"}, {"spin-down-ms", "10000"}}).spin_down_s, 10.0);
    for (const auto& [key, value] :
         std::vector<std::pair<std::string, std::string>>{{"resonance-hz", "9.99"},
                                                          {"resonance-hz", "1000.01"},
                                                          {"q", "0.99"},
                                                          {"q", "500.01"}}) {
        try {
            make_sim_actuator({{key, value}});
            ADD_FAILURE() << key << " = " << value << " accepted";
        } catch (const SettingError& error) {
            EXPECT_EQ(error.key(), key);
            EXPECT_THAT(error.what(),
                        HasSubstr(key + " = \"" + value + "\": expected a number from"));
        }
    }
    for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
             {"spin-up-ms", "0.99"}, {"spin-up-ms", "5000.01"}, {"spin-down-ms", "10000.01"}}) {
        EXPECT_THROW(make_sim_actuator({{"model", "erm"}, {key, value}}), SettingError) << key;
    }
}

TEST(MakeSimActuator, RefusesAKeyOfTheOtherModelAsTheDeclarationDoes) {
    try {
        make_sim_actuator({{"model", "erm"}, {"q", "12"}});
        FAIL();
    } catch (const SettingError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "sim setting q = \"12\" is for model = lra; this sim is model = erm");
    }
    EXPECT_THROW(make_sim_actuator({{"spin-up-ms", "40"}}), SettingError);
}

TEST(MakeSimActuator, SimulatesTheDeclaredActuatorAndRefusesASecondDeclaration) {
    actuator::Declaration board;
    board.kind = actuator::Kind::erm;
    board.spin_up_s = 0.033;
    board.brake = actuator::Brake::reverse;
    const auto actuator = make_sim_actuator({{"meter", "false"}}, board);
    const auto& sim = dynamic_cast<const SimActuator&>(*actuator);
    EXPECT_EQ(sim.model().physics().declaration(), board);
    EXPECT_TRUE(sim.capabilities().reverse);
    for (const char* key : {"model", "resonance-hz", "q", "spin-up-ms", "spin-down-ms"}) {
        try {
            make_sim_actuator({{key, "40"}}, board);
            ADD_FAILURE() << key << " accepted beside [actuator]";
        } catch (const SettingError& error) {
            EXPECT_EQ(error.key(), key);
            EXPECT_THAT(error.what(), HasSubstr(std::string(key) + " = \"40\""));
            EXPECT_THAT(error.what(), HasSubstr("declared in [actuator]"));
        }
    }
}

TEST(MakeSimActuator, ReadsEverySetting) {
    TempDir dir;
    const auto trace = dir.path() / "trace.csv";
    // An ERM's keys and an LRA's in two sims: a key of the other model is refused (above).
    const auto actuator = make_sim_actuator({{"model", "erm"},
                                             {"spin-up-ms", "35"},
                                             {"spin-down-ms", "120"},
                                             {"trace", trace.string()},
                                             {"meter", "false"}});
    const auto& model = dynamic_cast<const SimActuator&>(*actuator).model().physics().declaration();
    EXPECT_EQ(model.kind, actuator::Kind::erm);
    EXPECT_DOUBLE_EQ(model.spin_up_s, 0.035);
    EXPECT_DOUBLE_EQ(model.spin_down_s, 0.120);
    EXPECT_TRUE(std::filesystem::exists(trace));
    const auto lra = make_sim_actuator({{"model", "lra"}, {"resonance-hz", "205.5"}, {"q", "12"}});
    const auto& lra_model = dynamic_cast<const SimActuator&>(*lra).model().physics().declaration();
    EXPECT_EQ(lra_model.resonance_hz, 205.5);
    EXPECT_EQ(lra_model.q, 12.0);
}

TEST(MakeSimActuator, RejectsBadValuesNamingKeyAndValue) {
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"model", "piezo"}, {"resonance-hz", "abc"}, {"resonance-hz", "-175"}, {"q", "0"},
        {"q", "8x"},        {"spin-up-ms", ""},      {"spin-down-ms", "inf"},  {"meter", "yes"},
        {"trace", ""},      {"colour", "blue"},
    };
    for (const auto& [key, value] : bad) {
        try {
            make_sim_actuator({{key, value}});
            ADD_FAILURE() << key << " = " << value << " accepted";
        } catch (const std::invalid_argument& error) {
            EXPECT_THAT(error.what(), HasSubstr(key)) << error.what();
            EXPECT_THAT(error.what(), HasSubstr("\"" + value + "\"")) << error.what();
        }
    }
}

TEST(MakeSimActuator, UnwritableTraceNamesThePath) {
    TempDir dir;
    const auto trace = dir.path() / "no" / "such" / "dir.csv";
    EXPECT_THAT(
        [&] {
            make_sim_actuator({{"trace", trace.string()}});
        },
        ::testing::ThrowsMessage<std::runtime_error>(HasSubstr(trace.string())));
}

}  // namespace
}  // namespace vibscore::drivers
