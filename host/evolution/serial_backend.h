#pragma once

#include "evolution/evolution_backend.h"

namespace mcquad {

//! The reference path: plain loops over the vertices calling the shared
//! per-vertex functions, single-threaded and deterministic.
class SerialBackend : public EvolutionBackend {
 public:
  std::string name() const override { return "serial"; }
  std::string device_name() const override { return "host CPU (one thread)"; }
  void load(const CellTree& cells, const MeshArrays& mesh, const SkeletonRegions& regions) override;
  void step(const device::mcq_step_params& params) override;
  double error_level() override;
  std::vector<float> positions() override { return positions_; }
  std::vector<float> normals() override { return normals_; }
  void set_positions(const std::vector<float>& positions) override;

 private:
  void update_normals();
  void relax(float weight);

  const CellTree* cells_ = nullptr;
  const SkeletonRegions* regions_ = nullptr;
  MeshArrays mesh_;
  std::vector<float> positions_, next_positions_, normals_;
  std::vector<float> initial_normals_;  //!< at load; the initial positions stay in mesh_
  std::vector<int> nearest_cells_;      //!< each vertex's nearest cell at the last error level, a guess for the next
};

}  // namespace mcquad
