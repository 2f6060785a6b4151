#pragma once

#include <array>
#include <stdexcept>
#include <string>

namespace mcquad {

//! Malformed, truncated or inconsistent input: files, clouds, skeletons.
//! The message names the file (and line or element) and the problem.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Valid input this version cannot handle, e.g. a junction of valence 7.
class UnsupportedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! An initial mesh whose tubes or blocks overlap, so that its faces do not
//! make a manifold (an UnsupportedError): `site` says where, so that a fit
//! that made the skeleton itself can leave that part out.
class OverlapError : public UnsupportedError {
 public:
  OverlapError(const std::string& message, const std::array<double, 3>& where)
      : UnsupportedError(message), site(where) {}
  std::array<double, 3> site;
};

//! No usable OpenCL device, a failed kernel build, or a device fault.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! An output file could not be written; nothing half-written is left behind.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Process exit codes of the `mcquad` command, documented in the README.
enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,
  kExitUsage = 2,
  kExitInput = 3,
  kExitUnsupported = 4,
  kExitDevice = 5,
  kExitOutput = 6,
  kExitVerdict = 7,  //!< --strict: the outputs are written, but a check of the verdict failed
};

}  // namespace mcquad
