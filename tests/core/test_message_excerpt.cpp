// printable_excerpt / quote_value / message_excerpt (issue 33): what an error message may echo of a user's
// bytes, and InputError applying it to every message.
#include <catch2/catch.hpp>
#include <string>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/printable_excerpt.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_message_excerpt {

using namespace crowdlab;

TEST_CASE("printable_excerpt escapes control and invalid UTF-8 bytes and cuts at a character boundary") {
  CHECK(printable_excerpt("abc", 10) == "abc");
  CHECK(printable_excerpt("a\nb\x1b", 10) == "a\\x0ab\\x1b");
  CHECK(printable_excerpt("a\nb", 10, /*keep_layout=*/true) == "a\nb");
  CHECK(printable_excerpt("\xff\xfe", 10) == "\\xff\\xfe");
  CHECK(printable_excerpt("\xc3\xa9t\xc3\xa9", 10) == "\xc3\xa9t\xc3\xa9");  // "été" kept whole
  CHECK(printable_excerpt("ab\xc3\xa9", 3) == "ab... (2 more bytes)");       // not cut inside é
  CHECK(printable_excerpt(std::string(100, 'x'), 10) == "xxxxxxxxxx... (90 more bytes)");
  CHECK(quote_value(std::string(1000, 'y')) ==
        "'" + std::string(kMaxQuotedBytes, 'y') + "... (920 more bytes)'");
}

TEST_CASE("every InputError message is cut and escaped, whichever call site built it") {
  const std::string huge(50u << 20, '7');  // a 50 MB "number" on one CSV line
  const InputError e(SourceLocation{"big.csv", 2, 1, "column 'v'"}, "bad value '" + huge + "' \x1b[31mred");
  const std::string m = e.what();
  CHECK(m.size() < 1000);
  CHECK_THAT(m, Catch::Contains("big.csv:2:1: column 'v': bad value") && Catch::Contains("more bytes") &&
                    Catch::Contains("\\x1b[31mred"));
  // A long message with spaces keeps its head and its tail (where the hint to raise a limit is).
  std::string words;
  for (int i = 0; i < 2000; ++i) words += "word ";
  const std::string hint = InputError("start " + words + "raise it with --max-things").what();
  CHECK(hint.size() < 4200);
  CHECK_THAT(hint, Catch::StartsWith("start word") && Catch::EndsWith("raise it with --max-things") &&
                       Catch::Contains("bytes left out"));
  CHECK(std::string(InputError("plain message").what()) == "plain message");
}

TEST_CASE("a CSV number outside the range of a double is named as such, a subnormal is read") {
  const CsvTable t = parse_csv("v\n1e-400\n1e-320\n1e999\n", "r.csv");
  CHECK_THROWS_WITH(
      t.number(0, 0),
      Catch::Contains("r.csv:2:1: column 'v': a number outside the range of a double: '1e-400'"));
  CHECK(t.number(1, 0) > 0.0);
  CHECK_THROWS_WITH(t.number(2, 0), Catch::Contains("r.csv:4:1:"));
}

}  // namespace test_message_excerpt
