/*
 * A driver module as one built for driver ABI version 1 (before VIBSCORE_CAP_REVERSE) is: the
 * daemon still loads it, and never hands it a negative amplitude, even though it sets the bit
 * version 2 gave that meaning. Writes "apply <amplitude>" per drive to the file `path`.
 */
#include <vibscore/driver.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct old_actuator {
    FILE* out;
};

static void* old_open(const struct vibscore_setting* settings, size_t count, char* error,
                      size_t error_size) {
    const char* path = NULL;
    for (size_t i = 0; i < count; ++i) {
        if (strcmp(settings[i].key, "path") == 0) {
            path = settings[i].value;
        }
    }
    struct old_actuator* actuator = calloc(1, sizeof *actuator);
    if (path == NULL || actuator == NULL || (actuator->out = fopen(path, "we")) == NULL) {
        snprintf(error, error_size, "oldabi needs a writable path");
        free(actuator);
        return NULL;
    }
    return actuator;
}

static void old_close(void* handle) {
    struct old_actuator* actuator = handle;
    fclose(actuator->out);
    free(actuator);
}

static uint32_t old_capabilities(void* handle, double* max_on_time_s) {
    (void)handle;
    *max_on_time_s = 0.0;
    return VIBSCORE_CAP_AMPLITUDE | (1u << 5); /* bit 5 had no meaning in version 1 */
}

static int old_apply(void* handle, const struct vibscore_drive* drive, char* error,
                     size_t error_size) {
    (void)error;
    (void)error_size;
    struct old_actuator* actuator = handle;
    fprintf(actuator->out, "apply %.3f\n", drive->amplitude);
    fflush(actuator->out);
    return 0;
}

static void old_off(void* handle) {
    (void)handle;
}

static const struct vibscore_driver old_driver = {
    .abi_version = 1u,
    .name = "oldabi",
    .description = "a module built for driver ABI version 1",
    .open = old_open,
    .close = old_close,
    .capabilities = old_capabilities,
    .apply = old_apply,
    .off = old_off,
    .prepare = NULL,
    .set_gain = NULL,
};

const struct vibscore_driver* vibscore_driver_entry(void) {
    return &old_driver;
}
