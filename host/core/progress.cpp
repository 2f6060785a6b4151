#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace mcquad {
namespace {

ProgressSink& thread_sink() {
  thread_local ProgressSink sink;
  return sink;
}

}  // namespace

void set_progress_sink(ProgressSink sink) { thread_sink() = std::move(sink); }

void report_stage(const std::string& stage, bool finished, double seconds) {
  if (thread_sink()) {
    thread_sink()(stage, finished ? 1 : 0, 1);
    return;
  }
  if (isatty(STDERR_FILENO) == 0) return;
  if (!finished)
    std::fprintf(stderr, "\r%s ...\033[K", stage.c_str());
  else if (seconds >= 1.0)
    std::fprintf(stderr, "\r%s: %.1f s\033[K\n", stage.c_str(), seconds);
  else
    std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
}

Progress::Progress(std::string label, size_t total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) != 0), sink_(thread_sink()) {
  if (sink_) enabled_ = false;
}

Progress::~Progress() {
  if (enabled_ && last_percent_ >= 0) std::fprintf(stderr, "\r%s: done%20s\n", label_.c_str(), "");
}

void Progress::update(size_t done) {
  if ((!enabled_ && !sink_) || total_ == 0) return;
  int percent = static_cast<int>(100 * done / total_);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  if (sink_) {
    sink_(label_, done, total_);
    return;
  }
  std::fprintf(stderr, "\r%s: %3d%%", label_.c_str(), percent);
  std::fflush(stderr);
}

void warn(const std::string& message) { std::fprintf(stderr, "mcquad: warning: %s\n", message.c_str()); }

}  // namespace mcquad
