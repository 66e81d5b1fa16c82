#include "daemon/bus_errors.hpp"

#include <string>

#include "common/log.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/playback_thread.hpp"
#include "daemon/player.hpp"
#include "daemon/registry/registry.hpp"
#include "daemon/request_error.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "score/document_error.hpp"

namespace vibscore::daemon {

namespace {

using namespace haptics1::errors;

const char* error_name(RegistryError::Code code) {
    switch (code) {
        case RegistryError::Code::invalid_document:
            return kInvalidDocument;
        case RegistryError::Code::not_found:
            return kNotFound;
        case RegistryError::Code::permission_denied:
            return kPermissionDenied;
        case RegistryError::Code::limit_exceeded:
            return kLimitExceeded;
        case RegistryError::Code::in_use:
            return kBusy;
    }
    return kInvalidDocument;
}

const char* error_name(RequestError::Code code) {
    switch (code) {
        case RequestError::Code::invalid:
            return kInvalidDocument;
        case RequestError::Code::out_of_range:
            return kOutOfRange;
        case RequestError::Code::not_found:
            return kNotFound;
        case RequestError::Code::permission_denied:
            return kPermissionDenied;
        case RequestError::Code::limit_exceeded:
            return kLimitExceeded;
    }
    return kInvalidDocument;
}

}  // namespace

sdbus::Error to_bus_error(const char* method, const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const sdbus::Error& bus_error) {
        return bus_error;
    } catch (const RequestError& request_error) {
        return dbus::bus_error(error_name(request_error.code()), request_error.what());
    } catch (const RegistryError& registry_error) {
        return dbus::bus_error(error_name(registry_error.code()), registry_error.what());
    } catch (const DocumentError& document_error) {
        return dbus::bus_error(kInvalidDocument, document_error.what());
    } catch (const PlayerBusy& busy) {
        return dbus::bus_error(kBusy, busy.what());
    } catch (const CoolingDown& cooling) {
        return dbus::bus_error(kCoolingDown, cooling.what());
    } catch (const drivers::DeviceError& device_error) {
        return dbus::bus_error(kDevice, device_error.what());
    } catch (const PlaybackStuck& stuck) {
        log::error(std::string(method) + ": " + stuck.what());
        return dbus::bus_error(kDevice, stuck.what());
    } catch (const std::exception& unexpected) {
        log::error(std::string(method) + " failed unexpectedly: " + unexpected.what());
        return dbus::bus_error(kFailed, std::string(method) + " failed: " + unexpected.what());
    } catch (...) {
        log::error(std::string(method) + " failed with an unknown exception");
        return dbus::bus_error(kFailed, std::string(method) + " failed");
    }
}

}  // namespace vibscore::daemon
