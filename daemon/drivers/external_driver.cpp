#include "daemon/drivers/external_driver.hpp"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "include/vibscore/driver.h"

namespace vibscore::drivers {

namespace {

constexpr std::size_t kErrorSize = 512;

class ErrorText {
  public:
    char* data() { return text_.data(); }
    std::size_t size() const { return text_.size(); }
    // The driver's message, or a fallback when it wrote none (or no NUL).
    std::string message(const std::string& fallback) {
        text_.back() = '\0';
        return text_.front() == '\0' ? fallback : std::string(text_.data());
    }

  private:
    std::array<char, kErrorSize> text_{};
};

vibscore_drive to_c(const Drive& drive) {
    return {drive.amplitude, drive.frequency_hz, drive.ramp_to, drive.ramp_s};
}

class ExternalActuator final : public Actuator {
  public:
    ExternalActuator(std::shared_ptr<DriverModule> module, void* handle)
        : module_(std::move(module)), driver_(module_->entry()), handle_(handle) {
        reverse_ = capabilities().reverse;
    }
    ~ExternalActuator() override { driver_.close(handle_); }
    ExternalActuator(const ExternalActuator&) = delete;
    ExternalActuator& operator=(const ExternalActuator&) = delete;

    std::string_view driver_name() const override { return driver_.name; }

    Capabilities capabilities() const override {
        double max_on_time_s = 0.0;
        const std::uint32_t bits = driver_.capabilities(handle_, &max_on_time_s);
        Capabilities capabilities;
        capabilities.amplitude_control = (bits & VIBSCORE_CAP_AMPLITUDE) != 0;
        capabilities.frequency_control = (bits & VIBSCORE_CAP_FREQUENCY) != 0;
        capabilities.effect_memory =
            (bits & VIBSCORE_CAP_EFFECT_MEMORY) != 0 && driver_.prepare != nullptr;
        capabilities.envelopes = (bits & VIBSCORE_CAP_ENVELOPES) != 0;
        capabilities.gain_control = (bits & VIBSCORE_CAP_GAIN) != 0 && driver_.set_gain != nullptr;
        // Version 1 knew no reverse bit: whatever it set there means nothing.
        capabilities.reverse = driver_.abi_version >= 2 && (bits & VIBSCORE_CAP_REVERSE) != 0;
        capabilities.max_on_time_s = max_on_time_s > 0.0 ? max_on_time_s : 0.0;
        return capabilities;
    }

    void apply(const Drive& drive) override {
        const vibscore_drive c_drive = to_c(for_module(drive));
        check("apply", driver_.apply(handle_, &c_drive, error_.data(), error_.size()));
    }

    void off() noexcept override { driver_.off(handle_); }

    void prepare(const Drive& next) override {
        if (driver_.prepare) {
            const vibscore_drive c_drive = to_c(for_module(next));
            check("prepare", driver_.prepare(handle_, &c_drive, error_.data(), error_.size()));
        }
    }

    void set_gain(double gain) override {
        if (driver_.set_gain) {
            check("set_gain", driver_.set_gain(handle_, gain, error_.data(), error_.size()));
        }
    }

  private:
    // A module that cannot drive backwards never sees a negative amplitude.
    Drive for_module(Drive drive) const {
        if (!reverse_) {
            drive.amplitude = std::max(drive.amplitude, 0.0);
            drive.ramp_to = std::max(drive.ramp_to, 0.0);
        }
        return drive;
    }

    void check(const char* call, int result) {
        if (result != 0) {
            const std::string fallback =
                std::string(call) + " failed: " + std::strerror(result < 0 ? -result : result);
            throw DeviceError(std::string(driver_.name) + ": " + error_.message(fallback));
        }
    }

    std::shared_ptr<DriverModule> module_;  // keeps the code loaded while the handle lives
    const vibscore_driver& driver_;
    void* handle_;
    ErrorText error_;
    bool reverse_ = false;
};

bool valid_name(const char* name) {
    if (name == nullptr || *name == '\0' || std::strlen(name) > 64) {
        return false;
    }
    return std::all_of(name, name + std::strlen(name), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
    });
}

}  // namespace

DriverModule::DriverModule(Loaded, TrustedFile file, void* handle, const vibscore_driver* entry)
    : file_(std::move(file)), handle_(handle), entry_(entry) {}

DriverModule::~DriverModule() {
    ::dlclose(handle_);
    // A module the loader keeps (RTLD_NODELETE, a C++ module's unique symbols) keeps its name:
    // its descriptor is kept open for good, so the number is never another file's.
    const std::string name = descriptor_path(*file_.fd);
    if (void* kept = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD)) {
        // Found by name, or only as the same file loaded under another name (which holds no
        // name of this descriptor's).
        link_map* map = nullptr;
        const bool named = ::dlinfo(kept, RTLD_DI_LINKMAP, &map) == 0 && map != nullptr &&
                           map->l_name != nullptr && name == map->l_name;
        ::dlclose(kept);
        if (!named) {
            return;
        }
        static std::mutex mutex;
        static std::vector<std::shared_ptr<const UniqueFd>> kept_open;
        const std::lock_guard lock(mutex);
        kept_open.push_back(file_.fd);
    }
}

std::string entry_problem(void* handle, const vibscore_driver*& entry) {
    using EntryFunction = const vibscore_driver* (*)();
    auto* entry_function =
        reinterpret_cast<EntryFunction>(::dlsym(handle, "vibscore_driver_entry"));
    if (entry_function == nullptr) {
        return "has no vibscore_driver_entry symbol";
    }
    entry = entry_function();
    if (entry == nullptr) {
        return "vibscore_driver_entry() returned NULL";
    }
    if (entry->abi_version < VIBSCORE_DRIVER_ABI_OLDEST ||
        entry->abi_version > VIBSCORE_DRIVER_ABI_VERSION) {
        return "built for driver ABI " + std::to_string(entry->abi_version) +
               ", this vibscored speaks " + std::to_string(VIBSCORE_DRIVER_ABI_OLDEST) + " to " +
               std::to_string(VIBSCORE_DRIVER_ABI_VERSION);
    }
    if (!valid_name(entry->name)) {
        return "its name must be 1-64 of a-z, 0-9 and '-'";
    }
    if (!entry->open || !entry->close || !entry->capabilities || !entry->apply || !entry->off) {
        return "open, close, capabilities, apply and off must all be set";
    }
    return {};
}

std::shared_ptr<DriverModule> DriverModule::load(const TrustedFile& module, uid_t daemon_uid) {
    const std::string shown = "driver module " + module.path.string() + ": ";
    if (auto changed = changed_since_checked(module, daemon_uid)) {
        throw std::runtime_error(shown + *changed);
    }
    // RTLD_LOCAL keeps one module's symbols from resolving another's.
    const std::string name = descriptor_path(*module.fd);
    void* handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
        std::string why = ::dlerror();  // names /proc/self/fd/N, which means nothing in a log
        if (why.starts_with(name)) {
            why.replace(0, name.size(), module.path.string());
        }
        throw std::runtime_error(shown + why);
    }
    const vibscore_driver* entry = nullptr;
    if (const std::string wrong = entry_problem(handle, entry); !wrong.empty()) {
        ::dlclose(handle);
        throw std::runtime_error(shown + wrong);
    }
    return std::make_shared<DriverModule>(Loaded{}, module, handle, entry);
}

std::shared_ptr<DriverModule> DriverModule::load(const std::filesystem::path& path,
                                                 uid_t daemon_uid) {
    auto opened = open_trusted_module(path, daemon_uid);
    if (!opened.file) {
        throw std::runtime_error("driver module " + path.string() + ": " + opened.refusal);
    }
    return load(*opened.file, daemon_uid);
}

std::unique_ptr<Actuator> open_external_actuator(
    std::shared_ptr<DriverModule> module, const std::map<std::string, std::string>& settings) {
    std::vector<vibscore_setting> c_settings;
    for (const auto& [key, value] : settings) {
        c_settings.push_back({key.c_str(), value.c_str()});
    }
    ErrorText error;
    void* handle =
        module->entry().open(c_settings.data(), c_settings.size(), error.data(), error.size());
    if (handle == nullptr) {
        throw DeviceError(std::string(module->entry().name) + ": " + error.message("open failed"));
    }
    return std::make_unique<ExternalActuator>(std::move(module), handle);
}

}  // namespace vibscore::drivers
