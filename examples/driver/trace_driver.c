/*
 * An example vibscore driver module: it "drives" an actuator by writing every command to a
 * file, one line each, with its CLOCK_MONOTONIC time in nanoseconds:
 *     <ns> open
 *     <ns> apply <amplitude> <frequency_hz>
 *     <ns> off
 *     <ns> close
 * Settings ([trace] in vibscored.conf):
 *     path = /run/vibscore/trace-driver.log   where the lines go (required)
 *     on-off = true                           report no amplitude control, so vibscored
 *                                             pulse-modulates (default false)
 *     reverse = true                          report VIBSCORE_CAP_REVERSE: negative amplitudes
 *                                             (backwards, anti-phase) come through (default false)
 * Build: cc -shared -fPIC -I<vibscore>/include -o trace.so trace_driver.c, then install it
 * into vibscored's drivers directory (install -m 0755 -o root trace.so DIR: a module others may
 * write is refused) and set "driver = trace".
 */
#include <vibscore/driver.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

struct trace_actuator {
    FILE* out;
    int on_off;
    int reverse;
};

static long long now_ns(void) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (long long)now.tv_sec * 1000000000LL + now.tv_nsec;
}

static void say(char* error, size_t error_size, const char* format, const char* a, const char* b) {
    if (error_size > 0) {
        snprintf(error, error_size, format, a, b);
    }
}

static int line(struct trace_actuator* actuator, const char* text) {
    if (fprintf(actuator->out, "%lld %s\n", now_ns(), text) < 0 || fflush(actuator->out) != 0) {
        return -errno;
    }
    return 0;
}

static void* trace_open(const struct vibscore_setting* settings, size_t count, char* error,
                        size_t error_size) {
    const char* path = NULL;
    int on_off = 0;
    int reverse = 0;
    for (size_t i = 0; i < count; ++i) {
        const int flag = strcmp(settings[i].value, "true") == 0;
        const int is_flag = flag || strcmp(settings[i].value, "false") == 0;
        if (strcmp(settings[i].key, "path") == 0) {
            path = settings[i].value;
        } else if (strcmp(settings[i].key, "on-off") == 0 && is_flag) {
            on_off = flag;
        } else if (strcmp(settings[i].key, "reverse") == 0 && is_flag) {
            reverse = flag;
        } else {
            say(error, error_size,
                "bad trace setting %s = \"%s\" (known: path, on-off = true|false, reverse = "
                "true|false)",
                settings[i].key, settings[i].value);
            return NULL;
        }
    }
    if (path == NULL || *path == '\0') {
        say(error, error_size, "trace setting %s is required%s", "path", "");
        return NULL;
    }
    struct trace_actuator* actuator = calloc(1, sizeof *actuator);
    if (actuator == NULL) {
        say(error, error_size, "%s%s", "out of memory", "");
        return NULL;
    }
    actuator->out = fopen(path, "ae");
    if (actuator->out == NULL) {
        say(error, error_size, "cannot open %s: %s", path, strerror(errno));
        free(actuator);
        return NULL;
    }
    actuator->on_off = on_off;
    actuator->reverse = reverse;
    line(actuator, "open");
    return actuator;
}

static void trace_close(void* handle) {
    struct trace_actuator* actuator = handle;
    line(actuator, "close");
    fclose(actuator->out);
    free(actuator);
}

static uint32_t trace_capabilities(void* handle, double* max_on_time_s) {
    const struct trace_actuator* actuator = handle;
    *max_on_time_s = 0.0;
    if (actuator->on_off) {
        return 0u;
    }
    return VIBSCORE_CAP_AMPLITUDE | VIBSCORE_CAP_FREQUENCY |
           (actuator->reverse ? VIBSCORE_CAP_REVERSE : 0u);
}

static int trace_apply(void* handle, const struct vibscore_drive* drive, char* error,
                       size_t error_size) {
    char text[96];
    snprintf(text, sizeof text, "apply %.6f %.3f", drive->amplitude, drive->frequency_hz);
    const int result = line(handle, text);
    if (result != 0) {
        say(error, error_size, "cannot write the trace: %s%s", strerror(-result), "");
    }
    return result;
}

static void trace_off(void* handle) {
    line(handle, "off");
}

static const struct vibscore_driver trace_driver = {
    .abi_version = VIBSCORE_DRIVER_ABI_VERSION,
    .name = "trace",
    .description = "example driver module: writes each command to a file",
    .open = trace_open,
    .close = trace_close,
    .capabilities = trace_capabilities,
    .apply = trace_apply,
    .off = trace_off,
    .prepare = NULL,
    .set_gain = NULL,
};

const struct vibscore_driver* vibscore_driver_entry(void) {
    return &trace_driver;
}
