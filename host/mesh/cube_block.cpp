#include "mesh/cube_block.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <numeric>
#include <random>

#include "core/errors.h"

namespace mcquad {
namespace {

Eigen::Vector3d face_normal(int face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
  return n;
}

//! Best injective bone->face assignment for a rotation, by exhaustive search
//! (at most 6!/0! = 720 assignments).
double assignment_score(const Eigen::Matrix3d& rotation, const std::vector<Eigen::Vector3d>& bones,
                        std::vector<int>& best_faces, double& worst) {
  std::array<std::array<double, 6>, 6> cosine{};
  for (size_t b = 0; b < bones.size(); ++b)
    for (int f = 0; f < 6; ++f) cosine[b][f] = (rotation * face_normal(f)).dot(bones[b]);
  std::vector<int> faces(6);
  std::iota(faces.begin(), faces.end(), 0);
  double best = -1e30;
  do {
    double sum = 0, low = 1;
    for (size_t b = 0; b < bones.size(); ++b) {
      sum += cosine[b][faces[b]];
      low = std::min(low, cosine[b][faces[b]]);
    }
    double score = sum + low;
    if (score > best + 1e-12) {
      best = score;
      worst = low;
      best_faces.assign(faces.begin(), faces.begin() + bones.size());
    }
  } while (std::next_permutation(faces.begin(), faces.end()));
  return best;
}

Eigen::Matrix3d frame_from(const Eigen::Vector3d& x, const Eigen::Vector3d& hint) {
  Eigen::Vector3d y = hint - hint.dot(x) * x;
  if (y.norm() < 1e-9) y = x.unitOrthogonal();
  y.normalize();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = x.cross(y);
  return r;
}

}  // namespace

BlockOrientation orient_cube_block(const std::vector<Eigen::Vector3d>& bone_directions) {
  if (bone_directions.size() > 6)
    throw UnsupportedError("a junction of valence " + std::to_string(bone_directions.size()) +
                           " (more than 6 bones) is not supported");
  std::vector<Eigen::Matrix3d> candidates{Eigen::Matrix3d::Identity()};
  const auto& d = bone_directions;
  for (size_t a = 0; a < d.size(); ++a) {
    for (size_t b = 0; b < d.size(); ++b) {
      if (a == b) continue;
      Eigen::Matrix3d r = frame_from(d[a], d[b]);
      candidates.push_back(r);
      for (double angle : {M_PI / 4, -M_PI / 4, M_PI / 8, -M_PI / 8})
        candidates.emplace_back(r * Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix());
      // Bisector of two bones on a block diagonal: suits acute forks.
      Eigen::Vector3d bisector = (d[a] + d[b]).normalized();
      if (bisector.allFinite() && (d[a] + d[b]).norm() > 1e-6) {
        Eigen::Matrix3d s = frame_from(bisector, d[a]);
        candidates.emplace_back(s * Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                                Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix());
      }
    }
  }
  BlockOrientation best;
  double best_score = -1e30;
  auto consider = [&](const Eigen::Matrix3d& r) {
    std::vector<int> faces;
    double worst;
    double score = assignment_score(r, bone_directions, faces, worst);
    if (score > best_score + 1e-12) {
      best_score = score;
      best.rotation = r;
      best.face_of_bone = faces;
      best.worst_cosine = worst;
    }
  };
  for (const auto& r : candidates) consider(r);
  // Polish with small deterministic random rotations (fixed seed).
  std::mt19937 random(12345);  // NOLINT(bugprone-random-generator-seed): the same polish every run
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int step = 0; step < 300; ++step) {
    double scale = 0.3 * (1.0 - step / 300.0) + 0.01;
    Eigen::Vector3d axis(gauss(random), gauss(random), gauss(random));
    Eigen::Matrix3d r = Eigen::AngleAxisd(scale * gauss(random), axis.normalized()).toRotationMatrix() * best.rotation;
    consider(r);
  }
  return best;
}

std::vector<Port> add_cube_block(QuadSoup& soup, const Eigen::Vector3d& center, double size,
                                 const BlockOrientation& orientation,
                                 const std::function<double(const Eigen::Vector3d&)>& reach, bool closed) {
  std::map<std::array<int, 3>, int> grid_vertex;
  auto vertex = [&](const Eigen::Vector3i& g) {
    std::array<int, 3> key{g.x(), g.y(), g.z()};
    auto found = grid_vertex.find(key);
    if (found != grid_vertex.end()) return found->second;
    Eigen::Vector3d direction = orientation.rotation * g.cast<double>().normalized();
    int id = soup.add_vertex(center + std::min(size, reach(direction)) * direction, true);
    grid_vertex.emplace(key, id);
    return id;
  };
  std::vector<int> bone_of_face(6, -1);
  for (size_t b = 0; b < orientation.face_of_bone.size(); ++b) bone_of_face[orientation.face_of_bone[b]] = int(b);
  std::vector<Port> ports(orientation.face_of_bone.size());
  for (int face = 0; face < 6; ++face) {
    int axis = face / 2, sign = face % 2 == 0 ? 1 : -1;
    Eigen::Vector3i normal = Eigen::Vector3i::Zero(), u = Eigen::Vector3i::Zero(), v = Eigen::Vector3i::Zero();
    normal[axis] = sign;
    u[(axis + 1) % 3] = 1;
    v[(axis + 2) % 3] = 1;
    if (sign < 0) std::swap(u, v);  // keeps u x v = outward normal
    static const int kRingXy[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    std::array<int, 8> ring;
    for (int k = 0; k < 8; ++k) ring[k] = vertex(normal + kRingXy[k][0] * u + kRingXy[k][1] * v);
    int bone = bone_of_face[face];
    if (bone < 0 || closed) soup.add_quad_fan(vertex(normal), std::vector<int>(ring.begin(), ring.end()));
    if (bone < 0) continue;
    Port& port = ports[bone];
    port.ring = ring;
    port.outward = orientation.rotation * normal.cast<double>();
    port.center = Eigen::Vector3d::Zero();
    for (int id : ring) port.center += soup.vertices[id] / 8.0;
    port.radius = 0;
    for (int id : ring) port.radius += (soup.vertices[id] - port.center).norm() / 8.0;
  }
  return ports;
}

}  // namespace mcquad
