/*
 * vibscore external actuator drivers: the C ABI.
 *
 * vibscored loads every "*.so" in its drivers directory ([daemon] drivers-dir, by default
 * LIBDIR/vibscore/drivers) and asks each for vibscore_driver_entry(). The driver is then chosen
 * by its name like a built-in one (driver = NAME, its settings in the [NAME] section) and
 * listed by `vibscored --list-drivers`. An example is examples/driver/trace_driver.c.
 *
 * Loading: the daemon first loads each module in a child process, which must finish loading
 * within 2 s (constructors included), and loads it into itself only when its driver is used.
 * The module file and its directory must be owned by root (or the daemon's user) and writable
 * by nobody else, or the module is refused (docs/drivers.md, "How modules are loaded").
 * Threading: every function is called from the daemon's single event-loop thread and must
 * return quickly (no sleeping; hand long work to a thread of your own).
 * Errors: functions that can fail return 0 on success or a negative errno value, and write a
 * NUL-terminated message a person can act on (naming the device) into `error`, at most
 * `error_size` bytes including the NUL. The daemon ends the playback with reason
 * "device-error: MESSAGE" and keeps serving.
 * Safety: the daemon calls off() at start-up, when idle, on stop, on SIGTERM, before closing
 * and before switching drivers; it enforces max-on-time-ms itself. off() must not fail.
 */
#ifndef VIBSCORE_DRIVER_H
#define VIBSCORE_DRIVER_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bump on any change. The daemon loads modules built for this version and the older ones it
 * names below, and refuses others.
 *   1  the first
 *   2  VIBSCORE_CAP_REVERSE: a negative amplitude drives backwards. The structures are unchanged,
 *      so a module built for version 1 still loads; it never gets a negative amplitude (its
 *      capability bits are read as version 1 defines them). */
#define VIBSCORE_DRIVER_ABI_VERSION 2u
#define VIBSCORE_DRIVER_ABI_OLDEST 1u

/* What the actuator can do (vibscore_driver.capabilities). The daemon adapts what it sends:
 * without AMPLITUDE it sends only 0 and 1 and expresses strength as pulse width; without
 * FREQUENCY every frequency is 0 (the actuator's own); without ENVELOPES ramps arrive as
 * drives every 5 ms. */
#define VIBSCORE_CAP_AMPLITUDE (1u << 0)     /* strength can vary, not only on/off */
#define VIBSCORE_CAP_FREQUENCY (1u << 1)     /* frequency can be chosen per note */
#define VIBSCORE_CAP_EFFECT_MEMORY (1u << 2) /* prepare() loads the next drive ahead of time */
#define VIBSCORE_CAP_ENVELOPES (1u << 3)     /* a linear ramp can be taken whole */
#define VIBSCORE_CAP_GAIN (1u << 4)          /* set_gain() scales every drive in the device */
/* ABI 2: the actuator can be driven backwards: a negative amplitude reverses an ERM (an
 * H-bridge) or drives an LRA in anti-phase, continuing the drive's phase. With an [actuator]
 * declaring brake = reverse, the daemon brakes with it (docs/drivers.md). */
#define VIBSCORE_CAP_REVERSE (1u << 5)

/* One "key = value" line of the driver's configuration section. */
struct vibscore_setting {
    const char* key;
    const char* value;
};

/* From now on vibrate with this strength (0..1 of the actuator's full drive; 0 is off) at this
 * frequency (Hz; 0 = the actuator's own). With VIBSCORE_CAP_REVERSE the amplitude may be
 * negative, -1..0: as strong, backwards (anti-phase). With VIBSCORE_CAP_ENVELOPES, ramp_s > 0
 * asks for a linear move from amplitude to ramp_to over ramp_s seconds, then holding there. */
struct vibscore_drive {
    double amplitude;
    double frequency_hz;
    double ramp_to;
    double ramp_s;
};

struct vibscore_driver {
    uint32_t abi_version;    /* VIBSCORE_DRIVER_ABI_VERSION, as the module was built */
    const char* name;        /* [a-z0-9-]+, unique among drivers */
    const char* description; /* one line for --list-drivers */

    /* Opens the actuator with its settings. Returns a handle, or NULL with a message (an
     * unknown key or a bad value must be an error naming them). */
    void* (*open)(const struct vibscore_setting* settings, size_t count, char* error,
                  size_t error_size);
    /* Switches off and releases everything. */
    void (*close)(void* handle);
    /* VIBSCORE_CAP_* bits; *max_on_time_s may be set to the actuator's own limit (0: none). */
    uint32_t (*capabilities)(void* handle, double* max_on_time_s);
    int (*apply)(void* handle, const struct vibscore_drive* drive, char* error, size_t error_size);
    void (*off)(void* handle);
    /* Optional (may be NULL): see VIBSCORE_CAP_EFFECT_MEMORY and VIBSCORE_CAP_GAIN. */
    int (*prepare)(void* handle, const struct vibscore_drive* next, char* error, size_t error_size);
    int (*set_gain)(void* handle, double gain, char* error, size_t error_size);
};

/* The one symbol a driver module exports. */
const struct vibscore_driver* vibscore_driver_entry(void);

#ifdef __cplusplus
}
#endif

#endif /* VIBSCORE_DRIVER_H */
