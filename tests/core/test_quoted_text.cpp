// core/quoted_text.hpp: text from an untrusted file as one bounded line in messages and comments.
#include <catch2/catch.hpp>

#include <algorithm>

#include "rlrun/core/quoted_text.hpp"

using namespace rlrun;

TEST_CASE("quoted_text: control characters and line breaks are visible escapes, length bounded",
          "[core][quoted_text]") {
  CHECK(quoted_text("CartPole-v1") == "CartPole-v1");
  CHECK(quoted_text("a\nplugins: [x]\r\t\x1b[2J\x7f") == "a\\nplugins: [x]\\r\\t\\x1b[2J\\x7f");
  // NEL, LINE SEPARATOR and a byte order mark (YAML 1.1 readers break lines at the first two),
  // invalid UTF-8 (a stray continuation byte, a surrogate); other UTF-8 stays.
  CHECK(quoted_text("a\xc2\x85"
                    "b\xe2\x80\xa8"
                    "c\xef\xbb\xbf"
                    "d") == "a\\u0085b\\u2028c\\ufeffd");
  CHECK(quoted_text("\x80\xed\xa0\x80\xc3\xa9") == "\\x80\\xed\\xa0\\x80\xc3\xa9");
  CHECK(quoted_text(std::string(200, 'x')) == std::string(200, 'x'));
  CHECK(quoted_text(std::string(201, 'x')) == std::string(197, 'x') + "...");
  CHECK(quoted_text(std::string(100000, '\n')).size() <= kMaxQuotedBytes);
  CHECK(quoted_text("abcdef", 5) == "ab...");
}

TEST_CASE("bounded_message: each line bounded, at most a few dozen lines", "[core][quoted_text]") {
  CHECK(bounded_message("file:1:2: first\nfile:3:4: second") ==
        "file:1:2: first\nfile:3:4: second");
  const std::string long_line = bounded_message("x: " + std::string(200000, 'y'));
  CHECK(long_line.size() <= 1000);
  CHECK_THAT(long_line, Catch::EndsWith("..."));
  std::string many;
  for (int i = 0; i < 100000; ++i) many += "line\n";
  const std::string bounded = bounded_message(many);
  CHECK(std::count(bounded.begin(), bounded.end(), '\n') == 40);
  CHECK_THAT(bounded, Catch::EndsWith("(99961 more lines)"));
}
