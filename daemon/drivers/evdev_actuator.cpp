#include "daemon/drivers/evdev_actuator.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>

#include "common/log.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "daemon/drivers/evdev_discovery.hpp"

namespace vibscore::drivers {

namespace {

double unit(double value) {
    return std::isfinite(value) ? std::clamp(value, 0.0, 1.0) : 0.0;
}

// Periodic magnitudes and envelope levels share the scale 0..0x7fff; a magnitude may be negative
// (anti-phase, where the device plays it so).
std::int16_t periodic_level(double fraction) {
    const double level = std::isfinite(fraction) ? std::clamp(fraction, -1.0, 1.0) : 0.0;
    return static_cast<std::int16_t>(std::lround(level * 0x7fff));
}

std::uint16_t milliseconds(double seconds) {
    return static_cast<std::uint16_t>(std::clamp(std::llround(seconds * 1000.0), 1LL, 0xffffLL));
}

bool has_ramp(const Drive& drive) {
    return std::isfinite(drive.ramp_s) && drive.ramp_s > 0.0;
}

input_event ff_event(std::uint16_t code, std::int32_t value) {
    input_event event{};
    event.type = EV_FF;
    event.code = code;
    event.value = value;
    return event;
}

input_event playback(int id, bool play) {
    return ff_event(static_cast<std::uint16_t>(id), play ? 1 : 0);
}

std::string describe(const FfDevice& device) {
    return "evdev " + device.path() + " (" + device.name() + ")";
}

}  // namespace

EvdevActuator::EvdevActuator(EvdevSettings settings, FfDeviceOpener opener)
    : settings_(settings), opener_(std::move(opener)) {
    ensure_open();
}

EvdevActuator::~EvdevActuator() {
    if (!device_) {
        return;
    }
    // The kernel would drop our effects when the descriptor closes anyway; erasing them here
    // keeps that true for every device, and stops the motor first whatever the driver does.
    try {
        stop_playing();
    } catch (...) {
    }
    for (std::size_t i = 0; i < slot_count_ && device_; ++i) {
        if (slots_[i].id >= 0) {
            try {
                device_->erase(slots_[i].id);
            } catch (...) {
            }
        }
    }
}

Capabilities EvdevActuator::capabilities() const {
    return capabilities_;
}

std::string EvdevActuator::device_path() const {
    return device_ ? device_->path() : std::string();
}

void EvdevActuator::ensure_open() {
    if (device_) {
        return;
    }
    auto device = opener_();
    const FfFeatures features = device->features();
    const bool periodic = features.periodic && (features.sine || features.square);
    if (!periodic && !features.rumble) {
        throw DeviceError(describe(*device) +
                          ": no force-feedback effect to play (needs FF_RUMBLE, or FF_PERIODIC "
                          "with FF_SINE or FF_SQUARE)");
    }
    if (features.effect_slots < 1) {
        throw DeviceError(describe(*device) + ": holds no force-feedback effects");
    }
    kind_ = periodic ? EffectKind::periodic : EffectKind::rumble;
    const bool want_sine = settings_.waveform == FfWaveform::sine;
    waveform_ =
        (want_sine && features.sine) || (!want_sine && !features.square) ? FF_SINE : FF_SQUARE;
    slot_count_ = features.effect_slots >= 2 ? 2 : 1;
    has_gain_ = features.gain;
    slots_ = {};
    playing_.reset();
    spare_ = 0;

    capabilities_ = Capabilities{};
    capabilities_.amplitude_control = true;
    capabilities_.frequency_control = periodic && settings_.frequency_control;
    capabilities_.envelopes = periodic;
    capabilities_.effect_memory = slot_count_ == 2;
    capabilities_.gain_control = has_gain_;
    capabilities_.reverse = periodic && settings_.anti_phase;

    std::string effects =
        periodic ? (waveform_ == FF_SINE ? "periodic sine" : "periodic square") : "rumble";
    log::info(describe(*device) + ": " + effects + " effects, " +
              std::to_string(features.effect_slots) +
              (features.effect_slots == 1 ? " effect slot" : " effect slots") +
              (has_gain_ ? ", gain" : ""));
    device_ = std::move(device);

    if (gain_ && has_gain_) {
        const input_event gain =
            ff_event(FF_GAIN, static_cast<std::int32_t>(std::lround(*gain_ * 0xffff)));
        guarded([&](FfDevice& device) { device.write(std::span(&gain, 1)); });
    }
}

void EvdevActuator::close_device() noexcept {
    // Its effects went with it: the kernel frees a file's effects when the file is released.
    device_.reset();
    slots_ = {};
    playing_.reset();
    spare_ = 0;
}

template <typename Call>
void EvdevActuator::guarded(Call&& call) {
    try {
        call(*device_);
    } catch (const FfDeviceError& error) {
        if (error.device_gone()) {
            log::warning(std::string(error.what()) +
                         ": the device has gone; it is opened again on the next drive");
            close_device();
        }
        throw;
    }
}

template <typename Operation>
void EvdevActuator::reopening_once(Operation&& operation) {
    const bool held_open = device_ != nullptr;
    try {
        operation();
    } catch (const FfDeviceError& error) {
        // Nothing watches the device between playbacks, so a node held open can have gone
        // since the last call: unplugged, or its driver rebound, and maybe back already. The
        // first playback after that should not be lost to the stale node.
        if (!held_open || device_ || !error.device_gone()) {
            throw;
        }
        operation();
    }
}

double EvdevActuator::level(double amplitude) const {
    if (capabilities_.reverse && std::isfinite(amplitude)) {
        return std::clamp(amplitude, -1.0, 1.0);
    }
    return unit(amplitude);
}

bool EvdevActuator::plays_nothing(const Drive& drive) const {
    const bool rising_from_zero =
        kind_ == EffectKind::periodic && has_ramp(drive) && unit(drive.ramp_to) > 0.0;
    return level(drive.amplitude) == 0.0 && !rising_from_zero;
}

ff_effect EvdevActuator::effect_for(const Drive& drive) const {
    ff_effect effect{};
    effect.id = -1;
    // length 0 plays until stopped: ff-core passes it on, ff-memless only schedules a stop for a
    // non-zero length, and envelopes' attacks work without one.
    effect.replay.length = 0;
    effect.replay.delay = 0;
    const double amplitude = unit(drive.amplitude);
    if (kind_ == EffectKind::rumble) {
        // No envelopes here: the player moves rumble strength in small steps instead.
        const auto magnitude = static_cast<std::uint16_t>(std::lround(amplitude * 0xffff));
        effect.type = FF_RUMBLE;
        const RumbleMotor motor = settings_.rumble_motor;
        effect.u.rumble.strong_magnitude = motor == RumbleMotor::weak ? 0 : magnitude;
        effect.u.rumble.weak_magnitude = motor == RumbleMotor::strong ? 0 : magnitude;
        return effect;
    }
    effect.type = FF_PERIODIC;
    auto& periodic = effect.u.periodic;
    periodic.waveform = waveform_;
    const double frequency_hz = std::isfinite(drive.frequency_hz) && drive.frequency_hz > 0.0
                                    ? drive.frequency_hz
                                    : settings_.default_frequency_hz;
    periodic.period = milliseconds(1.0 / frequency_hz);
    if (has_ramp(drive)) {
        // The attack runs from attack_level to the magnitude and the effect then holds there,
        // in either direction: envelope levels are absolute (linux/input.h), and an attack that
        // falls is as valid as one that rises. A fade would need a finite replay length and
        // would drop to nothing at its end instead of holding.
        periodic.magnitude = periodic_level(unit(drive.ramp_to));
        periodic.envelope.attack_length = milliseconds(drive.ramp_s);
        periodic.envelope.attack_level = static_cast<std::uint16_t>(periodic_level(amplitude));
    } else {
        periodic.magnitude = periodic_level(level(drive.amplitude));
    }
    return effect;
}

void EvdevActuator::load(Slot& slot, const Drive& drive) {
    ff_effect effect = effect_for(drive);
    // The same id again updates the effect in place: one slot is never erased and allocated
    // anew while the daemon runs. Effects of the same type only; the kind is fixed per device
    // and the slots start afresh whenever a device is opened.
    effect.id = static_cast<std::int16_t>(slot.id);
    slot.loaded.reset();
    guarded([&](FfDevice& device) { device.upload(effect); });
    slot.id = effect.id;
    slot.loaded = drive;
}

void EvdevActuator::stop_playing() {
    if (!playing_) {
        return;
    }
    const input_event stop = playback(slots_[*playing_].id, false);
    guarded([&](FfDevice& device) { device.write(std::span(&stop, 1)); });
    playing_.reset();
}

void EvdevActuator::apply(const Drive& drive) {
    reopening_once([&] { apply_now(drive); });
}

void EvdevActuator::apply_now(const Drive& drive) {
    ensure_open();
    if (plays_nothing(drive)) {
        stop_playing();
        return;
    }
    Slot& next = slots_[spare_];
    if (next.loaded != drive) {
        load(next, drive);
    }
    std::array<input_event, 2> events{};
    std::size_t count = 0;
    if (playing_ && *playing_ != spare_) {
        events[count++] = playback(slots_[*playing_].id, false);
    }
    events[count++] = playback(next.id, true);
    guarded([&](FfDevice& device) { device.write(std::span(events.data(), count)); });
    playing_ = spare_;
    if (slot_count_ == 2) {
        spare_ = 1 - spare_;
    }
}

void EvdevActuator::prepare(const Drive& next) {
    reopening_once([&] { prepare_now(next); });
}

void EvdevActuator::prepare_now(const Drive& next) {
    ensure_open();
    if (slot_count_ < 2 || plays_nothing(next)) {
        return;
    }
    Slot& spare = slots_[spare_];
    if (spare.loaded != next) {
        load(spare, next);
    }
}

void EvdevActuator::off() noexcept {
    if (!device_) {
        return;
    }
    try {
        stop_playing();
    } catch (const std::exception& error) {
        // Still recorded as playing (unless the device has gone), so the next apply() stops it.
        log::warning(std::string("evdev: stopping the effect failed: ") + error.what());
    } catch (...) {
    }
}

void EvdevActuator::set_gain(double gain) {
    gain_ = unit(gain);
    if (!device_ || !has_gain_) {
        return;
    }
    const input_event event =
        ff_event(FF_GAIN, static_cast<std::int32_t>(std::lround(*gain_ * 0xffff)));
    try {
        guarded([&](FfDevice& device) { device.write(std::span(&event, 1)); });
    } catch (const FfDeviceError& error) {
        // Gone (and closed): the next drive opens the device again and sends the gain then.
        if (!error.device_gone()) {
            throw;
        }
    }
}

std::unique_ptr<Actuator> make_evdev_actuator(const std::map<std::string, std::string>& settings) {
    DriverSettings read("evdev", settings);
    const std::optional<std::string> device = read.text("device");
    DiscoverySettings discovery;
    discovery.input_dir = read.text("input-dir", discovery.input_dir.string());
    discovery.udev_data = read.text("udev-data", discovery.udev_data.string());
    EvdevSettings evdev;
    evdev.waveform = read.choice("waveform", "sine", {"sine", "square"}) == "square"
                         ? FfWaveform::square
                         : FfWaveform::sine;
    evdev.default_frequency_hz =
        read.number("default-frequency-hz", evdev.default_frequency_hz, 1.0, 1000.0);
    const std::string motor = read.choice("rumble-motor", "strong", {"strong", "weak", "both"});
    evdev.rumble_motor = motor == "weak"   ? RumbleMotor::weak
                         : motor == "both" ? RumbleMotor::both
                                           : RumbleMotor::strong;
    evdev.frequency_control = read.flag("frequency-control", evdev.frequency_control);
    evdev.anti_phase = read.flag("anti-phase", evdev.anti_phase);
    read.reject_unknown();

    FfDeviceOpener opener;
    if (device) {
        opener = [path = *device] { return open_ff_device(path); };
    } else {
        opener = [discovery] {
            const DiscoveredDevice found = discover_ff_device(discovery, kernel_discovery_probe());
            log::info("evdev: discovered " + found.path.string() +
                      (found.tagged_vibra ? " (udev: FEEDBACKD_TYPE=vibra)" : ""));
            return open_ff_device(found.path.string());
        };
    }
    return std::make_unique<EvdevActuator>(evdev, std::move(opener));
}

}  // namespace vibscore::drivers
