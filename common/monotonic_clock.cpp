#include "common/monotonic_clock.hpp"

#include <time.h>

namespace vibscore {

std::int64_t monotonic_now_ns() {
    timespec now{};
    ::clock_gettime(CLOCK_MONOTONIC, &now);
    return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

std::uint64_t monotonic_now_us() {
    return static_cast<std::uint64_t>(monotonic_now_ns()) / 1000u;
}

}  // namespace vibscore
