#include "hoilcd/core/util/json_reader.h"

#include <chrono>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "cpu_seconds.h"
#include "hoilcd/core/util/sizes.h"
#include "input_error_of.h"

namespace hoilcd {
namespace {

using test::InputErrorOf;

// CPU seconds, not wall time: a loaded machine must not fail a bound on a step's cost.
double SecondsOf(const std::function<void()>& fn) { return test::CpuSecondsOf(fn); }

std::string Parsing(const std::string& text) {
  return InputErrorOf([&] { ParseJson(text, "f.json"); });
}

TEST(ParseJson, NestingOfAHundredThousandLevelsIsRefusedAtItsPointerWithinTwoSeconds) {
  for (const std::string& deep : {std::string(100000, '[') + std::string(100000, ']'), [] {
                                    std::string text;
                                    for (int i = 0; i < 100000; ++i) text += "{\"a\":";
                                    return text + "1" + std::string(100000, '}');
                                  }()}) {
    std::string error;
    EXPECT_LT(SecondsOf([&] { error = Parsing(deep); }), 2.0);
    EXPECT_NE(error.find("f.json: /"), std::string::npos) << error.substr(0, 200);
    EXPECT_NE(error.find(": nests deeper than 64 levels of objects and arrays"), std::string::npos)
        << error.substr(0, 200);
  }
  EXPECT_NE(
      Parsing(R"({"a": [[{"b": )" + std::string(62, '[') + std::string(62, ']') + "}]]}").find("f.json: /a/0/0/b/0/0/"),
      std::string::npos);
}

TEST(ParseJson, NestingUpToTheBoundIsRead) {
  const std::string deepest = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_EQ(ParseJson(deepest, "f.json").dump(), deepest);
  EXPECT_NE(Parsing("[" + deepest + "]").find("nests deeper"), std::string::npos);
}

TEST(ParseJson, ARepeatedKeyIsRefusedAtItsPointer) {
  EXPECT_NE(
      Parsing(R"({"frames": 40, "frames": 30})").find(R"(f.json: /frames: the key "frames" is repeated in one object)"),
      std::string::npos);
  EXPECT_NE(Parsing(R"({"runs": [{"a": 1}, {"set": {"x": 1, "y": [1, 2], "x": 2}}]})").find("f.json: /runs/1/set/x: "),
            std::string::npos);
  EXPECT_NE(Parsing(R"({"a~b/c": {}, "a~b/c": 1})").find("f.json: /a~0b~1c: "), std::string::npos);
  // The same key in two objects, or a key that equals a value, is fine.
  EXPECT_EQ(ParseJson(R"([{"a": 1}, {"a": 2, "b": "a"}])", "f.json").dump(), R"([{"a":1},{"a":2,"b":"a"}])");
}

TEST(ParseJson, ControlCharactersInAKeyAreEscapedInTheMessage) {
  const std::string error = Parsing(std::string("{\"a\\u001b\": 1, \"a\\u001b\": 2}"));
  EXPECT_EQ(error.find('\x1b'), std::string::npos) << error;
  EXPECT_NE(error.find("a\\x1b"), std::string::npos) << error;
}

TEST(ParseJson, SyntaxErrorsSayInvalidJsonWithNlohmannsDetail) {
  try {
    ParseJson("{nope", "f.json");
    FAIL();
  } catch (const JsonSyntaxError& e) {
    EXPECT_EQ(e.detail().rfind("parse error at line 1", 0), 0u) << e.detail();
    EXPECT_EQ(std::string(e.what()).rfind("f.json: invalid JSON (parse error at line 1", 0), 0u) << e.what();
  }
  EXPECT_THROW(ParseJson("[1e400]", "f.json"), JsonSyntaxError);  // beyond a double
  EXPECT_TRUE(ParseJsonOrDiscarded("{nope").is_discarded());
  EXPECT_TRUE(ParseJsonOrDiscarded(R"({"a": 1, "a": 1})").is_discarded());
  EXPECT_EQ(ParseJsonOrDiscarded("[1]").dump(), "[1]");
}

TEST(ParseJson, AHundredThousandListItemsParseWithinTwoSeconds) {
  std::string items = "[";
  for (int i = 0; i < 100000; ++i) items += std::string(i ? "," : "") + R"({"k": )" + std::to_string(i) + "}";
  items += "]";
  nlohmann::json doc;
  EXPECT_LT(SecondsOf([&] { doc = ParseJson(items, "f.json"); }), 2.0);
  EXPECT_EQ(doc.size(), 100000u);
  EXPECT_NE(Parsing(items.substr(0, items.size() - 1) + R"(,{"k": 1, "k": 2}])").find("f.json: /100000/k: "),
            std::string::npos);
}

}  // namespace
}  // namespace hoilcd
