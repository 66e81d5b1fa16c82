#include "daemon/drivers/module_probe.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string_view>

#include "common/monotonic_clock.hpp"
#include "common/unique_fd.hpp"
#include "daemon/drivers/external_driver.hpp"
#include "daemon/drivers/module_confinement.hpp"
#include "include/vibscore/driver.h"

namespace vibscore::drivers {

namespace {

// The child's report: "loaded\0NAME\0DESCRIPTION\0" or "error\0WHAT\0".
constexpr std::string_view kLoaded = "loaded";

void write_all(int fd, std::string_view text) {
    while (!text.empty()) {
        const ssize_t written = ::write(fd, text.data(), text.size());
        if (written < 0 && errno == EINTR) {
            continue;
        }
        if (written <= 0) {
            return;
        }
        text.remove_prefix(static_cast<std::size_t>(written));
    }
}

// In the child: never returns. After fork() in a process that may have other threads, it only
// loads the module and writes to the pipe: glibc makes malloc and the dynamic loader usable in
// the child of a fork, and the module's own constructors are what is being tried out.
[[noreturn]] void probe_in_child(const TrustedFile& module, pid_t daemon, int report) {
    std::string message;
    if (const std::string unconfined = confine_trial_child(daemon, report); !unconfined.empty()) {
        write_all(report,
                  std::string("error") + '\0' + "cannot confine its trial: " + unconfined + '\0');
        ::_exit(0);
    }
    const std::string name = descriptor_path(*module.fd);
    void* handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
        // The loader names what it opened: /proc/self/fd/N, which means nothing in a log.
        std::string why = ::dlerror();
        if (why.starts_with(name)) {
            why.replace(0, name.size(), module.path.string());
        }
        message = std::string("error") + '\0' + why + '\0';
    } else {
        const vibscore_driver* entry = nullptr;
        const std::string wrong = entry_problem(handle, entry);
        message = wrong.empty() ? std::string(kLoaded) + '\0' + entry->name + '\0' +
                                      (entry->description ? entry->description : "") + '\0'
                                : std::string("error") + '\0' + wrong + '\0';
    }
    write_all(report, message);
    ::_exit(0);
}

struct Child {
    pid_t pid = -1;
    UniqueFd report;
    std::string received;
    bool done = false;  // end of the report seen
};

std::string signal_name(int signo) {
    const char* name = ::sigabbrev_np(signo);
    return name ? std::string("SIG") + name : "signal " + std::to_string(signo);
}

void read_reports(std::vector<Child>& children, std::uint64_t deadline_us) {
    for (;;) {
        std::vector<pollfd> fds;
        std::vector<Child*> open;
        for (auto& child : children) {
            if (!child.done) {
                fds.push_back({child.report.get(), POLLIN, 0});
                open.push_back(&child);
            }
        }
        const std::uint64_t now = monotonic_now_us();
        if (fds.empty() || now >= deadline_us) {
            return;
        }
        const int ready =
            ::poll(fds.data(), fds.size(), static_cast<int>((deadline_us - now) / 1000 + 1));
        if (ready < 0 && errno != EINTR) {
            return;
        }
        for (std::size_t i = 0; i < fds.size(); ++i) {
            if (fds[i].revents == 0) {
                continue;
            }
            char buffer[4096];
            const ssize_t got = ::read(fds[i].fd, buffer, sizeof buffer);
            if (got > 0) {
                open[i]->received.append(buffer, static_cast<std::size_t>(got));
            } else if (got == 0 || errno != EINTR) {
                open[i]->done = true;
            }
        }
    }
}

// The module as the child's report and exit tell it.
void conclude(Child& child, ProbedModule& probed, std::chrono::milliseconds timeout) {
    if (!child.done) {
        ::kill(child.pid, SIGKILL);
    }
    int status = 0;
    while (::waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
    }
    std::vector<std::string> fields;
    for (std::size_t start = 0; start < child.received.size();) {
        const auto end = child.received.find('\0', start);
        if (end == std::string::npos) {
            break;
        }
        fields.push_back(child.received.substr(start, end - start));
        start = end + 1;
    }
    // A whole report counts even without its end of file: a constructor may have started a
    // process of its own that holds the pipe open.
    if (fields.size() == 3 && fields[0] == kLoaded) {
        probed.name = fields[1];
        probed.description = fields[2];
    } else if (fields.size() == 2 && fields[0] != kLoaded) {
        probed.error = fields[1];
    } else if (!child.done) {
        probed.error = "did not finish loading within " + std::to_string(timeout.count()) +
                       " ms (a constructor that hangs?)";
    } else if (WIFSIGNALED(status) && WTERMSIG(status) == SIGSYS) {
        probed.error =
            "was stopped by SIGSYS while loading: it made a system call a module's "
            "trial may not make, or hid the report of one";
    } else if (WIFSIGNALED(status)) {
        probed.error = "crashed while loading (" + signal_name(WTERMSIG(status)) + ")";
    } else {
        probed.error = "exited with status " + std::to_string(WEXITSTATUS(status)) +
                       " while loading (a constructor that calls exit()?)";
    }
}

}  // namespace

std::vector<ProbedModule> probe_modules(const std::vector<TrustedFile>& modules,
                                        std::chrono::milliseconds timeout) {
    const pid_t daemon = ::getpid();
    std::vector<ProbedModule> probed(modules.size());
    std::vector<Child> children(modules.size());
    const std::uint64_t deadline_us =
        monotonic_now_us() + static_cast<std::uint64_t>(timeout.count()) * 1000;
    for (std::size_t i = 0; i < modules.size(); ++i) {
        probed[i].path = modules[i].path;
        int pipe[2];
        if (::pipe2(pipe, O_CLOEXEC) != 0) {
            probed[i].error = std::string("cannot make a pipe to try it: ") + std::strerror(errno);
            children[i].done = true;
            continue;
        }
        UniqueFd read_end(pipe[0]);
        UniqueFd write_end(pipe[1]);
        const pid_t pid = ::fork();
        if (pid < 0) {
            probed[i].error = std::string("cannot fork to try it: ") + std::strerror(errno);
            children[i].done = true;
            continue;
        }
        if (pid == 0) {
            probe_in_child(modules[i], daemon, write_end.get());
        }
        children[i].pid = pid;
        children[i].report = std::move(read_end);
    }
    read_reports(children, deadline_us);
    for (std::size_t i = 0; i < modules.size(); ++i) {
        if (children[i].pid > 0) {
            conclude(children[i], probed[i], timeout);
        }
    }
    return probed;
}

}  // namespace vibscore::drivers
