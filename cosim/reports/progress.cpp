#include "cosim/reports/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace voxcast::cosim {
namespace {

std::string clock_text(double s) {
  const long t = std::lround(s);
  std::ostringstream os;
  os << t / 60 << ":" << std::setw(2) << std::setfill('0') << t % 60;
  return os.str();
}

}  // namespace

bool Progress::stderr_is_terminal() { return isatty(STDERR_FILENO) != 0; }

Progress::Progress(std::string label, std::size_t total, bool force, bool at_most)
    : label_(std::move(label)),
      total_(std::max<std::size_t>(total, 1)),
      enabled_(force || stderr_is_terminal()),
      tty_(stderr_is_terminal()),
      at_most_(at_most),
      t0_(StopwatchClock::now()) {}

Progress::~Progress() {
  if (open_) std::cerr << "\n" << std::flush;
}

void Progress::step(std::size_t n) {
  if (!enabled_) return;
  const std::lock_guard lock(mutex_);
  done_ = std::min(done_ + n, total_);
  draw();
}

void Progress::draw() {
  const double elapsed = seconds_since(t0_);
  const int width = 30;
  const int filled = static_cast<int>(width * done_ / total_);
  std::cerr << (tty_ ? "\r" : "") << label_ << " ["
            << std::string(static_cast<std::size_t>(filled), '#')
            << std::string(static_cast<std::size_t>(width - filled), '.') << "] " << done_ << "/"
            << (at_most_ ? "<=" : "") << total_ << " " << std::setw(3) << 100 * done_ / total_
            << "%  elapsed " << clock_text(elapsed);
  if (!at_most_ && done_ > 0)
    std::cerr << "  left "
              << clock_text(elapsed / static_cast<double>(done_) *
                            static_cast<double>(total_ - done_));
  open_ = tty_ && done_ < total_;
  std::cerr << (open_ ? "" : "\n") << std::flush;
}

}  // namespace voxcast::cosim
