#pragma once

#include <csignal>

namespace vibscore::testing {

// The signal a segfaulting driver module ends its process with: SIGSEGV, except under
// AddressSanitizer, whose handler reports the fault and then aborts (abort_on_error=1).
#if defined(__SANITIZE_ADDRESS__)
// Whether it aborts, exits or re-raises depends on ASAN_OPTIONS: those tests skip.
inline constexpr bool kSanitizerOwnsCrashes = true;
inline constexpr int kCrashSignal = SIGABRT;
inline constexpr const char* kCrashSignalName = "SIGABRT";
#else
inline constexpr bool kSanitizerOwnsCrashes = false;
inline constexpr int kCrashSignal = SIGSEGV;
inline constexpr const char* kCrashSignalName = "SIGSEGV";
#endif

}  // namespace vibscore::testing
