#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace mcquad {

//! Vertices and quads (counter-clockwise seen from outside) while the initial
//! mesh is assembled; turned into an OpenMesh mesh once complete.
struct QuadSoup {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 4>> quads;
  std::vector<bool> irregular_allowed;  //!< per vertex: on a junction block or a cap

  //! How much the soup holds, to go back to (truncate).
  struct Size {
    size_t vertices = 0, quads = 0;
  };
  Size size() const { return {vertices.size(), quads.size()}; }
  //! Drops what was added after `size()` gave `to`.
  void truncate(const Size& to) {
    vertices.resize(to.vertices);
    irregular_allowed.resize(to.vertices);
    quads.resize(to.quads);
  }

  int add_vertex(const Eigen::Vector3d& p, bool on_block_or_cap = false) {
    vertices.push_back(p);
    irregular_allowed.push_back(on_block_or_cap);
    return int(vertices.size()) - 1;
  }

  //! Closes a polygon of a split face (counter-clockwise `boundary`, even
  //! positions its edge midpoints, odd ones its corners) with one quad per
  //! corner round `middle`.
  void add_quad_fan(int middle, const std::vector<int>& boundary) {
    const size_t n = boundary.size();
    for (size_t k = 0; k < n; k += 2) quads.push_back({middle, boundary[k], boundary[k + 1], boundary[(k + 2) % n]});
  }
};

//! Where a tube attaches: a ring of 8 vertices, counter-clockwise around
//! `outward` (the direction the tube leaves in), and the ring's centre.
struct Port {
  std::array<int, 8> ring{};
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d outward = Eigen::Vector3d::UnitZ();
  double radius = 0;  //!< mean distance of the ring's vertices from its centre
};

}  // namespace mcquad
