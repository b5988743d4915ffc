#include "core/json_text.h"

#include <gtest/gtest.h>

namespace skinslide {

TEST(JsonText, EscapesWhatJsonMustAndKeepsUtf8) {
  EXPECT_EQ(json_string("a\"b\\c\nd\te\x01"), "\"a\\\"b\\\\c\\nd\\te\\u0001\"");
  EXPECT_EQ(json_string("\xC3\xA9t\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"),
            "\"\xC3\xA9t\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80\"");
}

// A frame named in another encoding (a Latin-1 file system, a stray byte) would make the report
// unreadable by any JSON parser: each byte that is not UTF-8 becomes U+FFFD.
TEST(JsonText, AByteThatIsNotUtf8BecomesTheReplacementCharacter) {
  EXPECT_EQ(json_string("bad\xFF\x01.obj"), "\"bad\\ufffd\\u0001.obj\"");
  EXPECT_EQ(json_string("caf\xE9.obj"), "\"caf\\ufffd.obj\"");          // Latin-1 e-acute
  EXPECT_EQ(json_string("\xC0\xAF"), "\"\\ufffd\\ufffd\"");             // overlong '/'
  EXPECT_EQ(json_string("\xED\xA0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // a surrogate
  EXPECT_EQ(json_string("\xF4\x90\x80\x80"), "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");  // > U+10FFFF
  EXPECT_EQ(json_string("\xE2\x82"), "\"\\ufffd\\ufffd\"");                        // cut short
}

}  // namespace skinslide
