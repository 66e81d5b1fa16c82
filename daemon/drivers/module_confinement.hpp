#pragma once

#include <sys/types.h>

#include <string>

// What confines the child in which a driver module is tried (module_probe.hpp), so that the
// module's constructors cannot signal the daemon or leave processes behind it:
//  - its own session (setsid): no signal sent to the daemon's process group or terminal reaches
//    the daemon through it, and it has no terminal;
//  - PR_SET_PDEATHSIG = SIGKILL: it dies with the daemon (checked after setting it, in case the
//    daemon died first);
//  - PR_SET_NO_NEW_PRIVS and a seccomp filter (plain BPF from the kernel's headers, no library):
//      fork, vfork, and clone without CLONE_THREAD (a new process)           refused
//      clone3 (whose flags a filter cannot read)      ENOSYS, so glibc falls back to clone, and
//                                                     threads still start
//      kill, tkill, tgkill, rt_sigqueueinfo, rt_tgsigqueueinfo to any process but the child
//      itself (kill(0, ...) is its own group: its own session), pidfd_send_signal  refused
//      ptrace, process_vm_writev, process_vm_readv                          refused
//      prctl(PR_SET_PDEATHSIG) (undoing the above)                          refused
//      rt_sigaction on SIGSYS (silencing the report)                        kills the child
//      a system call of another ABI (x32, i386 on x86-64)                  kills the child
//    A refused call raises SIGSYS, whose handler writes the report "tried to ..." and exits, so
//    the daemon refuses the module naming the call. The filter guards against a module's
//    mistakes and accidents, not against a hostile one: a root module may still write files;
//    who may install modules is module_trust.hpp's rule.
namespace vibscore::drivers {

// The report the SIGSYS handler writes to `report_fd`: the probe's "error\0WHAT\0" format.
// Confines the calling process (the trial child, just forked from `parent`). Returns "" or
// why it could not be confined, in which case the module must not be loaded.
std::string confine_trial_child(pid_t parent, int report_fd);

}  // namespace vibscore::drivers
