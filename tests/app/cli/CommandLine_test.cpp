#include "app/cli/CommandLine.hpp"

#include <gtest/gtest.h>

#include "app/commands/CommandTestSupport.hpp"
#include "app/commands/Commands.hpp"

using namespace reftrack;
using namespace reftrack::app;

// Every command registers itself; the product's come first, then the research commands.
TEST(CommandLine, RegistersProductCommandsBeforeResearchCommands) {
  const std::vector<RegisteredCommand> commands = registeredCommands();
  ASSERT_GE(commands.size(), 17u);
  int research = 0;
  bool researchSeen = false;
  for (const RegisteredCommand& c : commands) {
    if (c.group == CommandGroup::Research) {
      researchSeen = true;
      ++research;
    }
    EXPECT_FALSE(researchSeen && c.group == CommandGroup::Product) << "product after research";
  }
  // experiment-6dof/-correlation/-relocalisation/-homography/-reference-pair,
  // bench-homography/-real/-recovery-cost, corner-variance
  EXPECT_EQ(research, 9);
}

// `reftrack --help` shows the two groups under their headings, each command once.
TEST(CommandLine, HelpListsResearchCommandsApart) {
  const auto dir = test::freshTempDir("CommandLine_help");
  const test::CommandRun run = test::runReftrack("--help", dir);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  const auto product = run.out.find(commandGroupHeading(CommandGroup::Product) + std::string(":"));
  const auto research =
      run.out.find(commandGroupHeading(CommandGroup::Research) + std::string(":"));
  ASSERT_NE(product, std::string::npos) << run.out;
  ASSERT_NE(research, std::string::npos) << run.out;
  EXPECT_LT(product, research);
  for (const char* name : {"track", "view", "prepare", "simulate", "eval"}) {
    const auto at = run.out.find(std::string("  ") + name + " ");
    EXPECT_TRUE(at > product && at < research) << name;
  }
  for (const char* name : {"experiment-6dof", "experiment-homography", "experiment-relocalisation",
                           "experiment-correlation", "bench-homography", "corner-variance"})
    EXPECT_GT(run.out.find(std::string("  ") + name), research) << name;
}
