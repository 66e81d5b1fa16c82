#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "client/editor/buttons.hpp"

namespace vibscore::editor {

// Which input key is which of the six buttons. A key can give two buttons, one for a short
// press and one for a long press, so a phone's three keys (volume up, volume down, power) can
// drive all six.
class ButtonMap {
  public:
    // Volume up/down: Up/Down, held: Right/Left; power: Select, held: Back.
    static ButtonMap phone();
    // "up=KEY_VOLUMEUP,right=long:KEY_VOLUMEUP,...,hold-ms=500": a button per entry, a key by
    // its evdev name (KEY_...) or code; "long:" for a long press; hold-ms sets how long is
    // long. Entries override the phone map's; "none" starts from an empty map. Throws
    // std::invalid_argument naming the entry and the value at fault.
    static ButtonMap parse(std::string_view text);

    void assign(Button button, unsigned code, bool long_press);
    std::optional<Button> short_press(unsigned code) const;
    std::optional<Button> long_press(unsigned code) const;
    bool has_long_press(unsigned code) const { return long_.contains(code); }
    int hold_ms() const { return hold_ms_; }
    // "KEY_VOLUMEUP" or the code as a number when libevdev has no name for it.
    static std::string key_name(unsigned code);

  private:
    std::map<unsigned, Button> short_;
    std::map<unsigned, Button> long_;
    int hold_ms_ = 500;
};

}  // namespace vibscore::editor
