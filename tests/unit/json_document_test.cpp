// The tree's one JSON reader (json/): where each value began, its limits at their edges
// (nesting, file size, numbers), duplicate keys, and the trailing commas it tolerates when
// asked to.
#include <gtest/gtest.h>

#include <string>

#include "json/json_document.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

std::string error_of(const std::string& text, JsonOptions options = {}) {
    try {
        JsonDocument(text, "t.json", options);
    } catch (const DocumentError& error) {
        return error.what();
    }
    return "<no error>";
}

std::string nested_arrays(std::size_t depth) {
    return std::string(depth, '[') + std::string(depth, ']');
}

TEST(AJsonDocument, RemembersTheLineAndColumnWhereEachValueAndKeyBegan) {
    const JsonDocument document("{\n  \"a\": [1, \"two\",\n   {\"b\": null}],\n  \"c\": true\n}",
                                "t.json");
    const JsonValue& root = document.root();
    ASSERT_EQ(root.kind, JsonValue::Kind::object);
    ASSERT_EQ(root.members.size(), 2u);
    const JsonValue& a = root.members[0].value;
    EXPECT_EQ(document.where(root.members[0].key_offset).line, 2);
    EXPECT_EQ(document.where(root.members[0].key_offset).column, 3);
    EXPECT_EQ(document.where(a).column, 8);
    ASSERT_EQ(a.items.size(), 3u);
    EXPECT_EQ(document.where(a.items[1]).column, 12);
    EXPECT_EQ(a.items[1].text, "two");
    const JsonValue& b = *a.items[2].find("b");
    EXPECT_EQ(b.kind, JsonValue::Kind::null);
    EXPECT_EQ(document.where(b).line, 3);
    EXPECT_EQ(document.where(b).column, 10);
    EXPECT_EQ(document.where(*root.find("c")).line, 4);
    EXPECT_TRUE(root.find("c")->boolean);
    EXPECT_EQ(root.find("d"), nullptr);
}

TEST(AJsonDocument, TellsWholeNumbersFromOnesWithAFractionOrExponent) {
    const JsonDocument document("[3, -4, 3.0, 1e2, 18446744073709551615]", "t.json");
    const auto& items = document.root().items;
    EXPECT_TRUE(items[0].integral);
    EXPECT_TRUE(items[1].integral);
    EXPECT_EQ(items[1].number, -4.0);
    EXPECT_FALSE(items[2].integral);
    EXPECT_FALSE(items[3].integral);
    EXPECT_EQ(items[3].number, 100.0);
    EXPECT_TRUE(items[4].integral);
}

TEST(AJsonDocument, AcceptsNestingToItsLimitAndRefusesOneLevelMore) {
    EXPECT_EQ(JsonDocument::max_depth, 64u);
    EXPECT_NO_THROW(JsonDocument(nested_arrays(JsonDocument::max_depth), "t.json"));
    EXPECT_EQ(error_of(nested_arrays(JsonDocument::max_depth + 1)),
              "t.json:1:65: nested deeper than 64 levels");
    // Objects count as arrays do.
    std::string objects;
    for (std::size_t i = 0; i < JsonDocument::max_depth; ++i) {
        objects += "{\"a\":";
    }
    EXPECT_NO_THROW(JsonDocument(objects + "1" + std::string(64, '}'), "t.json"));
    EXPECT_EQ(error_of(objects + "[]" + std::string(64, '}')),
              "t.json:1:321: nested deeper than 64 levels");
}

TEST(AJsonDocument, RefusesADeepThemeAtItsFirstLevelTooMany) {
    // Issue 27: 10,000 levels of a 20 KB theme took 14.9 s and 1.7 GB in the old feedback
    // reader; now the 65th bracket ends the reading (the fuzz seed deep-theme.json is this).
    const std::string deep =
        "{\"name\": \"deep\",\n \"profiles\": " + nested_arrays(10'000) + "}\n";
    EXPECT_EQ(error_of(deep), "t.json:2:77: nested deeper than 64 levels");
}

TEST(AJsonDocument, RefusesAKeyGivenTwiceInOneObjectAtItsSecondPlace) {
    EXPECT_EQ(error_of("{\"a\": 1,\n \"b\": {\"a\": 2},\n \"a\": 3}"),
              "t.json:3:2: key \"a\" appears twice in one object");
    EXPECT_NO_THROW(JsonDocument("[{\"a\": 1}, {\"a\": 2}]", "t.json"));
}

TEST(AJsonDocument, RefusesANumberTooLargeForADoubleWhereItStands) {
    EXPECT_EQ(error_of("{\"magnitude\":\n  1e999}"), "t.json:2:3: number 1e999 is too large");
    EXPECT_EQ(error_of("[0, -1e999]"), "t.json:1:5: number -1e999 is too large");
    // The largest double is still one; a tiny number rounds to zero as strtod rounds it.
    EXPECT_NO_THROW(JsonDocument("[1.7976931348623157e308, 1e-999]", "t.json"));
}

TEST(AJsonDocument, NamesTheLineAndColumnOfTextThatIsNotJson) {
    EXPECT_EQ(error_of("{\n  \"a\": [,]\n}"),
              "t.json:2:9: not JSON: syntax error while parsing value - unexpected ','; "
              "expected '[', '{', or a literal");
    EXPECT_EQ(error_of("[1,\n"),
              "t.json:2:1: not JSON: syntax error while parsing value - unexpected end of input; "
              "expected '[', '{', or a literal");
    // The same words from every nlohmann release (they differ for an empty text).
    EXPECT_EQ(error_of(""), "t.json:1:1: not JSON: the text is empty");
    EXPECT_EQ(error_of("\n  "), "t.json:2:3: not JSON: the text is empty");
}

TEST(AJsonDocument, RefusesTrailingCommasUnlessAskedToTolerateThem) {
    const std::string text = "{\"Pattern\": [\n  {\"Time\": 0.0,},\n  2,\n]\n,}";
    EXPECT_EQ(error_of(text),
              "t.json:2:16: not JSON: syntax error while parsing object key - unexpected '}'; "
              "expected string literal");
    const JsonDocument tolerant(text, "t.json", {.trailing_commas = true});
    const auto& pattern = tolerant.root().find("Pattern")->items;
    ASSERT_EQ(pattern.size(), 2u);
    EXPECT_EQ(pattern[0].find("Time")->number, 0.0);
    EXPECT_EQ(tolerant.where(pattern[1]).line, 3);  // offsets are those of the file
    ASSERT_EQ(tolerant.trailing_commas().size(), 3u);
    EXPECT_EQ(tolerant.where(tolerant.trailing_commas()[0]).line, 2);
    EXPECT_EQ(tolerant.where(tolerant.trailing_commas()[0]).column, 15);
    EXPECT_EQ(tolerant.where(tolerant.trailing_commas()[2]).line, 5);
    EXPECT_TRUE(
        JsonDocument("[1, 2]", "t.json", {.trailing_commas = true}).trailing_commas().empty());
}

TEST(AJsonDocument, ToleratesOnlyACommaThatFollowsAValue) {
    const JsonOptions tolerant{.trailing_commas = true};
    // No value before it: still not JSON.
    EXPECT_EQ(error_of("[,]", tolerant),
              "t.json:1:2: not JSON: syntax error while parsing value - unexpected ','; "
              "expected '[', '{', or a literal");
    EXPECT_EQ(error_of("[1,,]", tolerant),
              "t.json:1:4: not JSON: syntax error while parsing value - unexpected ','; "
              "expected '[', '{', or a literal");
    EXPECT_EQ(error_of("{\"a\":,}", tolerant),
              "t.json:1:6: not JSON: syntax error while parsing value - unexpected ','; "
              "expected '[', '{', or a literal");
    // Commas and brackets inside strings are text, escaped quotes included.
    const JsonDocument strings("[\"a,]\", \"b\\\",]\" ,\n]", "t.json", tolerant);
    ASSERT_EQ(strings.root().items.size(), 2u);
    EXPECT_EQ(strings.root().items[0].text, "a,]");
    EXPECT_EQ(strings.root().items[1].text, "b\",]");
    EXPECT_EQ(strings.trailing_commas().size(), 1u);
    // After each kind of value.
    EXPECT_EQ(
        JsonDocument("[true, null, 1.5, {}, [], \"x\",]", "t.json", tolerant).root().items.size(),
        6u);
}

TEST(ReadingAJsonFile, AcceptsOneMebibyteAndRefusesOneByteMore) {
    testing::TempDir dir;
    std::string text = "[0" + std::string(max_json_file_bytes - 3, ' ') + "]";
    ASSERT_EQ(text.size(), max_json_file_bytes);
    EXPECT_EQ(read_json_file(dir.write("limit.json", text).string()).root().items.size(), 1u);
    const auto over = dir.write("over.json", text + " ").string();
    EXPECT_EQ(testing::first_diagnostic([&] { read_json_file(over); }).message,
              "larger than 1048576 bytes, the limit for a JSON file");
}

TEST(ReadingAJsonFile, NamesAFileThatCannotBeOpenedAndTheFileOfAnError) {
    try {
        read_json_file("/nonexistent/theme.json");
        FAIL() << "no error";
    } catch (const DocumentError& error) {
        EXPECT_STREQ(error.what(),
                     "/nonexistent/theme.json: cannot open: No such file or directory");
    }
    testing::TempDir dir;
    const auto path = dir.write("bad.json", "{\n  \"a\": 1e999\n}").string();
    try {
        read_json_file(path);
        FAIL() << "no error";
    } catch (const DocumentError& error) {
        EXPECT_EQ(error.what(), path + ":2:8: number 1e999 is too large");
    }
}

TEST(ReadingAJsonFile, ReadsWithTheOptionsItIsGiven) {
    testing::TempDir dir;
    const auto path = dir.write("t.json", "[1,]").string();
    EXPECT_THROW(read_json_file(path), DocumentError);
    EXPECT_EQ(read_json_file(path, {.trailing_commas = true}).trailing_commas().size(), 1u);
}

}  // namespace
}  // namespace vibscore
