#include "progress_line.h"

#include <fmt/format.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>

namespace sfit::cli {
namespace {

std::atomic<bool> interrupted{false};
volatile std::sig_atomic_t received = 0;
struct sigaction old_int, old_term;

extern "C" void on_signal(int sig) {
  if (interrupted.load()) {  // the second one: as if no handler were there
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  received = sig;
  interrupted.store(true);
}

}  // namespace

Interruption::Interruption() {
  static_assert(std::atomic<bool>::is_always_lock_free);
  interrupted.store(false);
  received = 0;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
}

Interruption::~Interruption() {
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
}

const std::atomic<bool>* Interruption::flag() const {
  return &interrupted;
}

int Interruption::signal() const {
  return interrupted.load() ? static_cast<int>(received) : 0;
}

std::string Interruption::what() const {
  return fmt::format("interrupted by {}", signal() == SIGTERM ? "SIGTERM" : "SIGINT");
}

ProgressLine::ProgressLine(bool enabled, double after)
    : enabled_(enabled && ::isatty(2)), after_(after) {}

ProgressFunction ProgressLine::function(const Interruption& interrupt) {
  return [this, &interrupt](const FitProgress& p) {
    if (interrupt.signal() != 0) return false;
    // Redrawn at most 10 times a second, from `after_` seconds on.
    if (!enabled_ || p.seconds < after_ || (shown_ && p.seconds - last_ < 0.1)) return true;
    last_ = p.seconds;
    std::string line = fmt::format("sfit: {}", p.phase);
    if (p.total > 1) line += fmt::format(" {}/{}", p.done, p.total);
    if (p.pairs_tried > 0) line += fmt::format(", {} pairs tried", p.pairs_tried);
    if (p.best_u > 0) line += fmt::format(", best {} x {}", p.best_u, p.best_v);
    line += fmt::format(", {:.1f} s", p.seconds);
    // Back to the line's start, the line, then the rest of the old one erased.
    std::fprintf(stderr, "\r%s\033[K", line.c_str());
    std::fflush(stderr);
    shown_ = true;
    return true;
  };
}

void ProgressLine::clear() {
  if (!shown_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace sfit::cli
