#include "refmodel/volume/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <exception>

#include "refmodel/error.hpp"

namespace voxcast::ref {
namespace {

// Frames on the pipe: a type byte, the payload's length (8 bytes), the payload.
constexpr char kMessage = 'M';
constexpr char kThrew = 'T';
constexpr std::size_t kHeaderBytes = 1 + sizeof(std::uint64_t);
constexpr int kPipeBytes = 1 << 20;  // Linux's default pipe-max-size for unprivileged users

class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() { close(); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The parent has gone (or the pipe broke): nothing left to do.
struct PipeGone {};

void write_frame(int fd, char type, const std::string& payload) {
  char header[kHeaderBytes];
  header[0] = type;
  const std::uint64_t n = payload.size();
  std::memcpy(header + 1, &n, sizeof n);
  if (!write_all(fd, header, sizeof header) || !write_all(fd, payload.data(), payload.size()))
    throw PipeGone{};
}

// The child's side: never returns.
[[noreturn]] void run_child(int out, const std::function<void(const ChildSend&)>& work) {
  for (const int s : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) {
    struct sigaction action {};
    action.sa_handler = SIG_DFL;
    sigemptyset(&action.sa_mask);
    ::sigaction(s, &action, nullptr);
  }
  try {
    try {
      work([out](const std::string& message) { write_frame(out, kMessage, message); });
    } catch (const PipeGone&) {
      throw;
    } catch (const std::exception& e) {
      write_frame(out, kThrew, e.what());
    } catch (...) {
      write_frame(out, kThrew, "an exception that is not a std::exception");
    }
  } catch (const PipeGone&) {
    ::_exit(3);
  }
  ::_exit(0);
}

// The parent's side of the pipe: splits the byte stream into frames, copying
// each byte once (a slice's pixels are a large frame).
class FrameReader {
 public:
  explicit FrameReader(const std::function<void(std::string&&)>& receive) : receive_(receive) {}

  // Takes the bytes read; delivers every frame they complete.
  void take(const char* data, std::size_t n) {
    while (n > 0) {
      if (header_.size() < kHeaderBytes) {
        const std::size_t k = std::min(n, kHeaderBytes - header_.size());
        header_.append(data, k);
        data += k;
        n -= k;
        if (header_.size() < kHeaderBytes) return;
        std::memcpy(&length_, header_.data() + 1, sizeof length_);
        payload_.clear();
        payload_.reserve(length_);
      }
      const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(n, length_ - payload_.size()));
      payload_.append(data, k);
      data += k;
      n -= k;
      if (payload_.size() == length_) deliver();
    }
  }
  std::size_t messages() const { return messages_; }
  bool threw() const { return threw_; }
  const std::string& what() const { return what_; }
  bool clean_end() const { return header_.empty(); }

 private:
  void deliver() {
    const char type = header_[0];
    header_.clear();
    if (type == kThrew) {
      threw_ = true;
      what_ = std::move(payload_);
    } else {
      ++messages_;
      receive_(std::move(payload_));
    }
    payload_ = std::string();
  }

  const std::function<void(std::string&&)>& receive_;
  std::string header_;  // the current frame's header, as far as it has arrived
  std::uint64_t length_ = 0;
  std::string payload_;
  std::size_t messages_ = 0;
  bool threw_ = false;
  std::string what_;
};

// Reads the pipe until the child closes it (EOF: true) or sends nothing for
// `timeout` (false).
bool read_until_eof(int in, std::chrono::milliseconds timeout, FrameReader& frames) {
  std::string buffer(1 << 16, '\0');
  auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{in, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) throw Error(std::string("waiting for a child process: ") + std::strerror(errno));
    if (ready == 0) return false;
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(std::string("reading from a child process: ") + std::strerror(errno));
    if (n == 0) return true;
    const std::size_t before = frames.messages();
    frames.take(buffer.data(), static_cast<std::size_t>(n));
    if (frames.messages() != before) deadline = std::chrono::steady_clock::now() + timeout;
  }
}

int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw Error(std::string("waiting for a child process: ") + std::strerror(errno));
  return status;
}

ChildResult interpret(int status, const FrameReader& frames) {
  ChildResult r;
  r.messages = frames.messages();
  if (WIFSIGNALED(status)) {
    r.outcome = ChildResult::Outcome::Signalled;
    r.detail = signal_name(WTERMSIG(status));
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !frames.clean_end()) {
    r.outcome = ChildResult::Outcome::Exited;
    r.detail = "status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  } else if (frames.threw()) {
    r.outcome = ChildResult::Outcome::Threw;
    r.detail = frames.what();
  }
  return r;
}

}  // namespace

std::string signal_name(int signal) {
  const char* abbrev = ::sigabbrev_np(signal);
  return abbrev ? "SIG" + std::string(abbrev) : "signal " + std::to_string(signal);
}

ChildResult run_in_child(const std::function<void(const ChildSend&)>& work,
                         const std::function<void(std::string&&)>& receive,
                         std::chrono::milliseconds timeout) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw Error(std::string("cannot create a pipe for a child process: ") + std::strerror(errno));
  Fd in(fds[0]), out(fds[1]);
  // A large pipe: a 512x512 16-bit slice passes in one write instead of eight
  // hand-overs between the processes. Best effort: any size works.
  ::fcntl(out.get(), F_SETPIPE_SZ, kPipeBytes);
  const pid_t pid = ::fork();
  if (pid < 0) throw Error(std::string("cannot start a child process: ") + std::strerror(errno));
  if (pid == 0) {
    in.close();
    run_child(out.get(), work);
  }
  out.close();  // EOF arrives when the child ends
  FrameReader frames(receive);
  bool finished = false;
  try {
    finished = read_until_eof(in.get(), timeout, frames);
  } catch (...) {
    ::kill(pid, SIGKILL);
    wait_for(pid);
    throw;
  }
  if (!finished) {
    ::kill(pid, SIGKILL);
    wait_for(pid);
    ChildResult r;
    r.outcome = ChildResult::Outcome::TimedOut;
    r.messages = frames.messages();
    r.detail = "after " + std::to_string(timeout.count()) + " ms";
    return r;
  }
  return interpret(wait_for(pid), frames);
}

}  // namespace voxcast::ref
