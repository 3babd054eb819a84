// Running a third-party parser in a child process, so that whatever it does to
// a hostile input (an assertion's abort, a segfault, an endless loop) ends the
// child, never voxcast. Debian's GDCM 3.0 aborts the process on assertions for
// some malformed DICOM files (docs/extremes.md, "Fuzzing"); the DICOM loader
// parses a series' files through run_in_child.
//
// POSIX fork: the child shares the parent's memory image copy-on-write (its
// inputs need no copying), runs `work`, which sends its results as messages
// through a pipe, and ends with _exit (no atexit handlers, no stdio flush, no
// leak check). The parent takes each message as it arrives, so results larger
// than the pipe buffer flow, and gives up on a child that sends nothing for
// `timeout`. One child serves many inputs: a fork and a fresh address space per
// input cost more than the parsing itself (docs/extremes.md has the numbers).
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

namespace voxcast::ref {

struct ChildResult {
  enum class Outcome {
    Done,       // `work` returned
    Threw,      // `work` threw; `detail` holds the exception's what()
    Signalled,  // the child was killed by a signal; `detail` names it ("SIGABRT")
    Exited,     // the child exited on its own (a sanitizer report); `detail` = "status N"
    TimedOut,   // no message for `timeout`; the child was killed. `detail` = "after N ms"
  };
  Outcome outcome = Outcome::Done;
  std::size_t messages = 0;  // complete messages received (before the failure, if any)
  std::string detail;
};

// The child's side: `send(bytes)` delivers one message to the parent.
using ChildSend = std::function<void(const std::string&)>;

// Runs `work` in a forked child; `receive` gets each message in order, in the
// parent. In the child, SIGABRT, SIGSEGV, SIGBUS, SIGFPE and SIGILL get their
// default action back (a sanitizer's or libFuzzer's handler would turn the
// signal into an exit status), so a crash is reported as the signal. Throws
// voxcast::Error only if the child cannot be started or the pipe fails; an
// exception from `receive` kills the child and propagates.
ChildResult run_in_child(const std::function<void(const ChildSend&)>& work,
                         const std::function<void(std::string&&)>& receive,
                         std::chrono::milliseconds timeout);

// "SIGABRT" for SIGABRT (glibc's abbreviation), "signal N" if it has none.
std::string signal_name(int signal);

}  // namespace voxcast::ref
