#pragma once

#include <string>

namespace mcquad {

//! Progress on a long stage: shown on stderr when it is a terminal, silent
//! otherwise (pipes, CI logs, tests).
class Progress {
 public:
  Progress(std::string label, size_t total);
  ~Progress();
  void update(size_t done);

 private:
  std::string label_;
  size_t total_;
  bool enabled_;
  int last_percent_ = -1;
};

//! Warnings go to stderr with a common prefix.
void warn(const std::string& message);

}  // namespace mcquad
