#include "app/cli/ParsingValidator.hpp"

#include <gtest/gtest.h>

#include "engine/calibration/CalibrationBoard.hpp"
#include "engine/reference/MarkerSpec.hpp"

namespace reftrack::app {
namespace {

// An option checked by the validator: a good spec parses, a bad one is a usage error that
// carries the parser's own message.
std::string parseError(const CLI::Validator& validator, const std::string& value) {
  CLI::App app;
  std::string target;
  app.add_option("--spec", target)->check(validator);
  try {
    app.parse(std::vector<std::string>{value, "--spec"});
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return "";
}

TEST(ParsingValidator, AcceptsWhatTheParserAcceptsAndQuotesItsError) {
  const CLI::Validator board = parsingValidator<CalibrationBoard>("BOARD");
  EXPECT_EQ(parseError(board, "chessboard:9x6:0.025"), "");
  EXPECT_NE(parseError(board, "chessboard:9x:0.025"), "");
  const CLI::Validator marker = parsingValidator<MarkerSpec>("MARKER");
  EXPECT_EQ(parseError(marker, "DICT_6X6_250:23:0.2"), "");
  std::string expected;
  try {
    MarkerSpec::parse("DICT_6X6_250:23");
  } catch (const Error& e) {
    expected = e.what();
  }
  ASSERT_FALSE(expected.empty());
  EXPECT_NE(parseError(marker, "DICT_6X6_250:23").find(expected), std::string::npos);
}

}  // namespace
}  // namespace reftrack::app
