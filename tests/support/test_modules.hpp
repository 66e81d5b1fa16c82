#pragma once

#include <filesystem>
#include <string>

#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::testing {

// A drivers directory of a test's own (mode 0755, under the sticky /tmp, so vibscored trusts
// it), with copies of the driver modules the tests build (tests/support/modules: "hang",
// "crash-at-load", "exit-at-load", "segv", "counted") and of the example module ("trace").
class ModulesDir {
  public:
    ModulesDir() { std::filesystem::permissions(dir_.path(), std::filesystem::perms(0755)); }
    const std::filesystem::path& path() const { return dir_.path(); }

    // Copies test module `module` in as `as` (default: MODULE.so), mode 0755.
    std::filesystem::path add(const std::string& module, const std::string& as = "") const {
        return copy(std::filesystem::path(required_env("VIBSCORE_TEST_MODULES")) / (module + ".so"),
                    as.empty() ? module + ".so" : as);
    }
    // Copies the example module examples/driver/trace_driver.c in as trace.so.
    std::filesystem::path add_example() const {
        return copy(std::filesystem::path(required_env("VIBSCORE_EXAMPLE_DRIVERS")) / "trace.so",
                    "trace.so");
    }

  private:
    std::filesystem::path copy(const std::filesystem::path& from, const std::string& as) const {
        const auto target = dir_.path() / as;
        std::filesystem::copy_file(from, target);
        std::filesystem::permissions(target, std::filesystem::perms(0755));
        return target;
    }

    TempDir dir_;
};

}  // namespace vibscore::testing
