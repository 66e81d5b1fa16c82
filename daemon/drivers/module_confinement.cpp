#include "daemon/drivers/module_confinement.hpp"

#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace vibscore::drivers {

namespace {

#if defined(__x86_64__)
constexpr std::uint32_t kArch = AUDIT_ARCH_X86_64;
#elif defined(__aarch64__)
constexpr std::uint32_t kArch = AUDIT_ARCH_AARCH64;
#elif defined(__i386__)
constexpr std::uint32_t kArch = AUDIT_ARCH_I386;
#elif defined(__arm__) && defined(__ARMEL__)
constexpr std::uint32_t kArch = AUDIT_ARCH_ARM;
#elif defined(__powerpc64__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
constexpr std::uint32_t kArch = AUDIT_ARCH_PPC64LE;
#elif defined(__s390x__)
constexpr std::uint32_t kArch = AUDIT_ARCH_S390X;
#elif defined(__riscv) && __riscv_xlen == 64
constexpr std::uint32_t kArch = AUDIT_ARCH_RISCV64;
#elif defined(__mips__) && defined(__mips64) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
constexpr std::uint32_t kArch = AUDIT_ARCH_MIPSEL64;
#elif defined(__loongarch64) && defined(AUDIT_ARCH_LOONGARCH64)
constexpr std::uint32_t kArch = AUDIT_ARCH_LOONGARCH64;
#else
#define VIBSCORE_NO_TRIAL_FILTER 1
#endif

#ifndef VIBSCORE_NO_TRIAL_FILTER

using Program = std::vector<sock_filter>;

// s390's clone takes the stack first and the flags second.
#if defined(__s390x__)
constexpr int kCloneFlagsArgument = 1;
#else
constexpr int kCloneFlagsArgument = 0;
#endif

// The low 32 bits of argument `n`: pids, signals, flags and prctl options are ints.
constexpr std::uint32_t argument_low(int n) {
    return static_cast<std::uint32_t>(offsetof(seccomp_data, args) + 8 * n +
                                      (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__ ? 4 : 0));
}

sock_filter load(std::uint32_t offset) {
    return BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offset);
}
sock_filter jump_if_equal(std::uint32_t value, std::uint8_t if_true, std::uint8_t if_false) {
    return BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, value, if_true, if_false);
}
sock_filter give(std::uint32_t action) {
    return BPF_STMT(BPF_RET | BPF_K, action);
}

// `body` runs when the system call is `number`, and must end in a return.
void when_call(Program& program, long number, const Program& body) {
    program.push_back(jump_if_equal(static_cast<std::uint32_t>(number), 0,
                                    static_cast<std::uint8_t>(body.size())));
    // One by one: GCC 14 reads a range insert here as a memmove past the end
    // (-Wstringop-overflow, a false positive that -Werror makes fatal on trixie).
    for (const sock_filter& statement : body) {
        program.push_back(statement);
    }
}

void refuse(Program& program, long number) {
    when_call(program, number, {give(SECCOMP_RET_TRAP)});
}

// Allowed when argument `n` is one of `allowed` (at most a few), refused otherwise.
void refuse_unless(Program& program, long number, int n,
                   const std::vector<std::uint32_t>& allowed) {
    Program body{load(argument_low(n))};
    const auto count = allowed.size();
    for (std::size_t i = 0; i < count; ++i) {
        body.push_back(jump_if_equal(allowed[i], static_cast<std::uint8_t>(count - i), 0));
    }
    body.push_back(give(SECCOMP_RET_TRAP));
    body.push_back(give(SECCOMP_RET_ALLOW));
    when_call(program, number, body);
}

Program trial_filter(pid_t self) {
    const auto me = static_cast<std::uint32_t>(self);
    Program program{load(offsetof(seccomp_data, arch)), jump_if_equal(kArch, 1, 0),
                    give(SECCOMP_RET_KILL_PROCESS), load(offsetof(seccomp_data, nr))};
#if defined(__x86_64__)
    // x32 numbers are the same calls under another number: refused whole.
    program.push_back(BPF_JUMP(BPF_JMP | BPF_JGE | BPF_K, 0x40000000u, 0, 1));
    program.push_back(give(SECCOMP_RET_KILL_PROCESS));
#endif
#ifdef __NR_fork
    refuse(program, __NR_fork);
#endif
#ifdef __NR_vfork
    refuse(program, __NR_vfork);
#endif
    when_call(program, __NR_clone,
              {load(argument_low(kCloneFlagsArgument)),
               BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, CLONE_THREAD, 1, 0), give(SECCOMP_RET_TRAP),
               give(SECCOMP_RET_ALLOW)});
#ifdef __NR_clone3
    when_call(program, __NR_clone3, {give(SECCOMP_RET_ERRNO | ENOSYS)});
#endif
    refuse_unless(program, __NR_kill, 0, {me, 0});
    refuse_unless(program, __NR_tkill, 0, {me});
    refuse_unless(program, __NR_tgkill, 0, {me});
    refuse_unless(program, __NR_rt_sigqueueinfo, 0, {me});
    refuse_unless(program, __NR_rt_tgsigqueueinfo, 0, {me});
#ifdef __NR_pidfd_send_signal
    refuse(program, __NR_pidfd_send_signal);
#endif
    refuse(program, __NR_ptrace);
    refuse(program, __NR_process_vm_writev);
    refuse(program, __NR_process_vm_readv);
    when_call(program, __NR_prctl,
              {load(argument_low(0)), jump_if_equal(PR_SET_PDEATHSIG, 0, 1), give(SECCOMP_RET_TRAP),
               give(SECCOMP_RET_ALLOW)});
    when_call(program, __NR_rt_sigaction,
              {load(argument_low(0)), jump_if_equal(SIGSYS, 0, 1), give(SECCOMP_RET_KILL_PROCESS),
               give(SECCOMP_RET_ALLOW)});
    program.push_back(give(SECCOMP_RET_ALLOW));
    return program;
}

#endif  // VIBSCORE_NO_TRIAL_FILTER

volatile int report_to = -1;

struct Refused {
    long number;
    const char* what;
};

// What each refused call would have done, for the report.
constexpr Refused kRefused[] = {
#ifdef __NR_fork
    {__NR_fork, "start a process (fork)"},
#endif
#ifdef __NR_vfork
    {__NR_vfork, "start a process (vfork)"},
#endif
    {__NR_clone, "start a process (clone, fork)"},
    {__NR_kill, "signal another process (kill)"},
    {__NR_tkill, "signal another process (tkill)"},
    {__NR_tgkill, "signal another process (tgkill)"},
    {__NR_rt_sigqueueinfo, "signal another process (sigqueue)"},
    {__NR_rt_tgsigqueueinfo, "signal another process (rt_tgsigqueueinfo)"},
#ifdef __NR_pidfd_send_signal
    {__NR_pidfd_send_signal, "signal a process (pidfd_send_signal)"},
#endif
    {__NR_ptrace, "trace a process (ptrace)"},
    {__NR_process_vm_writev, "write another process's memory (process_vm_writev)"},
    {__NR_process_vm_readv, "read another process's memory (process_vm_readv)"},
    {__NR_prctl, "outlive the daemon (prctl PR_SET_PDEATHSIG)"},
};

void append(char* to, std::size_t& at, std::size_t size, const char* text) {
    for (; *text != '\0' && at + 1 < size; ++text) {
        to[at++] = *text;
    }
}

// Async-signal-safe: builds the report in a buffer of its own, writes it, exits.
void on_refused_call(int, siginfo_t* info, void*) {
    char report[256];
    std::size_t at = 0;
    append(report, at, sizeof report, "error");
    report[at++] = '\0';
    append(report, at, sizeof report, "tried to ");
    const char* what = "make a system call a module may not make while it is tried";
    for (const auto& refused : kRefused) {
        if (refused.number == info->si_syscall) {
            what = refused.what;
        }
    }
    append(report, at, sizeof report, what);
    append(report, at, sizeof report,
           " while loading; a module's constructors may not start processes, signal or trace "
           "other processes");
    report[at++] = '\0';
    if (report_to >= 0) {
        [[maybe_unused]] const ssize_t written = ::write(report_to, report, at);
    }
    ::_exit(0);
}

std::string failed(const char* what) {
    return std::string(what) + ": " + std::strerror(errno);
}

}  // namespace

std::string confine_trial_child(pid_t parent, int report_fd) {
    if (::setsid() < 0) {
        return failed("setsid");
    }
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0) {
        return failed("PR_SET_PDEATHSIG");
    }
    if (::getppid() != parent) {
        ::_exit(0);  // the daemon is already gone: nobody waits for this trial
    }
#ifdef VIBSCORE_NO_TRIAL_FILTER
    (void)report_fd;
    return "no seccomp filter is written for this architecture (module_confinement.cpp)";
#else
    report_to = report_fd;
    struct sigaction action {};
    action.sa_sigaction = on_refused_call;
    action.sa_flags = SA_SIGINFO;
    sigemptyset(&action.sa_mask);
    if (::sigaction(SIGSYS, &action, nullptr) != 0) {
        return failed("sigaction(SIGSYS)");
    }
    sigset_t sys;
    sigemptyset(&sys);
    sigaddset(&sys, SIGSYS);
    ::sigprocmask(SIG_UNBLOCK, &sys, nullptr);
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) {
        return failed("PR_SET_NO_NEW_PRIVS");
    }
    auto program = trial_filter(::getpid());
    const sock_fprog filter{static_cast<unsigned short>(program.size()), program.data()};
    if (::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &filter, 0, 0) != 0) {
        return failed("seccomp filter");
    }
    return {};
#endif
}

}  // namespace vibscore::drivers
