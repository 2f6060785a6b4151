#pragma once

#include <chrono>
#include <map>
#include <string>

#include "core/progress.h"

namespace mcquad {

//! Peak resident memory of the process so far, in MiB.
double peak_resident_megabytes();

//! Resident memory now, from /proc/self/statm (0 where there is none).
double current_resident_megabytes();

//! The observer every pipeline stage runs under: it times the stage, notes
//! the memory when it ended and reports its start and end as progress
//! (core/progress.h). The fit, `mcquad metrics`, the tests and the
//! benchmarks run the same stages (pipeline/prepare.h) through one.
class StageTimer {
 public:
  struct Record {
    double seconds = 0;
    //! Peak resident memory of the process when the stage ended: the first
    //! stage at the final peak is the one that set it.
    double peak_megabytes = 0;
    double resident_megabytes = 0;
  };

  //! Runs `work()` as the stage `stage` and returns what it returns.
  template <typename F>
  auto run(const std::string& stage, F&& work) {
    Scope scope(*this, stage);
    return work();
  }

  //! The stages run so far, by name.
  const std::map<std::string, Record>& records() const { return records_; }
  //! Seconds the stage took (0 when it did not run).
  double seconds(const std::string& stage) const;
  //! The stage recorded as `from` is recorded as `to` instead (nothing
  //! when it did not run): a stage found afterwards to be the first of two.
  void rename(const std::string& from, const std::string& to);

 private:
  //! Records the stage when it ends, also when it throws.
  class Scope {
   public:
    Scope(StageTimer& timer, std::string stage);
    ~Scope();

   private:
    StageTimer& timer_;
    std::string stage_;
    std::chrono::steady_clock::time_point start_;
  };
  std::map<std::string, Record> records_;
};

}  // namespace mcquad
