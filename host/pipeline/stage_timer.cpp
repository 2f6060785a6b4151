#include "pipeline/stage_timer.h"

#include <sys/resource.h>
#include <unistd.h>

#include <exception>
#include <fstream>

namespace mcquad {

double peak_resident_megabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

double current_resident_megabytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

double StageTimer::seconds(const std::string& stage) const {
  auto found = records_.find(stage);
  return found == records_.end() ? 0.0 : found->second.seconds;
}

void StageTimer::rename(const std::string& from, const std::string& to) {
  auto found = records_.find(from);
  if (found == records_.end()) return;
  records_[to] = found->second;
  records_.erase(found);
}

StageTimer::Scope::Scope(StageTimer& timer, std::string stage)
    : timer_(timer), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {
  report_stage(stage_, false);
}

StageTimer::Scope::~Scope() {
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  timer_.records_[stage_] = {seconds, peak_resident_megabytes(), current_resident_megabytes()};
  // A stage that threw did not finish: its end is not reported as progress.
  if (std::uncaught_exceptions() == 0) report_stage(stage_, true, seconds);
}

}  // namespace mcquad
