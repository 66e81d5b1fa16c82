#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

// The formats `vibscore convert` reads and writes, and how it tells them apart.
namespace vibscore::formats {

enum class Format { score, ahap, android_json, android_xml, android_envelope, rtttl, midi };

// "score", "ahap", "android-json", "android-xml", "android-envelope", "rtttl", "midi".
std::string_view to_string(Format format);
std::optional<Format> parse_format(std::string_view name);
// The names of the formats vibscore reads (for --from) and writes (for --to), joined by ", ",
// for messages: a format offered is one that works.
std::string readable_format_names();
std::string writable_format_names();

// From the file name: .score.xml and other .xml a score, .vibration.xml Android XML, .ahap,
// .json (Android), .rtttl and .rtx, .mid and .midi. Nothing for an unknown extension.
std::optional<Format> format_of_path(const std::filesystem::path& path);

// A .xml file may be a score or Android's XML: its root element tells.
Format format_of_xml_text(std::string_view text);

bool can_read(Format format);   // all but android-envelope, which android-xml reads
bool can_write(Format format);  // all but rtttl

}  // namespace vibscore::formats
