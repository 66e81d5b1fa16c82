// Driver modules as vibscored finds them: who may have put them there (module_trust), what they
// do while loading (module_probe: in a child, with a time limit), and the catalog that lists
// them without loading them again. The modules are built by the tests
// (tests/support/modules/misbehaving_driver.c) and copied into a directory of each test's own.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>

#include "common/monotonic_clock.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/drivers/module_catalog.hpp"
#include "daemon/drivers/module_probe.hpp"
#include "daemon/drivers/module_trust.hpp"
#include "tests/support/crash_signal.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"
#include "tests/support/test_modules.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::AnyOf;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using testing::TempDir;

constexpr uid_t kNobody = 65534;

using testing::ModulesDir;

// The modules at `paths`, opened as the scan opens them.
std::vector<TrustedFile> opened(const std::vector<std::filesystem::path>& paths) {
    std::vector<TrustedFile> files;
    for (const auto& path : paths) {
        auto file = open_trusted_module(path, ::geteuid());
        EXPECT_TRUE(file.file) << file.refusal;
        if (file.file) {
            files.push_back(std::move(*file.file));
        }
    }
    return files;
}

bool running_as_root() {
    return ::geteuid() == 0;
}

std::vector<std::string> names_of(const ModuleCatalog& catalog) {
    std::vector<std::string> names;
    for (const auto& module : catalog.modules()) {
        names.push_back(module.name);
    }
    return names;
}

std::string refusal_of(const ModuleCatalog& catalog, const std::filesystem::path& path) {
    for (const auto& refused : catalog.refused()) {
        if (refused.path == path) {
            return refused.reason;
        }
    }
    return "<not refused>";
}

// ---- who may have put a module there

TEST(ModuleTrust, AModuleOfRootOrTheDaemonsUserNobodyElseMayWriteIsTrusted) {
    ModulesDir dir;
    const auto module = dir.add("counted");
    EXPECT_EQ(untrusted_module(module, ::geteuid()), std::nullopt);
    EXPECT_EQ(untrusted_directory(dir.path(), ::geteuid()), std::nullopt)
        << "under /tmp, which is sticky";
}

TEST(ModuleTrust, AModuleOthersMayWriteIsRefusedNamingItsMode) {
    ModulesDir dir;
    const auto module = dir.add("counted");
    std::filesystem::permissions(module, std::filesystem::perms(0757));
    EXPECT_EQ(untrusted_module(module, ::geteuid()),
              module.string() + " is writable by group or others (mode 0757)");
    std::filesystem::permissions(module, std::filesystem::perms(0775));
    EXPECT_THAT(untrusted_module(module, ::geteuid()).value_or(""), HasSubstr("(mode 0775)"));
    std::filesystem::permissions(module, std::filesystem::perms(0755));
    EXPECT_EQ(untrusted_module(module, ::geteuid()), std::nullopt);
}

TEST(ModuleTrust, AModuleOwnedByAnotherUserIsRefusedUnlessItIsTheDaemonsUser) {
    if (!running_as_root()) {
        GTEST_SKIP() << "giving a file to another user takes root";
    }
    ModulesDir dir;
    const auto module = dir.add("counted");
    ASSERT_EQ(::chown(module.c_str(), kNobody, kNobody), 0);
    EXPECT_EQ(
        untrusted_module(module, 0),
        module.string() + " is owned by uid 65534, neither root nor the daemon's user (uid 0)");
    EXPECT_EQ(untrusted_module(module, kNobody), std::nullopt) << "the daemon's own user";
}

TEST(ModuleTrust, ADirectoryOthersMayWriteIsRefusedEvenIfSticky) {
    ModulesDir dir;
    std::filesystem::permissions(dir.path(), std::filesystem::perms(01777));
    EXPECT_EQ(untrusted_directory(dir.path(), ::geteuid()),
              dir.path().string() + " is writable by group or others (mode 1777)");
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0755));
    EXPECT_EQ(untrusted_directory(dir.path(), ::geteuid()), std::nullopt);
}

TEST(ModuleTrust, ADirectoryAboveThatOthersMayWriteIsRefusedUnlessSticky) {
    ModulesDir dir;
    const auto inner = dir.path() / "drivers";
    std::filesystem::create_directory(inner);
    std::filesystem::permissions(inner, std::filesystem::perms(0755));
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0777));
    EXPECT_EQ(untrusted_directory(inner, ::geteuid()),
              dir.path().string() + " is writable by group or others (mode 0777)")
        << "anyone could rename drivers/ and put another in its place";
    std::filesystem::permissions(dir.path(), std::filesystem::perms(01777));
    EXPECT_EQ(untrusted_directory(inner, ::geteuid()), std::nullopt);
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0755));
}

TEST(ModuleTrust, AGroupWritableDirectoryOnTheWayIsRefusedAndOneThatIsNotIsTrusted) {
    ModulesDir dir;
    const auto inner = dir.path() / "drivers";
    std::filesystem::create_directory(inner);
    std::filesystem::permissions(inner, std::filesystem::perms(0755));
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0775));
    EXPECT_EQ(untrusted_directory(inner, ::geteuid()),
              dir.path().string() + " is writable by group or others (mode 0775)");
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0755));
    EXPECT_EQ(untrusted_directory(inner, ::geteuid()), std::nullopt);
}

TEST(ModuleTrust, ASymlinkThatLeavesTheDriversDirectoryIsRefusedNamingTheLink) {
    ModulesDir dir;
    ModulesDir elsewhere;
    const auto real = elsewhere.add("counted");
    std::filesystem::create_symlink(real, dir.path() / "good.so");
    EXPECT_EQ(untrusted_module(dir.path() / "good.so", ::geteuid()),
              (dir.path() / "good.so").string() + " -> " + real.string() +
                  " leads out of the drivers directory " + dir.path().string() +
                  " (a link there may only name a file below it)")
        << "even to a file that would be trusted: what it names can be re-pointed";
    std::filesystem::create_symlink("../" + elsewhere.path().filename().string() + "/counted.so",
                                    dir.path() / "up.so");
    EXPECT_THAT(untrusted_module(dir.path() / "up.so", ::geteuid()).value_or(""),
                HasSubstr("up.so -> ../"));
}

TEST(ModuleTrust, ASymlinkToAFileBelowTheDriversDirectoryIsFollowedOnce) {
    ModulesDir dir;
    dir.add("counted", "counted.so.2");
    std::filesystem::create_symlink("counted.so.2", dir.path() / "counted.so");
    EXPECT_EQ(untrusted_module(dir.path() / "counted.so", ::geteuid()), std::nullopt);
    std::filesystem::create_directory(dir.path() / "v2");
    std::filesystem::permissions(dir.path() / "v2", std::filesystem::perms(0755));
    std::filesystem::copy_file(dir.path() / "counted.so.2", dir.path() / "v2" / "counted.so");
    std::filesystem::create_symlink("v2/counted.so", dir.path() / "sub.so");
    EXPECT_EQ(untrusted_module(dir.path() / "sub.so", ::geteuid()), std::nullopt);
    // The last mode allowed and the first refused of a directory below.
    std::filesystem::permissions(dir.path() / "v2", std::filesystem::perms(0775));
    EXPECT_EQ(untrusted_module(dir.path() / "sub.so", ::geteuid()),
              (dir.path() / "sub.so").string() + " -> v2/counted.so: " +
                  (dir.path() / "v2").string() + " is writable by group or others (mode 0775)");
    std::filesystem::permissions(dir.path() / "v2", std::filesystem::perms(0755));
    // A link to a link is not followed: the second could lead anywhere.
    std::filesystem::create_symlink("counted.so", dir.path() / "twice.so");
    EXPECT_EQ(untrusted_module(dir.path() / "twice.so", ::geteuid()),
              (dir.path() / "twice.so").string() +
                  " -> counted.so: " + (dir.path() / "counted.so").string() +
                  " is a symbolic link too (one link is followed, and only to a file)");
}

TEST(ModuleTrust, TheOpenFileIsTheOneCheckedAndAChangeSinceIsRefused) {
    ModulesDir dir;
    const auto module = dir.add("counted");
    auto opened = open_trusted_module(module, ::geteuid());
    ASSERT_TRUE(opened.file) << opened.refusal;
    EXPECT_EQ(changed_since_checked(*opened.file, ::geteuid()), std::nullopt);
    std::filesystem::permissions(module, std::filesystem::perms(0775));
    EXPECT_EQ(changed_since_checked(*opened.file, ::geteuid()),
              module.string() + " is writable by group or others (mode 0775)")
        << "someone else may have written it since";
    std::filesystem::permissions(module, std::filesystem::perms(0755));
    const timespec times[2] = {{0, UTIME_OMIT}, {12345, 0}};
    ASSERT_EQ(::utimensat(AT_FDCWD, module.c_str(), times, 0), 0);
    EXPECT_EQ(
        changed_since_checked(*opened.file, ::geteuid()),
        module.string() + " changed since it was checked and tried (a reload tries it again)");
}

// ---- what a module does while loading

TEST(ModuleProbe, AModuleThatLoadsTellsItsNameAndDescription) {
    ModulesDir dir;
    const auto probed = probe_modules(opened({dir.add("counted"), dir.add_example()}));
    ASSERT_EQ(probed.size(), 2u);
    EXPECT_TRUE(probed[0].loaded()) << probed[0].error;
    EXPECT_EQ(probed[0].name, "counted");
    EXPECT_EQ(probed[0].description, "a test module that misbehaves");
    EXPECT_EQ(probed[1].name, "trace");
}

TEST(ModuleProbe, AConstructorThatHangsIsGivenUpOnAtTheTimeLimitWithoutHoldingUpTheOthers) {
    ModulesDir dir;
    const auto started = monotonic_now_us();
    const auto probed = probe_modules(opened({dir.add("hang"), dir.add("counted")}),
                                      std::chrono::milliseconds(300));
    // The limit under test is honoured (never given up before it); that it was given up at all
    // is the answer itself, the constructor hanging for ever: no upper bound by the clock,
    // which a loaded machine stretches.
    EXPECT_GE(monotonic_now_us() - started, 300'000u);
    EXPECT_EQ(probed[0].error, "did not finish loading within 300 ms (a constructor that hangs?)");
    EXPECT_TRUE(probed[1].loaded()) << probed[1].error;
}

TEST(ModuleProbe, AConstructorThatCrashesOrExitsIsToldApart) {
    if (testing::kSanitizerOwnsCrashes) {
        GTEST_SKIP() << "AddressSanitizer's handler decides how a crashing module's process ends";
    }
    ModulesDir dir;
    const auto probed = probe_modules(opened({dir.add("crash-at-load"), dir.add("exit-at-load")}));
    EXPECT_EQ(probed[0].error,
              std::string("crashed while loading (") + testing::kCrashSignalName + ")");
    EXPECT_EQ(probed[1].error,
              "exited with status 3 while loading (a constructor that calls exit()?)");
}

TEST(ModuleProbe, AFileThatIsNotADriverIsRefusedWithTheLoadersReason) {
    TempDir dir;
    const auto garbage = dir.write("garbage.so", "not an ELF file");
    const auto probed = probe_modules(opened({garbage}));
    ASSERT_EQ(probed.size(), 1u);
    EXPECT_THAT(probed[0].error, HasSubstr(garbage.string()))
        << "the file's name, not the /proc/self/fd/N the loader opened";
    if (std::filesystem::exists("/lib/x86_64-linux-gnu/libc.so.6")) {
        EXPECT_EQ(probe_modules(opened({"/lib/x86_64-linux-gnu/libc.so.6"}))[0].error,
                  "has no vibscore_driver_entry symbol");
    }
}

TEST(ModuleProbe, TheTrialRunsInASessionOfItsOwnThatDiesWithTheDaemonUnderAFilter) {
    ModulesDir dir;
    TempDir logs;
    const auto log = logs.path() / "process";
    ::setenv("VIBSCORE_TEST_PROCESS_LOG", log.c_str(), 1);
    const auto probed = probe_modules(opened({dir.add("describe-trial")}));
    ::unsetenv("VIBSCORE_TEST_PROCESS_LOG");
    ASSERT_TRUE(probed[0].loaded()) << probed[0].error;
    std::ifstream in(log);
    long pid = 0, session = 0;
    int death_signal = 0, seccomp = 0;
    ASSERT_TRUE(in >> pid >> session >> death_signal >> seccomp);
    EXPECT_NE(pid, static_cast<long>(::getpid()));
    EXPECT_EQ(session, pid) << "the leader of a session of its own";
    EXPECT_NE(session, static_cast<long>(::getsid(0)));
    EXPECT_EQ(death_signal, SIGKILL);
    EXPECT_EQ(seccomp, 2) << "SECCOMP_MODE_FILTER";
}

TEST(ModuleProbe, AConstructorThatKillsItsParentOrForksIsRefusedAndThisProcessLivesOn) {
    ModulesDir dir;
    const auto probed =
        probe_modules(opened({dir.add("kill-parent"), dir.add("fork"), dir.add("threads")}));
    ASSERT_EQ(probed.size(), 3u);
    EXPECT_EQ(probed[0].error,
              "tried to signal another process (kill) while loading; a module's constructors may "
              "not start processes, signal or trace other processes");
    // Refused either way; which words depends on the C library: glibc 2.41 (Debian 13) blocks
    // every signal around fork's clone, so the kernel's SIGSYS kills the trial before its handler
    // can name the call, and the probe can only say that a refused call stopped it.
    EXPECT_THAT(probed[1].error,
                AnyOf("tried to start a process (clone, fork) while loading; a module's "
                      "constructors may not start processes, signal or trace other processes",
                      HasSubstr("was stopped by SIGSYS while loading")));
    EXPECT_FALSE(probed[1].loaded());
    EXPECT_TRUE(probed[2].loaded()) << "threads are allowed: " << probed[2].error;
    EXPECT_EQ(::kill(::getpid(), 0), 0) << "the parent the module tried to kill: this test";
}

// ---- the catalog

TEST(ModuleCatalog, ScanningRefusesEachUnsafeOrMisbehavingModuleWithALogLineNamingItAndWhy) {
    if (testing::kSanitizerOwnsCrashes) {
        GTEST_SKIP() << "AddressSanitizer's handler decides how a crashing module's process ends";
    }
    ModulesDir dir;
    dir.add_example();
    const auto hang = dir.add("hang");
    const auto crash = dir.add("crash-at-load");
    const auto writable = dir.add("counted", "writable.so");
    std::filesystem::permissions(writable, std::filesystem::perms(0777));
    ::testing::internal::CaptureStderr();
    const auto catalog = scan_driver_modules(dir.path());
    const std::string log = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(names_of(*catalog), std::vector<std::string>{"trace"});
    EXPECT_THAT(log, HasSubstr("driver module " + hang.string() +
                               " is not loaded: did not finish loading within 2000 ms"));
    EXPECT_THAT(log, HasSubstr("driver module " + crash.string() +
                               " is not loaded: crashed while loading (" +
                               testing::kCrashSignalName + ")"));
    EXPECT_THAT(log, HasSubstr("driver module " + writable.string() + " is not loaded: " +
                               writable.string() + " is writable by group or others (mode 0777)"));
    EXPECT_EQ(catalog->refused().size(), 3u);
    EXPECT_THAT(refusal_of(*catalog, hang), HasSubstr("did not finish loading"));
}

TEST(ModuleCatalog, AModuleThatKillsItsParentOrForksIsRefusedWithALogLineAndTheOthersLoad) {
    ModulesDir dir;
    dir.add_example();
    const auto killer = dir.add("kill-parent");
    const auto forker = dir.add("fork");
    ::testing::internal::CaptureStderr();
    const auto catalog = scan_driver_modules(dir.path());
    const std::string log = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(names_of(*catalog), std::vector<std::string>{"trace"});
    EXPECT_THAT(log, HasSubstr("driver module " + killer.string() +
                               " is not loaded: tried to signal another process (kill)"));
    // Named on glibc 2.36; on 2.41 fork blocks SIGSYS, so only "stopped by SIGSYS" (ModuleProbe).
    EXPECT_THAT(log, AnyOf(HasSubstr("driver module " + forker.string() +
                                     " is not loaded: tried to start a process (clone, fork)"),
                           HasSubstr("driver module " + forker.string() +
                                     " is not loaded: was stopped by SIGSYS while loading")));
}

TEST(ModuleCatalog, ALinkOutOfTheDirectoryIsRefusedAndALinkInsideIsListed) {
    ModulesDir dir;
    ModulesDir elsewhere;
    const auto outside = elsewhere.add_example();
    std::filesystem::create_symlink(outside, dir.path() / "good.so");
    dir.add("counted", "counted.so.2");
    std::filesystem::create_symlink("counted.so.2", dir.path() / "counted.so");
    const auto catalog = scan_driver_modules(dir.path());
    EXPECT_EQ(names_of(*catalog), std::vector<std::string>{"counted"});
    EXPECT_EQ(refusal_of(*catalog, dir.path() / "good.so"),
              (dir.path() / "good.so").string() + " -> " + outside.string() +
                  " leads out of the drivers directory " + dir.path().string() +
                  " (a link there may only name a file below it)");
}

TEST(ModuleCatalog, AFileRenamedIntoPlaceAfterTheScanIsNotWhatLoads) {
    ModulesDir dir;
    const auto module = dir.add("counted", "mod.so");
    const auto catalog = scan_driver_modules(dir.path());
    ASSERT_EQ(names_of(*catalog), std::vector<std::string>{"counted"});
    // Another module, put in the scanned one's place by rename (as an attacker with write
    // access to the directory, or a careless upgrade, would).
    const auto other = dir.path() / "staged";
    std::filesystem::copy_file(
        std::filesystem::path(testing::required_env("VIBSCORE_EXAMPLE_DRIVERS")) / "trace.so",
        other);
    std::filesystem::rename(other, module);
    const auto actuator = catalog->open("counted", {});
    ASSERT_NE(actuator, nullptr);
    EXPECT_EQ(actuator->driver_name(), "counted") << "the scanned file, not the one renamed in";
}

TEST(ModuleCatalog, AModuleChangedInPlaceAfterTheScanLoadsNothing) {
    ModulesDir dir;
    const auto module = dir.add("counted");
    const auto catalog = scan_driver_modules(dir.path());
    ASSERT_EQ(names_of(*catalog), std::vector<std::string>{"counted"});
    const timespec times[2] = {{0, UTIME_OMIT}, {12345, 0}};
    ASSERT_EQ(::utimensat(AT_FDCWD, module.c_str(), times, 0), 0);
    EXPECT_THAT([&] { catalog->open("counted", {}); },
                ::testing::ThrowsMessage<std::runtime_error>(
                    HasSubstr(module.string() + " changed since it was checked and tried")));
}

TEST(ModuleCatalog, AModuleOwnedByAnotherUserIsRefused) {
    if (!running_as_root()) {
        GTEST_SKIP() << "giving a file to another user takes root";
    }
    ModulesDir dir;
    const auto foreign = dir.add("counted");
    ASSERT_EQ(::chown(foreign.c_str(), kNobody, kNobody), 0);
    const auto catalog = scan_driver_modules(dir.path());
    EXPECT_THAT(catalog->modules(), IsEmpty());
    EXPECT_EQ(
        refusal_of(*catalog, foreign),
        foreign.string() + " is owned by uid 65534, neither root nor the daemon's user (uid 0)");
}

TEST(ModuleCatalog, AWorldWritableDirectoryLoadsNoneOfItsModules) {
    ModulesDir dir;
    const auto module = dir.add_example();
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0777));
    const auto catalog = scan_driver_modules(dir.path());
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0755));
    EXPECT_THAT(catalog->modules(), IsEmpty());
    EXPECT_EQ(refusal_of(*catalog, module), "its directory is not safe: " + dir.path().string() +
                                                " is writable by group or others (mode 0777)");
    EXPECT_THAT([&] { make_actuator("trace", {}, *catalog); },
                ::testing::ThrowsMessage<std::invalid_argument>(
                    HasSubstr("driver \"trace\": module " + module.string() +
                              " is not loaded: its directory is not safe")));
}

TEST(ModuleCatalog, ABuiltInNameOrATakenNameIsRefused) {
    ModulesDir dir;
    dir.add_example();
    const auto copy = dir.path() / "zz-copy.so";
    std::filesystem::copy_file(dir.path() / "trace.so", copy);
    const auto catalog = ModuleCatalog::scan(dir.path(), {"trace"});
    EXPECT_THAT(catalog->modules(), IsEmpty());
    EXPECT_EQ(refusal_of(*catalog, dir.path() / "trace.so"), "\"trace\" is a built-in driver");
    const auto twice = scan_driver_modules(dir.path());
    EXPECT_EQ(names_of(*twice), std::vector<std::string>{"trace"});
    EXPECT_EQ(refusal_of(*twice, copy),
              "\"trace\" is the name of " + (dir.path() / "trace.so").string());
}

TEST(ModuleCatalog, ListingLoadsNothingAndOpeningLoadsAModuleIntoTheDaemonOnce) {
    ModulesDir dir;
    dir.add("counted");
    TempDir logs;
    const auto load_log = logs.path() / "loads";
    ::setenv("VIBSCORE_TEST_LOAD_LOG", load_log.c_str(), 1);
    const auto loads = [&] {
        std::vector<long> pids;
        std::ifstream in(load_log);
        for (long pid; in >> pid;) {
            pids.push_back(pid);
        }
        return pids;
    };
    const auto catalog = scan_driver_modules(dir.path());
    ASSERT_EQ(loads().size(), 1u) << "tried once, in a child";
    EXPECT_NE(loads()[0], static_cast<long>(::getpid()));
    for (int i = 0; i < 20; ++i) {
        EXPECT_EQ(available_drivers(*catalog).back().name, "counted");
    }
    EXPECT_EQ(loads().size(), 1u) << "listing loads nothing";
    {
        const auto first = catalog->open("counted", {});
        const auto second = catalog->open("counted", {});
    }
    ASSERT_EQ(loads().size(), 2u) << "loaded into this process once";
    EXPECT_EQ(loads()[1], static_cast<long>(::getpid()));
    ::unsetenv("VIBSCORE_TEST_LOAD_LOG");
}

TEST(ModuleCatalog, TellsTheSameModuleFileFromAReplacedOne) {
    ModulesDir dir;
    const auto module = dir.add_example();
    const auto first = scan_driver_modules(dir.path());
    const auto again = scan_driver_modules(dir.path());
    EXPECT_TRUE(again->same_module(*first, "trace"));
    EXPECT_FALSE(again->same_module(*first, "sim"));
    std::filesystem::remove(module);
    dir.add_example();  // an upgrade: another file of the same name
    const auto upgraded = scan_driver_modules(dir.path());
    EXPECT_FALSE(upgraded->same_module(*first, "trace"));
}

TEST(ModuleCatalog, AnApplyThatSegfaultsKillsTheProcessThatRunsIt) {
    if (testing::kSanitizerOwnsCrashes) {
        GTEST_SKIP() << "AddressSanitizer's handler decides how a crashing module's process ends";
    }
    // What the daemon's crash record is for (ActuatorHostTest): this module really crashes.
    ModulesDir dir;
    dir.add("segv");
    const auto catalog = scan_driver_modules(dir.path());
    ASSERT_EQ(names_of(*catalog), std::vector<std::string>{"segv"});
    const pid_t child = ::fork();
    if (child == 0) {
        auto actuator = catalog->open("segv", {});
        actuator->off();
        actuator->apply({0.5, 0.0});
        ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), SIGSEGV);
}

}  // namespace
}  // namespace vibscore::drivers
