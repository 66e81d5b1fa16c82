#pragma once

#include <stdexcept>
#include <string>

namespace vibscore::daemon {

// A request the daemon refuses because of what the caller sent or asked. The bus service sends
// it as the named D-Bus error code() stands for, with what() as the message, which names the
// option or value at fault.
class RequestError : public std::runtime_error {
  public:
    // out_of_range: a well-formed number outside what its argument allows (Intensity 1.5, repeat
    // -2), told apart from a malformed request so a client can say which bound it crossed.
    enum class Code { invalid, out_of_range, not_found, permission_denied, limit_exceeded };

    RequestError(Code code, const std::string& message)
        : std::runtime_error(message), code_(code) {}

    Code code() const { return code_; }

  private:
    Code code_;
};

}  // namespace vibscore::daemon
