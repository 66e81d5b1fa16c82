#pragma once

#include <optional>
#include <string>
#include <string_view>

// How documents are named in vibscored's registry, and how a score's <Clef href> names a registry
// clef. The daemon's registry and the offline tools follow the same rule (docs/score-format.md,
// "How a score names its clefs").
namespace vibscore {

inline constexpr std::string_view kScoreSuffix = ".score.xml";
inline constexpr std::string_view kClefSuffix = ".clef.xml";
inline constexpr std::string_view kNameRule =
    "a name is 1 to 64 of a-z 0-9 . _ -, starting with a letter or a digit";

// Whether name is a valid registry name: 1-64 of [a-z0-9._-], starting with [a-z0-9].
bool is_valid_name(std::string_view name);

// The registry clef an href names: "NAME.clef.xml", "NAME.xml" or "NAME", with no folder in it.
// nullopt for a path ("clefs/x.clef.xml") or an invalid name.
std::optional<std::string> clef_name_in_href(std::string_view href);

}  // namespace vibscore
