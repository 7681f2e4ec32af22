#include "hoilcd/core/util/safe_text.h"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace hoilcd {
namespace {

using namespace std::string_literals;

TEST(SafeText, PrintableUtf8ComesOutUnchanged) {
  for (const std::string& text :
       {"slcd"s, "caf\xc3\xa9 / \xe6\x97\xa5\xe6\x9c\xac \xf0\x9f\x94\xa5"s, ""s, "back\\slash and \"quotes\""s}) {
    EXPECT_EQ(SafeText(text), text);
  }
}

TEST(SafeText, BytesThatAreNotUtf8AreWrittenAsHexEscapes) {
  EXPECT_EQ(SafeText("caf\xe9.npy"), "caf\\xe9.npy");               // Latin-1
  EXPECT_EQ(SafeText("\xc3"), "\\xc3");                             // a character cut short
  EXPECT_EQ(SafeText("\xc0\xaf"), "\\xc0\\xaf");                    // an overlong '/'
  EXPECT_EQ(SafeText("\xed\xa0\x80"), "\\xed\\xa0\\x80");           // a UTF-16 surrogate
  EXPECT_EQ(SafeText("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
}

TEST(SafeText, ControlCharactersAndNulAreWrittenAsHexEscapesSoNothingCutsTheText) {
  const std::string escaped = SafeText("0\0,1\x1b[31m\x7f\xc2\x9b"s);
  EXPECT_EQ(escaped, "0\\x00,1\\x1b[31m\\x7f\\xc2\\x9b");
  EXPECT_EQ(escaped.find('\0'), std::string::npos);
}

TEST(SafeText, AnyBytesComeOutAsTextThatJsonTakesAndThatSafeTextLeavesAlone) {
  std::string every_byte;
  for (int b = 0; b < 256; ++b) every_byte += static_cast<char>(b);
  const std::string safe = SafeText(every_byte + "\xe2\x82" + every_byte);
  EXPECT_NO_THROW(nlohmann::json(safe).dump());
  EXPECT_EQ(SafeText(safe), safe);
}

}  // namespace
}  // namespace hoilcd
