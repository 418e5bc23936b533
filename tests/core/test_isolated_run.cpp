// Computations in a child process (core/isolated_run.h): the result comes back byte for byte, an
// exception as its message, a fault or an abort as a crash of the child only, and nothing the
// work changes reaches the caller.
#include "core/isolated_run.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

using namespace tissuemesh;

TEST(IsolatedRun, TheChildsBytesComeBackWhole) {
  // More than a pipe's buffer (64 KiB), with every byte value, zeros included.
  std::string expected;
  for (unsigned i = 0; i < 300000; ++i) expected.push_back(static_cast<char>(i * 7919u % 256u));
  const IsolatedRun run = run_isolated([&](std::string& bytes) { bytes = expected; });
  ASSERT_TRUE(run.ok) << run.failure;
  EXPECT_FALSE(run.crashed);
  EXPECT_EQ(run.bytes, expected);
}

TEST(IsolatedRun, TheWorksChangesStayInTheChild) {
  int counter = 1;
  const IsolatedRun run = run_isolated([&](std::string& bytes) {
    counter = 42;
    bytes = std::to_string(counter);
    std::printf("printed in the child, discarded\n");
  });
  ASSERT_TRUE(run.ok) << run.failure;
  EXPECT_EQ(run.bytes, "42");
  EXPECT_EQ(counter, 1);
}

TEST(IsolatedRun, AnExceptionComesBackAsItsMessage) {
  const IsolatedRun run = run_isolated([](std::string&) { throw std::runtime_error("the input intersects itself"); });
  EXPECT_FALSE(run.ok);
  EXPECT_FALSE(run.crashed);
  EXPECT_EQ(run.failure, "the input intersects itself");
}

TEST(IsolatedRun, AFaultEndsTheChildOnly) {
  // Under AddressSanitizer the child reports the fault and exits with status 1 instead of
  // dying by the signal: a crash either way.
  const IsolatedRun run = run_isolated([](std::string& bytes) {
    bytes = "partial";
    std::raise(SIGSEGV);
  });
  EXPECT_FALSE(run.ok);
  EXPECT_TRUE(run.crashed);
  EXPECT_TRUE(run.bytes.empty());
  EXPECT_FALSE(run.failure.empty());
}

TEST(IsolatedRun, AnAbortIsACrashNamingTheSignal) {
  const IsolatedRun run = run_isolated([](std::string&) { std::abort(); });
  EXPECT_FALSE(run.ok);
  EXPECT_TRUE(run.crashed);
  EXPECT_NE(run.failure.find("signal 6"), std::string::npos) << run.failure;
}
