#pragma once

#include <time.h>

namespace vibscore::daemon {

// The CPU time the calling thread has used, in seconds: what a worker's job cost, charged to
// the caller it ran for (admission.hpp).
inline double thread_cpu_s() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) / 1e9;
}

}  // namespace vibscore::daemon
