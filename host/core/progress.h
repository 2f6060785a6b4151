#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace mcquad {

//! Where progress goes instead of the terminal: a label, units done, units
//! in all. The Python package passes its callback here.
using ProgressSink = std::function<void(const std::string& label, size_t done, size_t total)>;

//! Sends the progress of work started on this thread to `sink` from now on
//! (empty: to the terminal again). Per thread, so that fits running side by
//! side in one process each report to their own caller.
void set_progress_sink(ProgressSink sink);

//! A pipeline stage began (done 0 of 1) or ended (1 of 1, after `seconds`).
//! To the sink when there is one; else, when stderr is a terminal, the
//! stage's name while it runs, kept with its time when it took a second or
//! more; nothing on pipes and in logs.
void report_stage(const std::string& stage, bool finished, double seconds = 0);

//! Progress on a long stage: to this thread's sink when there is one, else
//! shown on stderr when it is a terminal, silent otherwise (pipes, CI logs,
//! tests).
class Progress {
 public:
  Progress(std::string label, size_t total);
  ~Progress();
  void update(size_t done);

 private:
  std::string label_;
  size_t total_;
  bool enabled_;
  ProgressSink sink_;
  int last_percent_ = -1;
};

//! Warnings go to stderr with a common prefix.
void warn(const std::string& message);

}  // namespace mcquad
