#include "mesh/crossing_guard.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <numeric>

#include "mesh/face_intersections.h"
#include "mesh/folds.h"
#include "mesh/quad_shape.h"

namespace mcquad {
namespace {

Eigen::Vector3d position(const std::vector<float>& positions, uint32_t v) {
  return {positions[3 * size_t(v)], positions[3 * size_t(v) + 1], positions[3 * size_t(v) + 2]};
}

//! Unit normal of quad f: its vector area (core/quad_mesh.h), as the
//! device's test of a step takes it (kernels/shared/mcq_guard.h).
Eigen::Vector3d face_normal(const MeshArrays& mesh, const std::vector<float>& positions, size_t f) {
  device::mcq_d3 corners[4];
  device::mcq_guard_quad_corners(positions.data(), mesh.faces.data(), uint32_t(f), corners);
  const device::mcq_d3 n = device::mcq_guard_quad_normal(corners);
  return {n.x, n.y, n.z};
}

//! Keeps the face pairs only (single faces have their floors instead).
void drop_single_faces(std::vector<std::pair<int, int>>& defects) {
  defects.erase(std::remove_if(defects.begin(), defects.end(), [](const auto& d) { return d.second < 0; }),
                defects.end());
}

bool vertex_moved(const std::vector<float>& before, const std::vector<float>& after, uint32_t v) {
  size_t i = 3 * size_t(v);
  return before[i] != after[i] || before[i + 1] != after[i + 1] || before[i + 2] != after[i + 2];
}

}  // namespace

CrossingGuard::CrossingGuard(const MeshArrays& mesh)
    : mesh_(mesh),
      triangles_(triangulate(mesh.faces, mesh.positions)),
      close_pairs_(CloseTrianglePairs::half_mean_edge(triangles_)) {
  // Faces across each edge, from the vertex-face lists (no map of edges: at
  // millions of faces that would cost more than the mesh).
  std::vector<std::vector<uint32_t>> across(mesh.face_count());
  for (size_t f = 0; f < mesh.face_count(); ++f)
    for (size_t k = 0; k < 4; ++k) {
      uint32_t a = mesh.faces[4 * f + k], b = mesh.faces[4 * f + (k + 1) % 4];
      for (uint32_t j = mesh.vertex_face_offsets[a]; j < mesh.vertex_face_offsets[a + 1]; ++j) {
        uint32_t g = mesh.vertex_faces[j];
        const uint32_t* q = &mesh.faces[4 * size_t(g)];
        if (g != f && std::find(q, q + 4, b) != q + 4) across[f].push_back(g);
      }
    }
  neighbour_offsets_.push_back(0);
  for (auto& faces : across) {
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    neighbours_.insert(neighbours_.end(), faces.begin(), faces.end());
    neighbour_offsets_.push_back(uint32_t(neighbours_.size()));
  }
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    Eigen::Vector3d n = face_normal(mesh, mesh.positions, f);
    initial_normals_.insert(initial_normals_.end(), {float(n.x()), float(n.y()), float(n.z())});
  }
  jacobian_floor_.assign(mesh.face_count(), -1.0);
  low_faces_.resize(mesh.face_count());
  std::iota(low_faces_.begin(), low_faces_.end(), 0u);
  raise_jacobian_floors(mesh.positions);
  // The start's crossings by a search of their own: the close pairs are
  // made when first needed, at the positions then (the guards of the
  // settling steps start far from here, and a list made here went at once).
  known_ = with_shape_defects(intersecting_face_pairs(triangles_), mesh.positions, nullptr);
  drop_single_faces(known_);
  known_at_ = mesh.positions;
}

GuardArrays CrossingGuard::device_arrays() const {
  GuardArrays arrays;
  // The close pairs at the positions last accepted (triangles_ holds them),
  // if no call has made them yet.
  if (close_pairs_.builds() == 0) close_pairs_.intersecting_face_pairs(triangles_);
  for (const auto& corners : triangles_.corners)
    arrays.triangle_corners.insert(arrays.triangle_corners.end(),
                                   {uint32_t(corners[0]), uint32_t(corners[1]), uint32_t(corners[2])});
  arrays.close_pairs = close_pairs_.flat_pairs();
  arrays.references = close_pairs_.reference_floats();
  arrays.move_limit = close_pairs_.move_limit();
  for (uint32_t f = 0; f + 1 < neighbour_offsets_.size(); ++f)
    for (uint32_t j = neighbour_offsets_[f]; j < neighbour_offsets_[f + 1]; ++j)
      if (neighbours_[j] > f) arrays.fold_pairs.insert(arrays.fold_pairs.end(), {f, neighbours_[j]});
  arrays.initial_normals = initial_normals_;
  arrays.jacobian_floors = jacobian_floor_;
  return arrays;
}

bool CrossingGuard::widen_close_pairs() {
  if (widenings_ >= size_t(kMostWidenings)) return false;
  close_pairs_ = CloseTrianglePairs(2 * close_pairs_.gap());
  ++widenings_;
  // Made now, at the positions last accepted (triangles_ holds them after
  // apply()), so that device_arrays() never hands out an empty list.
  close_pairs_.intersecting_face_pairs(triangles_);
  return true;
}

void CrossingGuard::resume(const std::vector<float>& before, const std::vector<double>& floors) {
  jacobian_floor_ = floors;
  low_faces_.clear();
  for (uint32_t f = 0; f < jacobian_floor_.size(); ++f)
    if (jacobian_floor_[f] < kLeastScaledJacobian) low_faces_.push_back(f);
  known_at_ = before;
}

std::vector<CrossingGuard::Defect> CrossingGuard::defects(const std::vector<float>& positions,
                                                          const std::vector<char>* only_faces) const {
  MeshTriangles triangles = triangulate(mesh_.faces, positions);
  return find_defects(triangles, positions, only_faces);
}

std::vector<CrossingGuard::Defect> CrossingGuard::find_defects(const MeshTriangles& triangles,
                                                               const std::vector<float>& positions,
                                                               const std::vector<char>* only_faces) const {
  return with_shape_defects(close_pairs_.intersecting_face_pairs(triangles, only_faces), positions, only_faces);
}

std::vector<CrossingGuard::Defect> CrossingGuard::with_shape_defects(std::vector<Defect> found,
                                                                     const std::vector<float>& positions,
                                                                     const std::vector<char>* only_faces) const {
  const size_t faces = mesh_.face_count();
  // The faces to test, and those whose normals the fold test needs: theirs
  // and their neighbours'.
  std::vector<int> tested;
  std::vector<char> needs_normal(faces, only_faces ? 0 : 1);
  for (size_t f = 0; f < faces; ++f) {
    if (only_faces && !(*only_faces)[f]) continue;
    tested.push_back(int(f));
    if (!only_faces) continue;
    needs_normal[f] = 1;
    for (uint32_t j = neighbour_offsets_[f]; j < neighbour_offsets_[f + 1]; ++j) needs_normal[neighbours_[j]] = 1;
  }
  std::vector<Eigen::Vector3d> normal(faces);
  const long face_count = long(faces);
#pragma omp parallel for schedule(static) if (face_count > 4096)
  for (long f = 0; f < face_count; ++f)
    if (needs_normal[size_t(f)]) normal[size_t(f)] = face_normal(mesh_, positions, size_t(f));
  // Per tested face, once: whether it turned over or lost shape.
  std::vector<char> bad(tested.size(), 0);
  const long tested_count = long(tested.size());
#pragma omp parallel for schedule(static) if (tested_count > 4096)
  for (long t = 0; t < tested_count; ++t) {
    size_t i = size_t(tested[size_t(t)]);
    bad[size_t(t)] = device::mcq_guard_face_is_bad(positions.data(), mesh_.faces.data(), initial_normals_.data(),
                                                   jacobian_floor_.data(), uint32_t(i));
  }
  for (size_t t = 0; t < tested.size(); ++t) {
    const int f = tested[t];
    if (bad[t]) found.emplace_back(f, -1);
    for (uint32_t j = neighbour_offsets_[size_t(f)]; j < neighbour_offsets_[size_t(f) + 1]; ++j) {
      const int g = int(neighbours_[j]);
      if (only_faces || g > f)  // all faces tested: each pair once
        if (normals_fold(normal[size_t(f)], normal[size_t(g)])) found.emplace_back(std::min(f, g), std::max(f, g));
    }
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

void CrossingGuard::raise_jacobian_floors(const std::vector<float>& positions) {
  std::vector<uint32_t> still_low;
  for (uint32_t f : low_faces_) {
    Eigen::Vector3d corners[4];
    for (size_t k = 0; k < 4; ++k) corners[k] = position(positions, mesh_.faces[4 * size_t(f) + k]);
    jacobian_floor_[f] = std::max(jacobian_floor_[f], std::min(kLeastScaledJacobian, scaled_jacobian(corners)));
    if (jacobian_floor_[f] < kLeastScaledJacobian) still_low.push_back(f);
  }
  low_faces_.swap(still_low);
}

std::vector<uint32_t> CrossingGuard::apply(const std::vector<float>& before, std::vector<float>& after) {
  const std::vector<float> proposed = after;
  // Per vertex, the fraction of its proposed step it takes.
  std::vector<float> fraction(mesh_.vertex_count(), 1.0f);
  size_t held_back = 0;            // how many vertices have been shortened so far
  auto step_length = [&](int f) {  // the longest step a corner of face f takes
    double longest = 0;
    for (int k = 0; k < 4; ++k) {
      uint32_t v = mesh_.faces[4 * size_t(f) + size_t(k)];
      longest = std::max(longest, (position(after, v) - position(before, v)).squaredNorm());
    }
    return longest;
  };
  // Where known_ holds for `before` (every call but one after the guard was
  // made from other positions), the first round may look only at the faces
  // with a corner that moved: among the others the pairs are known_'s, and
  // a defect of theirs alone has no moved corner to hold back. When most
  // faces moved (an evolution step moves every vertex), it tests the whole
  // mesh, which costs less than the faces one by one. Later rounds look only
  // at the faces around vertices just held back (a defect elsewhere was
  // ruled out).
  std::vector<char> dirty(mesh_.face_count(), 0), changed(mesh_.face_count(), 0);
  size_t moved_faces = 0;
  const bool known_holds = known_at_ == before;
  if (known_holds)
    for (uint32_t v = 0; v < mesh_.vertex_count(); ++v)
      if (vertex_moved(before, after, v))
        for (uint32_t j = mesh_.vertex_face_offsets[v]; j < mesh_.vertex_face_offsets[v + 1]; ++j)
          moved_faces += !dirty[mesh_.vertex_faces[j]], dirty[mesh_.vertex_faces[j]] = 1;
  const bool look_at_all = !known_holds || 2 * moved_faces > mesh_.face_count();
  for (size_t v = 0; v < mesh_.vertex_count(); ++v) triangles_.positions[v] = position(after, uint32_t(v));
  std::vector<Defect> found_first;
  for (bool first = true;; first = false) {
    std::vector<Defect> found = find_defects(triangles_, after, first && look_at_all ? nullptr : &dirty);
    if (first) {
      found_first = found;
      if (!look_at_all)
        for (const Defect& d : known_)
          if (!dirty[size_t(d.first)] && !dirty[size_t(d.second)]) found_first.push_back(d);
    }
    std::vector<Defect> fresh;
    std::set_difference(found.begin(), found.end(), known_.begin(), known_.end(), std::back_inserter(fresh));
    std::fill(dirty.begin(), dirty.end(), 0);
    std::vector<uint32_t> shortened;
    for (const auto& [a, b] : fresh) {
      // Usually one face ran into the other: the one that moved further
      // gives way; if that is not enough, the next round shortens again.
      double la = step_length(a), lb = b >= 0 ? step_length(b) : 0.0;
      for (int f : {a, b}) {
        if (f < 0 || (f == a && la < lb) || (f == b && lb < la)) continue;
        for (int k = 0; k < 4; ++k) {
          uint32_t v = mesh_.faces[4 * size_t(f) + size_t(k)];
          if (vertex_moved(before, after, v)) shortened.push_back(v);
        }
      }
    }
    if (shortened.empty()) break;
    std::sort(shortened.begin(), shortened.end());
    shortened.erase(std::unique(shortened.begin(), shortened.end()), shortened.end());
    for (uint32_t v : shortened) {
      held_back += fraction[v] == 1.0f;
      fraction[v] = fraction[v] > 0.125f ? 0.5f * fraction[v] : 0.0f;
      for (size_t i = 3 * size_t(v); i < 3 * size_t(v) + 3; ++i)
        after[i] = fraction[v] > 0.0f ? before[i] + fraction[v] * (proposed[i] - before[i]) : before[i];
      triangles_.positions[v] = position(after, v);
      for (uint32_t j = mesh_.vertex_face_offsets[v]; j < mesh_.vertex_face_offsets[v + 1]; ++j)
        dirty[mesh_.vertex_faces[j]] = changed[mesh_.vertex_faces[j]] = 1;
    }
  }
  // The defects now: those of the first round away from the faces that
  // changed since, and those around the changed faces anew.
  known_.clear();
  for (const Defect& d : found_first)
    if (!changed[size_t(d.first)] && (d.second < 0 || !changed[size_t(d.second)])) known_.push_back(d);
  if (held_back > 0) {
    std::vector<Defect> around_changes = find_defects(triangles_, after, &changed);
    known_.insert(known_.end(), around_changes.begin(), around_changes.end());
  }
  drop_single_faces(known_);
  std::sort(known_.begin(), known_.end());
  known_.erase(std::unique(known_.begin(), known_.end()), known_.end());
  raise_jacobian_floors(after);
  known_at_ = after;
  std::vector<uint32_t> held;
  for (uint32_t v = 0; v < fraction.size(); ++v)
    if (fraction[v] < 1.0f) held.push_back(v);
  return held;
}

}  // namespace mcquad
