/*
 * Driver modules that misbehave, built by the tests to prove vibscored survives them
 * (docs/drivers.md, "How modules are loaded"). One source, one misdeed per build:
 *   HANG_AT_LOAD    a constructor that never returns
 *   CRASH_AT_LOAD   a constructor that segfaults
 *   EXIT_AT_LOAD    a constructor that calls exit()
 *   CRASH_IN_APPLY  an apply() that segfaults (open and off work)
 *   HANG_IN_APPLY   an apply() that never returns (a driver stuck in a kernel call)
 *   COUNT_LOADS     well behaved; each load appends the loading process's id to the file
 *                   $VIBSCORE_TEST_LOAD_LOG, so a test can count the loads and tell where
 *   KILL_PARENT_AT_LOAD  a constructor that calls kill(getppid(), SIGKILL): the process that
 *                   loaded it is a child of the daemon only while it is tried
 *   FORK_AT_LOAD    a constructor that forks, and the copy lives on (pause())
 *   THREAD_AT_LOAD  well behaved, but its constructor starts and joins a thread, which the
 *                   trial must still allow
 *   DESCRIBE_PROCESS_AT_LOAD  well behaved; each load writes "PID SID PDEATHSIG SECCOMP" of the
 *                   loading process to $VIBSCORE_TEST_PROCESS_LOG (SECCOMP: /proc/self/status's
 *                   Seccomp field, 2 under a filter), so a test can see how the trial is confined
 * DRIVER_NAME is the driver's name.
 */
#include <vibscore/driver.h>

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#if defined(THREAD_AT_LOAD)
#include <pthread.h>
#endif
#if defined(DESCRIBE_PROCESS_AT_LOAD)
#include <string.h>
#include <sys/prctl.h>
#endif

#ifndef DRIVER_NAME
#error "DRIVER_NAME must be defined"
#endif

/* A real invalid write, which the compiler cannot see is one (a literal null it would turn into
 * a trap, or drop). */
static int* volatile nowhere = NULL;

#if defined(THREAD_AT_LOAD)
static void* in_thread(void* argument) {
    return argument;
}
#endif

__attribute__((constructor)) static void at_load(void) {
#if defined(KILL_PARENT_AT_LOAD)
    kill(getppid(), SIGKILL);
#elif defined(FORK_AT_LOAD)
    if (fork() == 0) {
        for (;;) {
            pause();
        }
    }
#elif defined(DESCRIBE_PROCESS_AT_LOAD)
    int deathsig = 0;
    prctl(PR_GET_PDEATHSIG, &deathsig);
    int seccomp = -1;
    FILE* status = fopen("/proc/self/status", "r");
    char line[256];
    while (status && fgets(line, sizeof line, status)) {
        if (strncmp(line, "Seccomp:", 8) == 0) {
            seccomp = atoi(line + 8);
        }
    }
    if (status) {
        fclose(status);
    }
    const char* log = getenv("VIBSCORE_TEST_PROCESS_LOG");
    FILE* out = log ? fopen(log, "a") : NULL;
    if (out) {
        fprintf(out, "%ld %ld %d %d\n", (long)getpid(), (long)getsid(0), deathsig, seccomp);
        fclose(out);
    }
#elif defined(THREAD_AT_LOAD)
    pthread_t thread;
    if (pthread_create(&thread, NULL, in_thread, NULL) != 0 || pthread_join(thread, NULL) != 0) {
        abort();
    }
#elif defined(HANG_AT_LOAD)
    for (;;) {
        pause();
    }
#elif defined(CRASH_AT_LOAD)
    *nowhere = 1;
#elif defined(EXIT_AT_LOAD)
    exit(3);
#elif defined(COUNT_LOADS)
    const char* log = getenv("VIBSCORE_TEST_LOAD_LOG");
    FILE* out = log ? fopen(log, "a") : NULL;
    if (out) {
        fprintf(out, "%ld\n", (long)getpid());
        fclose(out);
    }
#endif
}

static int handle_storage;

static void* misbehaving_open(const struct vibscore_setting* settings, size_t count, char* error,
                              size_t error_size) {
    (void)settings;
    (void)count;
    (void)error;
    (void)error_size;
    return &handle_storage;
}

static void misbehaving_close(void* handle) {
    (void)handle;
}

static uint32_t misbehaving_capabilities(void* handle, double* max_on_time_s) {
    (void)handle;
    *max_on_time_s = 0.0;
    return VIBSCORE_CAP_AMPLITUDE;
}

static int misbehaving_apply(void* handle, const struct vibscore_drive* drive, char* error,
                             size_t error_size) {
    (void)handle;
    (void)drive;
    (void)error;
    (void)error_size;
#if defined(CRASH_IN_APPLY)
    *nowhere = 1;
#elif defined(HANG_IN_APPLY)
    for (;;) {
        pause();
    }
#endif
    return 0;
}

static void misbehaving_off(void* handle) {
    (void)handle;
}

static const struct vibscore_driver driver = {
    .abi_version = VIBSCORE_DRIVER_ABI_VERSION,
    .name = DRIVER_NAME,
    .description = "a test module that misbehaves",
    .open = misbehaving_open,
    .close = misbehaving_close,
    .capabilities = misbehaving_capabilities,
    .apply = misbehaving_apply,
    .off = misbehaving_off,
    .prepare = NULL,
    .set_gain = NULL,
};

const struct vibscore_driver* vibscore_driver_entry(void) {
    return &driver;
}
