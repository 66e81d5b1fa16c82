#include "tests/fakes/fake_ff_device.hpp"

#include <cerrno>
#include <span>
#include <utility>

namespace vibscore::testing {
namespace {

using drivers::FfDeviceError;
using drivers::FfFeatures;

class FakeFfDevice : public drivers::FfDevice {
  public:
    explicit FakeFfDevice(std::shared_ptr<FakeFfKernel> kernel)
        : kernel_(std::move(kernel)), generation_(kernel_->generation) {}

    const std::string& path() const override { return kernel_->path; }
    const std::string& name() const override { return name_; }
    FfFeatures features() const override { return kernel_->features; }

    void upload(ff_effect& effect) override {
        check("EVIOCSFF");
        FfCall call{FfCall::Kind::upload, effect};
        if (effect.id == -1) {
            if (static_cast<int>(kernel_->live.size()) >= kernel_->features.effect_slots) {
                throw FfDeviceError(path(), "EVIOCSFF", ENOSPC);
            }
            effect.id = static_cast<std::int16_t>(kernel_->next_id++);
        } else {
            // The kernel updates in place only an effect of the same type.
            const auto found = kernel_->live.find(effect.id);
            if (found == kernel_->live.end() || found->second != effect.type) {
                throw FfDeviceError(path(), "EVIOCSFF", EINVAL);
            }
        }
        kernel_->live[effect.id] = effect.type;
        call.id = effect.id;
        record(std::move(call));
    }

    void erase(int id) override {
        check("EVIOCRMFF");
        if (kernel_->live.erase(id) == 0) {
            throw FfDeviceError(path(), "EVIOCRMFF", EINVAL);
        }
        FfCall call{FfCall::Kind::erase};
        call.id = id;
        record(std::move(call));
    }

    void write(std::span<const input_event> events) override {
        check("write");
        FfCall call{FfCall::Kind::write};
        for (const auto& event : events) {
            call.events.push_back({event.type, event.code, event.value});
        }
        record(std::move(call));
    }

  private:
    void check(const char* what) {
        if (!kernel_->present || generation_ != kernel_->generation) {
            throw FfDeviceError(path(), what, ENODEV);
        }
        if (const int error = std::exchange(kernel_->fail_next_errno, 0)) {
            throw FfDeviceError(path(), what, error);
        }
    }
    void record(FfCall call) {
        call.generation = generation_;
        kernel_->calls.push_back(std::move(call));
    }

    std::shared_ptr<FakeFfKernel> kernel_;
    unsigned generation_;
    std::string name_ = "fake vibrator";
};

}  // namespace

std::ostream& operator<<(std::ostream& out, const WrittenEvent& event) {
    return out << "{" << event.type << ", " << event.code << ", " << event.value << "}";
}

drivers::FfDeviceOpener fake_ff_opener(const std::shared_ptr<FakeFfKernel>& kernel) {
    return [kernel]() -> std::unique_ptr<drivers::FfDevice> {
        ++kernel->opens;
        if (!kernel->present) {
            throw FfDeviceError(kernel->path, "open", ENOENT);
        }
        return std::make_unique<FakeFfDevice>(kernel);
    };
}

}  // namespace vibscore::testing
