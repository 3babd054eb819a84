// run_in_child (refmodel/volume/child_process.hpp): every way a child can end
// is reported as itself, with the messages sent before it, and a large result
// arrives byte for byte. The DICOM loader relies on it to survive GDCM's
// assertions (tests/fuzz_regress/data/dicom/vr16_read_pre_value_assert.dcm).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/volume/child_process.hpp"

namespace voxcast::ref {
namespace VOXCAST_UNITY_ID {

using namespace std::chrono_literals;
using Outcome = ChildResult::Outcome;

struct ChildRun {
  ChildResult result;
  std::vector<std::string> messages;
};

ChildRun run(const std::function<void(const ChildSend&)>& work, std::chrono::milliseconds timeout = 20s) {
  ChildRun r;
  r.result = run_in_child(work, [&](std::string&& m) { r.messages.push_back(std::move(m)); }, timeout);
  return r;
}

// Bytes that differ from position to position (a shifted copy would show).
std::string pattern(std::size_t n, unsigned seed) {
  std::string s(n, '\0');
  unsigned x = seed;
  for (char& c : s) {
    x = x * 1664525u + 1013904223u;  // Numerical Recipes' LCG
    c = static_cast<char>(x >> 24);
  }
  return s;
}

TEST(ChildProcess, MessagesArriveInOrderAndWhole) {
  // 3 MiB is three times the largest pipe buffer: the parent must read while
  // the child writes. The empty message must survive as one.
  const std::vector<std::string> sent = {"first", std::string(), pattern(3 << 20, 7), "last"};
  const ChildRun r = run([&](const ChildSend& send) {
    for (const std::string& m : sent) send(m);
  });
  EXPECT_EQ(r.result.outcome, Outcome::Done);
  EXPECT_EQ(r.result.messages, sent.size());
  ASSERT_EQ(r.messages.size(), sent.size());
  for (std::size_t k = 0; k < sent.size(); ++k) EXPECT_TRUE(r.messages[k] == sent[k]) << k;
}

TEST(ChildProcess, AbortIsReportedAsSigabrtAfterTheMessagesBeforeIt) {
  const ChildRun r = run([](const ChildSend& send) {
    send("one");
    send("two");
    std::abort();
  });
  EXPECT_EQ(r.result.outcome, Outcome::Signalled);
  EXPECT_EQ(r.result.detail, "SIGABRT");
  EXPECT_EQ(r.result.messages, 2u);
  EXPECT_EQ(r.messages, (std::vector<std::string>{"one", "two"}));
}

TEST(ChildProcess, SegfaultIsReportedAsSigsegv) {
  const ChildRun r = run([](const ChildSend&) { ::raise(SIGSEGV); });
  EXPECT_EQ(r.result.outcome, Outcome::Signalled);
  EXPECT_EQ(r.result.detail, "SIGSEGV");
  EXPECT_EQ(r.result.messages, 0u);
}

TEST(ChildProcess, ExitWithoutFinishingIsReportedWithItsStatus) {
  const ChildRun r = run([](const ChildSend& send) {
    send("partial");
    ::_exit(7);
  });
  EXPECT_EQ(r.result.outcome, Outcome::Exited);
  EXPECT_EQ(r.result.detail, "status 7");
  EXPECT_EQ(r.result.messages, 1u);
}

TEST(ChildProcess, ExceptionInTheChildIsReportedWithItsText) {
  const ChildRun r = run([](const ChildSend&) { throw std::runtime_error("no such tag"); });
  EXPECT_EQ(r.result.outcome, Outcome::Threw);
  EXPECT_EQ(r.result.detail, "no such tag");
}

TEST(ChildProcess, SilentChildIsKilledAtTheTimeout) {
  const auto t0 = std::chrono::steady_clock::now();
  const ChildRun r = run(
      [](const ChildSend& send) {
        send("before");
        std::this_thread::sleep_for(60s);
      },
      300ms);
  const auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_EQ(r.result.outcome, Outcome::TimedOut);
  EXPECT_EQ(r.result.detail, "after 300 ms");
  EXPECT_EQ(r.result.messages, 1u);
  EXPECT_GE(took, 300ms);
  EXPECT_LT(took, 10s);  // killed, not waited for
}

TEST(ChildProcess, TheTimeoutCountsFromTheLastMessage) {
  // Five messages 150 ms apart: 750 ms in all, each gap inside a 600 ms timeout.
  const ChildRun r = run(
      [](const ChildSend& send) {
        for (int k = 0; k < 5; ++k) {
          std::this_thread::sleep_for(150ms);
          send(std::to_string(k));
        }
      },
      600ms);
  EXPECT_EQ(r.result.outcome, Outcome::Done);
  EXPECT_EQ(r.result.messages, 5u);
}

TEST(ChildProcess, ErrorInTheReceiverPropagatesAndEndsTheChild) {
  EXPECT_THROW(run_in_child(
                   [](const ChildSend& send) {
                     send("bad");
                     std::this_thread::sleep_for(60s);
                   },
                   [](std::string&&) { throw Error("receiver rejects"); }, 20s),
               Error);
}

TEST(ChildProcess, SignalNames) {
  EXPECT_EQ(signal_name(SIGABRT), "SIGABRT");
  EXPECT_EQ(signal_name(SIGKILL), "SIGKILL");
  EXPECT_EQ(signal_name(0x7ff), "signal 2047");
}

}  // namespace
}  // namespace voxcast::ref
