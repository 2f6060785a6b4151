#pragma once

#include <mutex>
#include <sstream>
#include <string>

namespace mcquad {

//! While it lives, what OpenMesh says on its omerr and omlog streams goes to
//! a buffer instead of the terminal. A face OpenMesh cannot add is reported
//! there only ("PolyMeshT::add_face: complex edge"): its readers drop the
//! face or give it copies of its corners, and add_face returns an invalid
//! handle. mcquad says what went wrong itself, in one line naming the file
//! (io/mesh_io.h, mesh/initial_mesh.h). The streams are the process's, so
//! one holder at a time (fits on several threads read meshes for their
//! HTML reports).
class OpenMeshMessages {
 public:
  OpenMeshMessages();
  ~OpenMeshMessages();
  OpenMeshMessages(const OpenMeshMessages&) = delete;
  OpenMeshMessages& operator=(const OpenMeshMessages&) = delete;
  //! How many times OpenMesh has said `message` so far.
  size_t count(const std::string& message);

 private:
  std::lock_guard<std::mutex> lock_;
  const bool log_was_enabled_, errors_went_to_cerr_, log_went_to_clog_;
  std::ostringstream said_;
};

}  // namespace mcquad
