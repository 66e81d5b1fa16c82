#pragma once

#include <cerrno>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "daemon/drivers/gpio_lines_chip.hpp"

namespace vibscore::testing {

// Chips behind the libgpiod seam of gpio_lines_chip.hpp, by path: what the shared part of
// open_gpio_lines() (finding the chip, checking lines, messages, the release) is tested on.
// Every call the code makes is written to calls() in order, e.g. "open /dev/gpiochip0",
// "request 0,1 for vibscored", "set 1,0", "release". Errors are std::system_error with an
// errno, as from libgpiod.
class FakeGpioChips {
  public:
    struct Chip {
        std::string label;
        unsigned lines = 4;
        std::map<unsigned, std::string> users;  // lines another consumer holds
        int request_error = 0;                  // errno of every request; 0 grants it
    };

    void add(const std::filesystem::path& path, Chip chip) { chips_[path] = std::move(chip); }
    // Opening `path` fails with `error` (when no chip is there either, with ENOENT).
    void refuse(const std::filesystem::path& path, int error) { refused_[path] = error; }
    // From now on setting values fails with EIO.
    void fail_sets() { state_->fail_sets = true; }

    drivers::GpioChipOpener opener() {
        return [this](const std::filesystem::path& path) -> std::unique_ptr<drivers::GpioChip> {
            state_->calls.push_back("open " + path.string());
            if (const auto refused = refused_.find(path); refused != refused_.end()) {
                throw std::system_error(refused->second, std::generic_category(), path.string());
            }
            const auto found = chips_.find(path);
            if (found == chips_.end()) {
                throw std::system_error(ENOENT, std::generic_category(), path.string());
            }
            return std::make_unique<OpenChip>(path.filename().string(), found->second, state_);
        };
    }

    const std::vector<std::string>& calls() const { return state_->calls; }

  private:
    struct State {
        std::vector<std::string> calls;
        bool fail_sets = false;
    };

    static std::string joined(const std::vector<unsigned>& offsets) {
        std::string text;
        for (const unsigned offset : offsets) {
            text += (text.empty() ? "" : ",") + std::to_string(offset);
        }
        return text;
    }

    class Request final : public drivers::GpioLineRequest {
      public:
        explicit Request(std::shared_ptr<State> state) : state_(std::move(state)) {}
        void set_values(const std::vector<int>& values) override {
            if (state_->fail_sets) {
                throw std::system_error(EIO, std::generic_category(), "setting line values");
            }
            std::string text;
            for (const int value : values) {
                text += (text.empty() ? "" : ",") + std::to_string(value);
            }
            state_->calls.push_back("set " + text);
        }
        void release() override { state_->calls.push_back("release"); }

      private:
        std::shared_ptr<State> state_;
    };

    class OpenChip final : public drivers::GpioChip {
      public:
        OpenChip(std::string name, Chip chip, std::shared_ptr<State> state)
            : name_(std::move(name)), chip_(std::move(chip)), state_(std::move(state)) {}
        std::string name() const override { return name_; }
        std::string label() const override { return chip_.label; }
        unsigned line_count() const override { return chip_.lines; }
        std::optional<std::string> user(unsigned offset) const override {
            const auto found = chip_.users.find(offset);
            if (found == chip_.users.end()) {
                return std::nullopt;
            }
            return found->second;
        }
        std::unique_ptr<drivers::GpioLineRequest> request_outputs(
            const std::vector<unsigned>& offsets, const std::string& consumer) override {
            state_->calls.push_back("request " + joined(offsets) + " for " + consumer);
            if (chip_.request_error != 0) {
                throw std::system_error(chip_.request_error, std::generic_category(),
                                        "requesting lines");
            }
            return std::make_unique<Request>(state_);
        }

      private:
        std::string name_;
        Chip chip_;
        std::shared_ptr<State> state_;
    };

    std::map<std::filesystem::path, Chip> chips_;
    std::map<std::filesystem::path, int> refused_;
    std::shared_ptr<State> state_ = std::make_shared<State>();
};

}  // namespace vibscore::testing
