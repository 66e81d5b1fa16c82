// The command line keeps the README's promises, run as a new user runs it: the exit status and
// message of each wrong usage, one rule for how a score names its clefs in check and play (both
// ways), and every command the README shows, verbatim, against the real daemon on a private bus.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <thread>

#include "client/editor/documents.hpp"
#include "client/editor/editor_model.hpp"
#include "score/score_xml.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;

std::vector<std::string> command(const char* program_env, std::vector<std::string> args) {
    args.insert(args.begin(), testing::required_env(program_env));
    return args;
}

struct WrongUsage {
    const char* program;  // the environment variable holding its path
    std::vector<std::string> args;
    int status;
    std::string message;  // a line of standard error
};

TEST(WrongUsage, EachEndsWithTheReadmesStatusAndAMessageNamingWhatIsWrong) {
    const std::vector<WrongUsage> table = {
        {"VIBSCORED",
         {"--bogus"},
         2,
         "vibscored: The following argument was not expected: --bogus"},
        {"VIBSCORED", {"extra"}, 2, "vibscored: The following argument was not expected: extra"},
        {"VIBSCORED",
         {"--config", "/nonexistent.conf"},
         1,
         "/nonexistent.conf: cannot open: No such file or directory"},
        {"VIBSCORE", {}, 2, "vibscore: a command is required (see --help for the commands)"},
        {"VIBSCORE", {"--bogus"}, 2, "vibscore: unknown option --bogus"},
        {"VIBSCORE",
         {"frobnicate"},
         2,
         "vibscore: unknown command \"frobnicate\"; the commands are: check render convert clef "
         "info "
         "play stop "
         "list get compose delete drivers driver show assign calibrate edit"},
        {"VIBSCORE",
         {"lsit"},
         2,
         "vibscore: unknown command \"lsit\" (did you mean list?); the commands are: check render "
         "convert "
         "clef info play stop list get compose delete drivers driver show assign calibrate edit"},
        {"VIBSCORE",
         {"play", "x", "--usage", "bogus"},
         2,
         "vibscore: --usage: bogus not in {ringtone,alarm,notification,communication,"
         "accessibility,hardware-feedback,touch,media}"},
        {"VIBSCORE",
         {"play", "x", "--repeat", "-5"},
         2,
         "vibscore: --repeat: -5 is out of range (-1 to 2147483647)"},
        {"VIBSCORE",
         {"play", "x", "--repeat", "1.5"},
         2,
         "vibscore: --repeat: not a whole number: 1.5"},
        {"VIBSCORE",
         {"play", "x", "--intensity", "2"},
         2,
         "vibscore: --intensity: 2 is out of range (0 to 1)"},
        {"VIBSCORE", {"render", "f", "--rate", "abc"}, 2, "vibscore: --rate: not a number: abc"},
        {"VIBSCORE",
         {"render", "f", "--width", "5"},
         2,
         "vibscore: --width: 5 is out of range (10 to 1000)"},
        {"VIBSCORE", {"list", "foo"}, 2, "vibscore: KIND: foo not in {score,scores,clef,clefs}"},
        {"VIBSCORE",
         {"get", "sco", "x"},
         2,
         "vibscore: KIND: sco not in {score,scores,clef,clefs}"},
        {"VIBSCORE", {"stop", "abc"}, 2, "vibscore: ID: not a number: abc"},
        {"VIBSCORE", {"stop", "0"}, 2, "vibscore: ID: 0 is out of range (1 or more)"},
        {"VIBSCORE", {"check"}, 2, "vibscore: FILE is required"},
        // An empty actuator name is refused, not read as a declaration that is not there.
        {"VIBSCORE",
         {"clef", "fit", "lra-phone", "--actuator", ""},
         2,
         "vibscore: clef fit: --actuator needs a file or 'daemon', not an empty name"},
        {"VIBSCORE",
         {"check", "--clefs", "/nonexistent", "f.xml"},
         2,
         "vibscore: --clefs: Directory does not exist: /nonexistent"},
        // Not usage errors: the file is missing, said the same way by both verbs.
        {"VIBSCORE",
         {"play", "nope.score.xml"},
         1,
         "nope.score.xml: cannot open: No such file or directory"},
        {"VIBSCORE",
         {"show", "nope.score.xml"},
         1,
         "nope.score.xml: cannot open: No such file or directory"},
    };
    setenv("DBUS_SYSTEM_BUS_ADDRESS", "unix:path=/nonexistent/bus", 1);
    for (const auto& usage : table) {
        const auto result = testing::run_command(command(usage.program, usage.args));
        std::string shown = usage.program;
        for (const auto& arg : usage.args) {
            shown += " " + arg;
        }
        EXPECT_EQ(result.exit_code, usage.status) << shown << "\n" << result.err;
        EXPECT_THAT(result.err, HasSubstr(usage.message + "\n")) << shown;
    }
}

TEST(WrongUsage, EveryProgramAndVerbHasHelpEndingInSuccess) {
    for (const char* verb : {"check", "render", "info", "play", "stop", "list", "get", "compose",
                             "delete", "drivers", "driver", "show", "edit"}) {
        const auto result = testing::run_command(command("VIBSCORE", {verb, "--help"}));
        EXPECT_EQ(result.exit_code, 0) << verb;
        EXPECT_THAT(result.out, HasSubstr("Usage:")) << verb;
    }
    EXPECT_EQ(testing::run_command(command("VIBSCORE", {"--help"})).exit_code, 0);
    EXPECT_EQ(testing::run_command(command("VIBSCORED", {"--help"})).exit_code, 0);
    const std::filesystem::path source = testing::required_env("VIBSCORE_SOURCE_ROOT");
    const auto vm_run = testing::run_command({(source / "tests/hil/vm-run").string(), "--help"});
    EXPECT_EQ(vm_run.exit_code, 0) << vm_run.err;
    EXPECT_THAT(vm_run.out, HasSubstr("usage: vm-run"));
}

// A score in a folder of its own, with the daemon's shipped lra-phone clef under clefs/.
class ClefRule : public ::testing::Test {
  protected:
    ClefRule() {
        std::filesystem::create_directories(work.path() / "scores");
        std::filesystem::create_directories(work.path() / "clefs");
        std::filesystem::copy_file(shipped / "lra-phone.clef.xml",
                                   work.path() / "clefs" / "lra-phone.clef.xml");
    }

    testing::CommandResult vibscore(std::vector<std::string> args) const {
        setenv("DBUS_SYSTEM_BUS_ADDRESS", daemon.bus_address().c_str(), 1);
        return testing::run_command(command("VIBSCORE", std::move(args)));
    }

    // check and play agree: both accept the file, and it plays to its end on the actuator.
    void expect_checks_and_plays(const std::filesystem::path& file) const {
        const auto checked = vibscore({"check", file.string()});
        EXPECT_EQ(checked.exit_code, 0) << checked.err;
        const auto played = vibscore({"play", file.string(), "--wait"});
        EXPECT_EQ(played.exit_code, 0) << played.err;
        EXPECT_THAT(played.out, HasSubstr(" completed\n"));
    }

    const std::filesystem::path shipped{testing::required_env("VIBSCORE_CLEFS")};
    DaemonFixture daemon;
    testing::TempDir work{};
    const std::string bar =
        "<Bar clef=\"l\"><Note length=\"8th\" number=\"9\" string=\"6\"/></Bar>";
};

TEST_F(ClefRule, AFileWrittenByTheEditorChecksAndPlays) {
    Score score = editor::EditorModel::blank_score("mine", {"lra-phone", "lra-phone.clef.xml"});
    score.bars = {read_score("<VibScore><Clef id=\"lra-phone\" href=\"x\"/><Bar clef=\"lra-phone\">"
                             "<Note length=\"8th\" number=\"9\" string=\"6\"/></Bar></VibScore>",
                             "bar")
                      .score.bars};
    const auto file = work.path() / "scores" / "mine.score.xml";
    editor::write_score_file(file, score);
    expect_checks_and_plays(file);
    const auto info = vibscore({"info", file.string()});
    EXPECT_THAT(info.out, HasSubstr("from registry")) << info.out;
    EXPECT_EQ(vibscore({"compose", "mine", file.string()}).exit_code, 0);

    // Without a daemon the offline verbs find it in a clefs folder given with --clefs.
    setenv("DBUS_SYSTEM_BUS_ADDRESS", "unix:path=/nonexistent/bus", 1);
    const auto offline = testing::run_command(
        command("VIBSCORE", {"check", "--clefs", (work.path() / "clefs").string(), file.string()}));
    EXPECT_EQ(offline.exit_code, 0) << offline.err;
}

TEST_F(ClefRule, AFileNamingItsClefByARelativePathChecksPlaysAndComposes) {
    const auto file = work.path() / "scores" / "relative.score.xml";
    std::ofstream(file) << "<VibScore><Title>r</Title><Clef id=\"l\" "
                           "href=\"../clefs/lra-phone.clef.xml\"/>" +
                               bar + "</VibScore>";
    expect_checks_and_plays(file);
    const auto composed = vibscore({"compose", "relative", file.string()});
    EXPECT_EQ(composed.exit_code, 0) << composed.err;
    const auto stored = vibscore({"get", "score", "relative"});
    EXPECT_THAT(stored.out, HasSubstr("href=\"lra-phone.clef.xml\"")) << stored.out;
}

TEST_F(ClefRule, AClefFileOfItsOwnIsSentWithThePlayButComposeAsksToStoreItFirst) {
    std::string clef = testing::read_file(work.path() / "clefs" / "lra-phone.clef.xml");
    // Not std::regex: GCC 12 warns maybe-uninitialized inside it under -O2 with sanitizers.
    const auto open = clef.find("<Tempo>");
    const auto close = clef.find("</Tempo>", open);
    ASSERT_NE(close, std::string::npos) << clef;
    clef.replace(open, close - open, "<Tempo>0.3");
    std::ofstream(work.path() / "clefs" / "slower.clef.xml") << clef;
    const auto file = work.path() / "scores" / "own.score.xml";
    std::ofstream(file) << "<VibScore><Clef id=\"l\" href=\"../clefs/slower.clef.xml\"/>" + bar +
                               "</VibScore>";
    expect_checks_and_plays(file);
    const auto composed = vibscore({"compose", "own", file.string()});
    EXPECT_EQ(composed.exit_code, 1);
    EXPECT_THAT(composed.err, HasSubstr("the registry has no clef \"slower\"; store it first: "
                                        "vibscore compose slower"));
}

// Issue 25: with a daemon running, convert finds its clef as check does (the registry holds
// lra-phone), names it by its registry name, and what it wrote checks and plays.
TEST_F(ClefRule, AnImportFindsItsClefInTheRegistryAndNamesItSo) {
    const auto pulse = work.path() / "pulse.json";
    std::ofstream(pulse) << R"({"timings": [0, 200, 200, 200]})";
    const auto file = work.path() / "scores" / "pulse.score.xml";
    const auto converted = vibscore({"convert", pulse.string(), file.string()});
    ASSERT_EQ(converted.exit_code, 0) << converted.err;
    EXPECT_THAT(converted.out, HasSubstr(" on clef lra-phone from vibscored's registry\n"));
    EXPECT_THAT(testing::read_file(file), HasSubstr("href=\"lra-phone.clef.xml\""));
    expect_checks_and_plays(file);
}

TEST_F(ClefRule, AFileFetchedWithGetChecksAndPlays) {
    const auto fetched = vibscore({"get", "score", "notification-message"});
    ASSERT_EQ(fetched.exit_code, 0) << fetched.err;
    const auto file = work.path() / "fetched.score.xml";
    std::ofstream(file) << fetched.out;
    expect_checks_and_plays(file);
}

TEST_F(ClefRule, AFileThatFailsCheckFailsPlayWithTheSameMessage) {
    const auto file = work.path() / "scores" / "unknown.score.xml";
    std::ofstream(file) << "<VibScore><Clef id=\"l\" href=\"no-such.clef.xml\"/>" + bar +
                               "</VibScore>";
    const auto checked = vibscore({"check", file.string()});
    const auto played = vibscore({"play", file.string()});
    EXPECT_EQ(checked.exit_code, 1);
    EXPECT_EQ(played.exit_code, 1);
    EXPECT_THAT(played.err, HasSubstr("no clef \"no-such\" in vibscored's registry"));
    EXPECT_THAT(checked.err, HasSubstr(played.err));
}

TEST_F(ClefRule, StopSaysWhetherAnythingOfYoursWasPlaying) {
    const auto idle = vibscore({"stop"});
    EXPECT_EQ(idle.exit_code, 0) << idle.err;
    EXPECT_EQ(idle.out, "none of your playbacks was playing\n");
    // A repeating playback lasts as long as its caller stays: one waits in the background.
    const auto output = work.path() / "playing.out";
    testing::Process playing(command("VIBSCORE", {"play", "ringtone", "--repeat", "-1", "--wait"}),
                             output);
    testing::wait_until_file_contains(output, "bar 1");
    const auto stopped = vibscore({"stop"});
    EXPECT_EQ(stopped.out, "stopped your playback\n");
    EXPECT_EQ(playing.wait(), 0);
    EXPECT_THAT(testing::read_file(output), HasSubstr(" stopped\n"));
}

// The README's command lines (backslash continuations joined), from its ```sh blocks.
std::vector<std::string> readme_commands(const std::filesystem::path& readme) {
    std::ifstream in(readme);
    std::vector<std::string> commands;
    std::string line, pending;
    bool in_block = false;
    while (std::getline(in, line)) {
        if (line.starts_with("```")) {
            in_block = line == "```sh";
            continue;
        }
        if (!in_block || line.empty()) {
            continue;
        }
        if (line.ends_with("\\")) {
            pending += line.substr(0, line.size() - 1);
            continue;
        }
        commands.push_back(pending + line);
        pending.clear();
    }
    return commands;
}

// A folder where the README's commands run as in a checkout: its clefs/ and examples/, ./dev,
// a fresh docs/pictures/ (the picture commands must not rewrite the committed pictures), and a
// build/ whose entries are the build tree's but for run/, so that `./dev daemon` keeps its
// private service here, not in the build tree where a developer's may run.
class ReadmeCheckout {
  public:
    ReadmeCheckout() {
        for (const char* entry : {"clefs", "examples", "dev"}) {
            std::filesystem::create_symlink(source / entry, dir.path() / entry);
        }
        std::filesystem::create_directories(dir.path() / "docs" / "pictures");
        std::filesystem::create_directories(dir.path() / "build");
        for (const auto& entry : std::filesystem::directory_iterator(built)) {
            if (entry.path().filename() != "run") {
                std::filesystem::create_symlink(entry.path(),
                                                dir.path() / "build" / entry.path().filename());
            }
        }
    }
    // Whatever happened, the private daemon of `./dev daemon --background` ends with the test.
    ~ReadmeCheckout() { testing::run_command({"/bin/bash", "-c", shell("./dev daemon --stop")}); }

    // `line` as a user types it in the checkout, after the README's `export` lines so far. No
    // build folder on PATH: the commands must work as written. VIBSCORE_BUILD_DIR makes ./dev
    // use the build tree as it is (the test run built it; nothing is installed).
    std::string shell(const std::string& line) const {
        return "cd " + path().string() + " && export PATH=/usr/bin:/bin HOME=" + path().string() +
               " COLUMNS=80 VIBSCORE_BUILD_DIR=" + (path() / "build").string() +
               " DBUS_SYSTEM_BUS_ADDRESS=unix:path=/nonexistent/bus && " + exports + line;
    }
    const std::filesystem::path& path() const { return dir.path(); }

    const std::filesystem::path source = testing::required_env("VIBSCORE_SOURCE_ROOT");
    const std::filesystem::path built = testing::required_env("VIBSCORE_BUILD_ROOT");
    testing::TempDir dir;
    std::string exports;  // the README's export lines so far, each followed by " && "
};

TEST(Readme, EveryCommandItShowsWorksVerbatim) {
    ReadmeCheckout checkout;
    // Not run here, each for its reason: the test run is `./dev test` (or the by-hand build)
    // itself; `./dev run` is the interactive demo; the editor is driven in tmux by editor_e2e;
    // the packages are built by suite package (tests/package/build-debs, as `./dev package`) and
    // installed with apt under systemd by suite hil-systemd, in a Debian 12 guest, not here.
    const std::vector<std::string> run_elsewhere = {
        "./dev run", "./dev test", "meson setup build && ninja -C build && meson test -C build",
        "./dev package          # build/debs: vibscored, vibscore, vibscore-feedback, vibscore-dev",
        "sudo apt install ./build/debs/vibscored_*.deb ./build/debs/vibscore_*.deb"};
    const auto bus = checkout.path() / "build" / "run" / "bus";

    int ran = 0;
    bool daemon_started = false, daemon_stopped = false;
    for (const auto& line : readme_commands(checkout.source / "README.md")) {
        if (std::find(run_elsewhere.begin(), run_elsewhere.end(), line) != run_elsewhere.end() ||
            line.starts_with("build/client/vibscore edit ")) {
            continue;
        }
        ++ran;
        if (line.starts_with("export ")) {
            checkout.exports += line + " && ";
            const auto exported = testing::run_command(
                {"/bin/bash", "-c", checkout.shell("echo $DBUS_SYSTEM_BUS_ADDRESS")});
            EXPECT_EQ(exported.out, "unix:path=" + bus.string() + "\n") << line;
            continue;
        }
        if (line.find("--repeat -1 --wait") != std::string::npos) {
            // "Ctrl-C stops it": it plays until interrupted, then says so and succeeds.
            const auto output = checkout.path() / "interrupted.out";
            testing::Process playing({"/bin/bash", "-c", checkout.shell("exec " + line)}, output);
            testing::wait_until_file_contains(output, "bar 1");
            playing.signal(SIGINT);
            EXPECT_EQ(playing.wait(), 0) << line << "\n" << testing::read_file(output);
            EXPECT_THAT(testing::read_file(output), HasSubstr(" stopped\n")) << line;
            continue;
        }
        const auto result = testing::run_command({"/bin/bash", "-c", checkout.shell(line)});
        EXPECT_EQ(result.exit_code, 0) << line << "\n" << result.out << result.err;
        if (line.starts_with("./dev daemon --background")) {
            // It prints the one line to paste, and the README's next line is that line.
            daemon_started = true;
            EXPECT_EQ(result.out,
                      "export DBUS_SYSTEM_BUS_ADDRESS=unix:path=" + bus.string() + "\n");
            EXPECT_TRUE(std::filesystem::exists(bus)) << result.err;
        }
        if (line.starts_with("build/client/vibscore list scores")) {
            // The daemon from the build tree found the checkout's shipped scores by itself.
            EXPECT_THAT(result.out, HasSubstr("ringtone\t")) << result.err;
        }
        if (line == "./dev daemon --stop") {
            daemon_stopped = true;
            EXPECT_FALSE(
                std::filesystem::exists(checkout.path() / "build" / "run" / "vibscored.pid"));
            const auto after = testing::run_command(
                {"/bin/bash", "-c", checkout.shell("build/client/vibscore list scores")});
            EXPECT_EQ(after.exit_code, 1) << after.out;
        }
    }
    EXPECT_TRUE(daemon_started);
    EXPECT_TRUE(daemon_stopped);
    EXPECT_GE(ran, 30);
}

// `./dev man PAGE` shows the page as the packages install it: meson's filled copy in build/man/,
// no @VERSION@ or @CLEFDIR@ left; a page that is not there is named with the ones that are.
TEST(DevMan, ShowsTheFilledPageFromTheBuildTree) {
    ReadmeCheckout checkout;
    const auto shown =
        testing::run_command({"/bin/bash", "-c", checkout.shell("MANWIDTH=80 ./dev man vibscore")});
    ASSERT_EQ(shown.exit_code, 0) << shown.err;
    EXPECT_THAT(shown.out, HasSubstr("clef fit CLEF"));
    EXPECT_THAT(shown.out, ::testing::Not(HasSubstr("@VERSION@")));
    EXPECT_THAT(shown.out, ::testing::Not(HasSubstr("@CLEFDIR@")));
    const auto conf = testing::run_command(
        {"/bin/bash", "-c", checkout.shell("MANWIDTH=80 ./dev man vibscored.conf")});
    EXPECT_EQ(conf.exit_code, 0) << conf.err;
    const auto missing =
        testing::run_command({"/bin/bash", "-c", checkout.shell("./dev man vibscoer")});
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_THAT(missing.err, HasSubstr("no page vibscoer in "));
    EXPECT_THAT(missing.err, HasSubstr(" vibscored.conf "));
}

// The private daemon of ./dev keeps a person's own settings: an [actuator] declared in
// build/run/local.conf lasts across restarts (./dev never rewrites that file), wins over what ./dev
// writes itself (no clash with the sim's own model), and `./dev daemon --reload` applies an edit.
TEST(DevDaemon, KeepsTheDeclarationInLocalConfAcrossRestartsAndReloads) {
    ReadmeCheckout checkout;
    const auto run = [&](const std::string& line) {
        return testing::run_command({"/bin/bash", "-c", checkout.shell(line)});
    };
    const auto local = checkout.path() / "build" / "run" / "local.conf";
    const auto bus = "DBUS_SYSTEM_BUS_ADDRESS=unix:path=" +
                     (checkout.path() / "build" / "run" / "bus").string() + " ";
    const auto driver = [&] { return run(bus + "build/client/vibscore driver").out; };

    // The first start makes a commented local.conf that declares nothing.
    ASSERT_EQ(run("./dev daemon --background").exit_code, 0);
    ASSERT_TRUE(std::filesystem::exists(local));
    EXPECT_THAT(driver(), HasSubstr("actuator: none declared"));
    ASSERT_EQ(run("./dev daemon --stop").exit_code, 0);

    { std::ofstream(local, std::ios::app) << "[actuator]\nkind = lra\nresonance-hz = 170\n"; }
    const auto started = run("./dev daemon --background");
    ASSERT_EQ(started.exit_code, 0) << started.err;
    EXPECT_THAT(driver(), HasSubstr("actuator: lra: resonance 170 Hz"))
        << testing::read_file(checkout.path() / "build" / "run" / "vibscored.log");
    ASSERT_EQ(run("./dev daemon --stop").exit_code, 0);
    ASSERT_EQ(run("./dev daemon --background").exit_code, 0);
    EXPECT_THAT(driver(), HasSubstr("actuator: lra: resonance 170 Hz"))
        << "a restart lost the declaration";
    EXPECT_THAT(testing::read_file(local), HasSubstr("resonance-hz = 170"));

    // An edit, then --reload: the running daemon takes it.
    std::string text = testing::read_file(local);
    text.replace(text.rfind("resonance-hz = 170"), 18, "resonance-hz = 165");
    std::ofstream(local) << text;
    const auto reload = run("./dev daemon --reload");
    EXPECT_EQ(reload.exit_code, 0) << reload.err;
    EXPECT_TRUE(testing::wait_until([&] {
        return driver().find("actuator: lra: resonance 165 Hz") != std::string::npos;
    })) << driver();

    // A line that is not `key = value` is named with the user's file and line, not ./dev's.
    std::ofstream(local, std::ios::app) << "resonance\n";
    const auto bad = run("./dev daemon --reload");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_THAT(bad.err, HasSubstr(local.string() + ":"));
    EXPECT_THAT(bad.err, HasSubstr("'resonance' is not 'key = value'"));
}

// ./dev daemon also runs vibscore-feedback (the feedbackd API) on a private session bus, with the
// checkout's theme (a build-tree program finds its checkout's), and says how to point fbcli at it;
// an event triggered there reaches the private vibscored's actuator.
TEST(DevDaemon, RunsTheFeedbackServiceBesideItWithTheCheckoutsTheme) {
    ReadmeCheckout checkout;
    const auto run = [&](const std::string& line) {
        return testing::run_command({"/bin/bash", "-c", checkout.shell(line)});
    };
    const auto started = run("./dev daemon --background");
    ASSERT_EQ(started.exit_code, 0) << started.err;
    const auto session = checkout.path() / "build" / "run" / "session-bus";
    EXPECT_THAT(started.err,
                HasSubstr("export DBUS_SESSION_BUS_ADDRESS=unix:path=" + session.string() + "\n"));
    EXPECT_THAT(testing::read_file(checkout.path() / "build" / "run" / "feedback.log"),
                HasSubstr("/feedback/themes/default.json"));

    const auto trace = checkout.path() / "build" / "run" / "trace.csv";
    const auto triggered =
        run("busctl --address=unix:path=" + session.string() +
            " -- call org.sigxcpu.Feedback /org/sigxcpu/Feedback org.sigxcpu.Feedback "
            "TriggerFeedback 'ssa{sv}i' org.example.test phone-incoming-call 0 -1");
    EXPECT_EQ(triggered.exit_code, 0) << triggered.err;
    // The ringtone drives the sim: a row with a non-zero amplitude appears in the trace.
    EXPECT_TRUE(testing::wait_until([&] {
        const auto text = testing::read_file(trace);
        std::istringstream rows(text);
        std::string row;
        while (std::getline(rows, row)) {
            const auto comma = row.find(',');
            if (comma != std::string::npos && row.compare(comma, 3, ",0,") != 0 &&
                row.find("amplitude") == std::string::npos) {
                return true;
            }
        }
        return false;
    })) << testing::read_file(trace);
    ASSERT_EQ(run("./dev daemon --stop").exit_code, 0);
    EXPECT_FALSE(std::filesystem::exists(checkout.path() / "build" / "run" / "feedback.pid"));
}

// `vibscore list` with nothing to list says so, and where the daemon looked.
TEST(Readme, AnEmptyListSaysWhereTheDaemonLooked) {
    testing::TempDir dir;
    std::filesystem::create_directories(dir.path() / "shipped");
    std::filesystem::copy_file(
        std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) / "lra-phone.clef.xml",
        dir.path() / "shipped" / "lra-phone.clef.xml");
    DaemonFixture daemon{"shipped = " + (dir.path() / "shipped").string()};
    const auto scores = testing::run_command(command("VIBSCORE", {"list", "scores"}));
    EXPECT_EQ(scores.exit_code, 0) << scores.err;
    EXPECT_EQ(scores.out, "");
    EXPECT_EQ(scores.err, "vibscore: vibscored has no scores: none shipped in " +
                              (dir.path() / "shipped").string() +
                              " (shipped = in vibscored.conf) and none composed in " +
                              daemon.store().string() + " (store =)\n");
    const auto clefs = testing::run_command(command("VIBSCORE", {"list", "clef"}));
    EXPECT_EQ(clefs.out, "lra-phone\tsine, tempo 0.2 s, 6 strings\n");
    EXPECT_EQ(clefs.err, "");
}

}  // namespace
}  // namespace vibscore
