// SPDX-License-Identifier: BSD-3-Clause
// Runs the volrad command from a test and captures what it prints.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>

namespace volrad::test {

struct CommandRun
{
  int code;
  std::string output;
};

/// Runs volrad with `args` (after `prefix`, e.g. "env -u DISPLAY "); stdout
/// and stderr together.
inline CommandRun runVolrad(const std::string& args, const std::string& prefix = "")
{
  // One log per test: ctest runs the tests in parallel.
  const std::string log = std::string(VOLRAD_TEST_OUTPUT_DIR) + "/volrad-" +
                          ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".log";
  const int status = std::system(
    (prefix + std::string(VOLRAD_COMMAND) + " " + args + " > " + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return { WEXITSTATUS(status), text };
}

inline bool fileExists(const std::string& path)
{
  return bool(std::ifstream(path));
}

} // namespace volrad::test
