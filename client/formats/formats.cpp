#include "client/formats/formats.hpp"

#include <array>
#include <string>

#include "score/xml_support.hpp"

namespace vibscore::formats {

namespace {

constexpr std::array<std::pair<Format, std::string_view>, 7> kNames{{
    {Format::score, "score"},
    {Format::ahap, "ahap"},
    {Format::android_json, "android-json"},
    {Format::android_xml, "android-xml"},
    {Format::android_envelope, "android-envelope"},
    {Format::rtttl, "rtttl"},
    {Format::midi, "midi"},
}};

}  // namespace

std::string_view to_string(Format format) {
    for (const auto& [each, name] : kNames) {
        if (each == format) {
            return name;
        }
    }
    return "?";
}

std::optional<Format> parse_format(std::string_view name) {
    for (const auto& [each, each_name] : kNames) {
        if (each_name == name) {
            return each;
        }
    }
    return std::nullopt;
}

namespace {

std::string names_where(bool (*keep)(Format)) {
    std::string names;
    for (const auto& [format, name] : kNames) {
        if (keep(format)) {
            names += (names.empty() ? "" : ", ") + std::string(name);
        }
    }
    return names;
}

}  // namespace

std::string readable_format_names() {
    return names_where(can_read);
}

std::string writable_format_names() {
    return names_where(can_write);
}

std::optional<Format> format_of_path(const std::filesystem::path& path) {
    const std::string name = path.filename().string();
    const auto ends = [&](std::string_view suffix) { return name.ends_with(suffix); };
    if (ends(".vibration.xml")) {
        return Format::android_xml;
    }
    if (ends(".xml")) {
        return Format::score;
    }
    if (ends(".ahap")) {
        return Format::ahap;
    }
    if (ends(".json")) {
        return Format::android_json;
    }
    if (ends(".rtttl") || ends(".rtx")) {
        return Format::rtttl;
    }
    if (ends(".mid") || ends(".midi")) {
        return Format::midi;
    }
    return std::nullopt;
}

Format format_of_xml_text(std::string_view text) {
    const auto root = xml::root_name(text);
    return root == "vibration-effect" || root == "vibration-select" || root == "vibration"
               ? Format::android_xml
               : Format::score;
}

bool can_read(Format format) {
    return format != Format::android_envelope;
}

bool can_write(Format format) {
    return format != Format::rtttl;
}

}  // namespace vibscore::formats
