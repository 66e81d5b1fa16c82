// main() of the hil test programs: they create kernel devices and load nothing themselves, so
// they only make sense inside the guest vm-run boots (which sets VIBSCORE_HIL_GUEST).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    if (std::getenv("VIBSCORE_HIL_GUEST") == nullptr) {
        std::fprintf(stderr,
                     "%s: a hil test runs inside the test VM: meson test -C build --suite hil, "
                     "or tests/hil/vm-run -- %s\n",
                     argv[0], argv[0]);
        return 77;
    }
    return RUN_ALL_TESTS();
}
