// What the store's crash safety rests on, seen at the system calls: this program defines fsync,
// rename and unlink itself, so the registry code linked into it calls these (which record the
// call and forward to the C library's), and a test can make the directory's fsync fail.
#include <dlfcn.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <cstdio>
#include <string>
#include <system_error>
#include <vector>

#include "common/atomic_file.hpp"
#include "daemon/registry/registry.hpp"
#include "tests/support/support.hpp"

namespace {

bool g_recording = false;
bool g_fail_directory_fsync = false;
std::vector<std::string> g_calls;

template <typename Function>
Function* next_definition(const char* name) {
    return reinterpret_cast<Function*>(::dlsym(RTLD_NEXT, name));
}

std::string path_of_fd(int fd) {
    char target[4096];
    const auto length =
        ::readlink(("/proc/self/fd/" + std::to_string(fd)).c_str(), target, sizeof target - 1);
    return length < 0 ? "?" : std::string(target, static_cast<std::size_t>(length));
}

bool is_directory(int fd) {
    struct stat status {};
    return ::fstat(fd, &status) == 0 && S_ISDIR(status.st_mode);
}

}  // namespace

extern "C" int fsync(int fd) {
    static auto* const real = next_definition<int(int)>("fsync");
    if (g_recording) {
        g_calls.push_back("fsync " + path_of_fd(fd));
        if (g_fail_directory_fsync && is_directory(fd)) {
            errno = EIO;
            return -1;
        }
    }
    return real(fd);
}

extern "C" int rename(const char* from, const char* to) noexcept {
    static auto* const real = next_definition<int(const char*, const char*)>("rename");
    if (g_recording) {
        g_calls.push_back(std::string("rename ") + from + " " + to);
    }
    return real(from, to);
}

extern "C" int unlink(const char* path) noexcept {
    static auto* const real = next_definition<int(const char*)>("unlink");
    if (g_recording) {
        g_calls.push_back(std::string("unlink ") + path);
    }
    return real(path);
}

namespace vibscore::daemon {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;

class Durability : public ::testing::Test {
  protected:
    Durability() : dir(std::filesystem::canonical(tmp.path())) {}
    void SetUp() override {
        g_calls.clear();
        g_recording = true;
    }
    void TearDown() override {
        g_recording = false;
        g_fail_directory_fsync = false;
    }
    std::vector<std::string> calls() {
        g_recording = false;
        return g_calls;
    }

    vibscore::testing::TempDir tmp;
    std::filesystem::path dir;
};

TEST_F(Durability, AWriteFsyncsTheTemporaryThenRenamesThenFsyncsTheDirectory) {
    write_file_atomically(dir / "a.xml", "new");
    const std::string temporary = dir.string() + "/\\.a\\.xml\\.tmp-.{6}";
    EXPECT_THAT(calls(),
                ElementsAre(MatchesRegex("fsync " + temporary),
                            MatchesRegex("rename " + temporary + " " + dir.string() + "/a\\.xml"),
                            "fsync " + dir.string()));
}

TEST_F(Durability, ARemovalUnlinksThenFsyncsTheDirectory) {
    tmp.write("gone.xml", "x");
    g_calls.clear();
    EXPECT_TRUE(remove_file_durably(dir / "gone.xml"));
    EXPECT_THAT(calls(),
                ElementsAre("unlink " + dir.string() + "/gone.xml", "fsync " + dir.string()));
}

TEST_F(Durability, StaleTemporariesAreRemovedThenTheDirectoryFsynced) {
    tmp.write(".a.xml.tmp-abcdef", "half");
    tmp.write("kept.xml", "x");
    g_calls.clear();
    EXPECT_EQ(remove_stale_temporaries(dir).size(), 1u);
    EXPECT_THAT(calls(), ElementsAre("unlink " + dir.string() + "/.a.xml.tmp-abcdef",
                                     "fsync " + dir.string()));
}

TEST_F(Durability, AFailingDirectoryFsyncFailsTheWriteNamingTheDirectory) {
    g_fail_directory_fsync = true;
    try {
        write_file_atomically(dir / "a.xml", "new");
        FAIL() << "the write succeeded";
    } catch (const std::system_error& error) {
        EXPECT_EQ(error.code().value(), EIO);
        EXPECT_THAT(error.what(), HasSubstr(dir.string() + ": fsync failed"));
    }
}

TEST_F(Durability, TheRegistryMakesComposesAndDeletesDurable) {
    const auto store = dir / "store";
    std::filesystem::create_directories(store);
    std::filesystem::create_directories(dir / "shipped");
    tmp.write("store/.old.score.xml.tmp-123456", "half");
    g_calls.clear();
    Registry registry(dir / "shipped", store);
    EXPECT_THAT(calls(), ::testing::Contains("fsync " + store.string()))
        << "after removing a stale temporary";
    g_recording = true;
    g_calls.clear();
    registry.compose("c", vibscore::testing::sine_clef(0.2, {170}, {0.5}));
    auto compose = calls();
    ASSERT_GE(compose.size(), 3u);
    EXPECT_THAT(compose[compose.size() - 2],
                MatchesRegex("rename .* " + store.string() + "/c\\.clef\\.xml"));
    EXPECT_EQ(compose.back(), "fsync " + store.string());
    g_recording = true;
    g_calls.clear();
    registry.remove(DocumentKind::clef, "c");
    EXPECT_THAT(calls(),
                ElementsAre("unlink " + store.string() + "/c.clef.xml", "fsync " + store.string()));
}

}  // namespace
}  // namespace vibscore::daemon
