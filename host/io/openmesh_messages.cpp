#include "io/openmesh_messages.h"

#include <OpenMesh/Core/System/omstream.hh>
#include <iostream>

namespace mcquad {
namespace {

std::mutex& streams_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

OpenMeshMessages::OpenMeshMessages()
    : lock_(streams_mutex()),
      log_was_enabled_(omlog().is_enabled()),
      errors_went_to_cerr_(omerr().disconnect(std::cerr)),
      log_went_to_clog_(omlog().disconnect(std::clog)) {
  omerr().connect(said_);
  omlog().enable();
  omlog().connect(said_);
}

OpenMeshMessages::~OpenMeshMessages() {
  omerr().flush();
  omlog().flush();
  omerr().disconnect(said_);
  omlog().disconnect(said_);
  if (errors_went_to_cerr_) omerr().connect(std::cerr);
  if (log_went_to_clog_) omlog().connect(std::clog);
  if (!log_was_enabled_) omlog().disable();
}

size_t OpenMeshMessages::count(const std::string& message) {
  omerr().flush();
  omlog().flush();
  const std::string text = said_.str();
  size_t n = 0;
  for (size_t at = text.find(message); at != std::string::npos; at = text.find(message, at + 1)) ++n;
  return n;
}

}  // namespace mcquad
