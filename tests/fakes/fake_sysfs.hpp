#pragma once

#include <gtest/gtest.h>

#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/sysfs_attributes.hpp"
#include "tests/support/support.hpp"

namespace vibscore::testing {

// A fake kernel behind SysfsAttributes: real files in a temporary tree (written through the real
// implementation), plus what the kernel does on some writes: export/unexport of PWM channels
// and their rules (duty_cycle never above the period, no period 0), the LED transient trigger's
// attributes, brightness following activate. Writes are logged; any attribute can be made to
// fail with an errno.
class FakeSysfs : public std::enable_shared_from_this<FakeSysfs> {
  public:
    explicit FakeSysfs(std::filesystem::path root) : root_(std::move(root)) {}

    const std::filesystem::path& root() const { return root_; }

    // class/pwm/pwmchipN with export and unexport.
    void add_pwm_chip(int chip) {
        create("class/pwm/pwmchip" + std::to_string(chip) + "/export", "");
        create("class/pwm/pwmchip" + std::to_string(chip) + "/unexport", "");
    }
    // An already exported channel in the given state.
    void add_pwm_channel(int chip, int channel, std::int64_t period, std::int64_t duty,
                         bool enabled) {
        const std::string dir =
            "class/pwm/pwmchip" + std::to_string(chip) + "/pwm" + std::to_string(channel);
        create(dir + "/period", std::to_string(period));
        create(dir + "/duty_cycle", std::to_string(duty));
        create(dir + "/enable", enabled ? "1" : "0");
        create(dir + "/polarity", "normal");
    }
    // class/leds/NAME with brightness, max_brightness and trigger ("none" selected).
    void add_led(const std::string& name, const std::string& selected = "none") {
        create("class/leds/" + name + "/brightness", "0");
        create("class/leds/" + name + "/max_brightness", "255");
        create("class/leds/" + name + "/trigger", trigger_list(selected));
    }
    void add_timed_output(const std::string& name) {
        create("class/timed_output/" + name + "/enable", "0");
    }
    void create(const std::string& relative, const std::string& content) {
        const auto path = root_ / relative;
        std::filesystem::create_directories(path.parent_path());
        std::ofstream(path) << content;
    }

    // The content of an attribute ("<missing>" when it is not there).
    std::string value(const std::string& relative) const {
        std::ifstream in(root_ / relative);
        if (!in) {
            return "<missing>";
        }
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        return text;
    }
    bool exists(const std::string& relative) const {
        return std::filesystem::exists(root_ / relative);
    }

    // Every accepted write as "relative/path=value", in order.
    const std::vector<std::string>& writes() const { return writes_; }
    void clear_writes() { writes_.clear(); }

    // Writes to `relative` fail with `error` until heal().
    void fail(const std::string& relative, int error) { failures_[relative] = error; }
    void heal() { failures_.clear(); }

    // A new PWM channel stays invisible for this many exists() calls after its export; -1:
    // it never shows (but can be unexported).
    void hide_exported_channels_for(int polls) { hide_polls_ = polls; }

    std::unique_ptr<drivers::SysfsAttributes> attributes();

  private:
    class Attributes;

    static std::string trigger_list(const std::string& selected) {
        std::string text;
        for (const char* name : {"none", "timer", "transient"}) {
            text += (text.empty() ? "" : " ") +
                    (name == selected ? "[" + std::string(name) + "]" : std::string(name));
        }
        return text;
    }

    [[noreturn]] void refuse(const std::filesystem::path& path, std::string_view value,
                             int error) const {
        throw drivers::DeviceError(path.string() + ": cannot write \"" + std::string(value) +
                                   "\": " + std::strerror(error));
    }

    static std::int64_t number(std::string_view text) {
        std::int64_t value = -1;
        std::from_chars(text.data(), text.data() + text.size(), value);
        return value;
    }
    std::int64_t number_at(const std::filesystem::path& path) const {
        return number(value(std::filesystem::relative(path, root_).string()));
    }

    // The kernel's side of a write: validation and side effects. Returns false when the value
    // is not to be stored in the file (write-only attributes).
    bool kernel_write(const std::filesystem::path& path, std::string_view value) {
        const std::string name = path.filename().string();
        const auto dir = path.parent_path();
        if (name == "export") {
            const auto channel = dir / ("pwm" + std::string(value));
            if (std::filesystem::exists(channel)) {
                refuse(path, value, EBUSY);
            }
            add_pwm_channel_at(std::filesystem::relative(channel, root_).string());
            hidden_ = channel;
            hidden_polls_left_ = hide_polls_ < 0 ? std::numeric_limits<int>::max() : hide_polls_;
            return false;
        }
        if (name == "unexport") {
            const auto channel = dir / ("pwm" + std::string(value));
            if (!std::filesystem::exists(channel)) {
                refuse(path, value, EINVAL);
            }
            std::filesystem::remove_all(channel);
            return false;
        }
        const bool pwm = dir.filename().string().rfind("pwm", 0) == 0 &&
                         dir.parent_path().filename().string().rfind("pwmchip", 0) == 0;
        if (pwm && name == "period") {
            const auto period = number(value);
            if (period <= 0 || period < number_at(dir / "duty_cycle")) {
                refuse(path, value, EINVAL);
            }
        }
        if (pwm && name == "duty_cycle") {
            const auto period = number_at(dir / "period");
            if (period <= 0 || number(value) < 0 || number(value) > period) {
                refuse(path, value, EINVAL);
            }
        }
        if (pwm && name == "enable") {
            if ((value != "0" && value != "1") ||
                (value == "1" && number_at(dir / "period") <= 0)) {
                refuse(path, value, EINVAL);
            }
        }
        if (dir.parent_path().filename() == "leds") {
            return led_write(dir, name, value, path);
        }
        return true;
    }

    void add_pwm_channel_at(const std::string& relative) {
        create(relative + "/period", "0");
        create(relative + "/duty_cycle", "0");
        create(relative + "/enable", "0");
        create(relative + "/polarity", "normal");
    }

    bool led_write(const std::filesystem::path& led, const std::string& name,
                   std::string_view value, const std::filesystem::path& path) {
        const auto relative = std::filesystem::relative(led, root_).string();
        if (name == "trigger") {
            const std::string trigger(value);
            if (trigger != "none" && trigger != "timer" && trigger != "transient") {
                refuse(path, value, EINVAL);
            }
            // Changing the trigger switches the LED off; transient brings its attributes.
            create(relative + "/brightness", "0");
            for (const char* attribute : {"activate", "state", "duration"}) {
                std::filesystem::remove(led / attribute);
            }
            if (trigger == "transient") {
                create(relative + "/activate", "0");
                create(relative + "/state", "0");
                create(relative + "/duration", "0");
            }
            create(relative + "/trigger", trigger_list(trigger));
            return false;
        }
        if (name == "activate" || name == "state") {
            if (value != "0" && value != "1") {
                refuse(path, value, EINVAL);
            }
        }
        if (name == "activate") {
            const bool on = value == "1" && this->value(relative + "/state") == "1" &&
                            number(this->value(relative + "/duration")) > 0;
            create(relative + "/brightness", on ? "255" : "0");
        }
        return true;
    }

    std::filesystem::path root_;
    std::vector<std::string> writes_;
    std::map<std::string, int> failures_;
    int hide_polls_ = 0;
    std::filesystem::path hidden_;
    int hidden_polls_left_ = 0;
};

class FakeSysfs::Attributes final : public drivers::SysfsAttributes {
  public:
    explicit Attributes(std::shared_ptr<FakeSysfs> sysfs)
        : sysfs_(std::move(sysfs)), files_(drivers::make_kernel_sysfs_attributes()) {}

    void write(const std::filesystem::path& attribute, std::string_view value) override {
        const auto relative = std::filesystem::relative(attribute, sysfs_->root_).string();
        if (const auto failure = sysfs_->failures_.find(relative);
            failure != sysfs_->failures_.end()) {
            sysfs_->refuse(attribute, value, failure->second);
        }
        if (!std::filesystem::exists(attribute)) {
            sysfs_->refuse(attribute, value, ENOENT);
        }
        if (sysfs_->kernel_write(attribute, value)) {
            files_->write(attribute, value);
        }
        sysfs_->writes_.push_back(relative + "=" + std::string(value));
    }

    std::string read(const std::filesystem::path& attribute) override {
        return files_->read(attribute);
    }

    bool exists(const std::filesystem::path& path) override {
        const auto& hidden = sysfs_->hidden_;
        const auto inside = path.lexically_relative(hidden);
        if (!hidden.empty() && !inside.empty() && *inside.begin() != ".." &&
            sysfs_->hidden_polls_left_ > 0) {
            --sysfs_->hidden_polls_left_;
            return false;
        }
        return files_->exists(path);
    }

  private:
    std::shared_ptr<FakeSysfs> sysfs_;
    std::unique_ptr<drivers::SysfsAttributes> files_;
};

inline std::unique_ptr<drivers::SysfsAttributes> FakeSysfs::attributes() {
    return std::make_unique<Attributes>(shared_from_this());
}

// The fixture of a sysfs backend's tests: a fake kernel tree the backend is opened on.
class SysfsTreeTest : public ::testing::Test {
  protected:
    std::string path(const std::string& relative) const {
        return (tree.path() / relative).string();
    }

    // The message of whatever `open` throws (DeviceError or invalid_argument).
    template <typename Open>
    static std::string error_of(Open&& open) {
        try {
            open();
        } catch (const std::exception& error) {
            return error.what();
        }
        return "<no error>";
    }

    TempDir tree;
    std::shared_ptr<FakeSysfs> sysfs = std::make_shared<FakeSysfs>(tree.path());
};

}  // namespace vibscore::testing
