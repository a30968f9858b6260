// Text from captures goes into JSON and XML as UTF-8: well-formed sequences pass, any
// other byte becomes U+FFFD (RFC 3629's table of well-formed byte sequences).
#include <gtest/gtest.h>

#include "core/utf8.h"
#include "sinks/event_format.h"
#include "sinks/xml_escape.h"

using namespace busdecode;

namespace {

const std::string kReplacement = "\xEF\xBF\xBD";

TEST(Utf8, WellFormedSequencesHaveTheirLength) {
    for (const auto& [text, length] : std::vector<std::pair<std::string, std::size_t>>{
             {"\xC2\xB5", 2},           // µ, the lowest two-byte lead
             {"\xDF\xBF", 2},           // U+07FF
             {"\xE0\xA0\x80", 3},       // U+0800, the shortest three-byte form
             {"\xE2\x82\xAC", 3},       // €
             {"\xED\x9F\xBF", 3},       // U+D7FF, below the surrogates
             {"\xEF\xBF\xBD", 3},       // U+FFFD
             {"\xF0\x90\x80\x80", 4},   // U+10000
             {"\xF4\x8F\xBF\xBF", 4}})  // U+10FFFF, the last code point
        EXPECT_EQ(utf8SequenceLength(text, 0), length) << text;
}

TEST(Utf8, IllFormedBytesStartNoSequence) {
    for (const std::string text : {"\x80",              // a continuation byte alone
                                   "\xC0\xAF",          // overlong '/'
                                   "\xC1\xBF",          // overlong
                                   "\xE0\x9F\xBF",      // overlong three-byte form
                                   "\xED\xA0\x80",      // a surrogate, U+D800
                                   "\xF0\x8F\xBF\xBF",  // overlong four-byte form
                                   "\xF4\x90\x80\x80",  // past U+10FFFF
                                   "\xF5\x80\x80\x80",  // no such lead byte
                                   "\xFF",              // never in UTF-8
                                   "\xE2\x82",          // cut short
                                   "\xE2\x28\xA1"})     // a continuation byte missing
        EXPECT_EQ(utf8SequenceLength(text, 0), 0u) << testing::PrintToString(text);
}

TEST(Utf8, JsonStringsAreAlwaysUtf8) {
    // A $date of Latin-1 bytes, and good text around bad bytes.
    EXPECT_EQ(valueToJson(std::string("\xFF\xFE")), "\"" + kReplacement + kReplacement + "\"");
    EXPECT_EQ(valueToJson(std::string("caf\xE9 \xE2\x82\xAC")),
              "\"caf" + kReplacement + " \xE2\x82\xAC\"");
    EXPECT_EQ(valueToJson(std::string("\xE2\x82")), "\"" + kReplacement + kReplacement + "\"");
    EXPECT_EQ(valueToJson(std::string("a\"\\\x01")), "\"a\\\"\\\\\\u0001\"");  // as before
}

TEST(Utf8, XmlTextIsAlwaysUtf8) {
    EXPECT_EQ(xmlEscape("r\xE9<sum>"), "r" + kReplacement + "&lt;sum&gt;");
    EXPECT_EQ(xmlEscape("\xC2\xB5s"), "\xC2\xB5s");
}

}  // namespace
