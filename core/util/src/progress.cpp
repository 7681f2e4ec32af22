#include "hoilcd/core/util/progress.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include <sys/ioctl.h>
#include <unistd.h>

namespace hoilcd {
namespace {
std::atomic<bool> g_quiet_default{false};
// The reporters on the terminal line, in the order they first drew; guarded by the mutex.
std::mutex g_terminal_mutex;
std::vector<const ProgressReporter*> g_on_terminal;
thread_local std::string g_title_prefix;
thread_local int g_thread_quiet = 0;

std::string FormatSeconds(double s) {
  char buf[32];
  if (s < 0 || s > 1e7) return "?";
  const int total = static_cast<int>(s + 0.5);
  std::snprintf(buf, sizeof(buf), "%d:%02d", total / 60, total % 60);
  return buf;
}
}  // namespace

void ProgressReporter::SetQuietByDefault(bool quiet) { g_quiet_default = quiet; }

ProgressReporter::ThreadTitlePrefix::ThreadTitlePrefix(std::string prefix) : previous_(g_title_prefix) {
  g_title_prefix = previous_ + prefix;
}

ProgressReporter::ThreadTitlePrefix::~ThreadTitlePrefix() { g_title_prefix = previous_; }

ProgressReporter::ThreadQuiet::ThreadQuiet() { ++g_thread_quiet; }

ProgressReporter::ThreadQuiet::~ThreadQuiet() { --g_thread_quiet; }

ProgressReporter::ProgressReporter(std::string title, int64_t total, std::string unit, bool quiet)
    : title_(g_title_prefix + title),
      unit_(std::move(unit)),
      total_(total),
      quiet_(quiet || g_quiet_default.load() || g_thread_quiet > 0),
      tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

ProgressReporter::~ProgressReporter() {
  if (!done_) Done();
}

double ProgressReporter::ElapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressReporter::Update(int64_t done_increment) {
  count_.fetch_add(done_increment);
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double interval = tty_ ? 0.1 : 10.0;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || done_) return;  // done: off the terminal line for good
  if (std::chrono::duration<double>(now - last_print_).count() < interval) return;
  last_print_ = now;
  Print(false);
}

void ProgressReporter::Done() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (done_) return;
  done_ = true;
  if (!quiet_) Print(true);
}

std::string ProgressReporter::Status(int bar_width, bool final_line) const {
  const int64_t done = count_.load();
  const double elapsed = ElapsedSeconds();
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  const double left = rate > 0 ? (total_ - done) / rate : -1.0;
  const std::string time = FormatSeconds(final_line ? elapsed : left);
  const char* took = final_line ? "took" : "left";
  char text[256];
  if (bar_width == 0) {
    std::snprintf(text, sizeof(text), "%s: %lld/%lld %s, %.1f %s/s, %s %s", title_.c_str(),
                  static_cast<long long>(done), static_cast<long long>(total_), unit_.c_str(), rate, unit_.c_str(),
                  took, time.c_str());
    return text;
  }
  const int filled = total_ > 0 ? static_cast<int>(bar_width * std::min(done, total_) / total_) : 0;
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(static_cast<size_t>(bar_width), '.');
  std::snprintf(text, sizeof(text), "%s [%s] %lld/%lld %s  %.1f %s/s  %s %s", title_.c_str(), bar.c_str(),
                static_cast<long long>(done), static_cast<long long>(total_), unit_.c_str(), rate, unit_.c_str(), took,
                time.c_str());
  return text;
}

void ProgressReporter::Print(bool final_line) {
  if (tty_) {
    // One terminal line for every reporter drawing at once: its own final line goes above it.
    std::lock_guard<std::mutex> lock(g_terminal_mutex);
    std::string line = "\r";
    if (final_line) {
      line += Status(30, true) + "\033[K\n";
      g_on_terminal.erase(std::remove(g_on_terminal.begin(), g_on_terminal.end(), this), g_on_terminal.end());
    } else if (std::find(g_on_terminal.begin(), g_on_terminal.end(), this) == g_on_terminal.end()) {
      g_on_terminal.push_back(this);
    }
    const int width = g_on_terminal.size() > 1 ? 12 : 30;
    std::string bars;
    for (size_t i = 0; i < g_on_terminal.size(); ++i) {
      bars += (i ? " | " : "") + g_on_terminal[i]->Status(width, false);
    }
    // Cut to the terminal's width: a wrapped line would leave a stale copy above at each redraw.
    winsize size{};
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1 && bars.size() >= size.ws_col) {
      bars.resize(size.ws_col - 1);
    }
    std::fputs((line + bars + "\033[K").c_str(), stderr);
  } else {
    std::fputs((Status(0, final_line) + "\n").c_str(), stderr);
  }
  std::fflush(stderr);
}

}  // namespace hoilcd
