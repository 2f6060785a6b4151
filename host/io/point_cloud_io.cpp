#include "io/point_cloud_io.h"

#include <cstdio>

#include "core/errors.h"
#include "io/file_utils.h"
#include "io/ply_io.h"

namespace mcquad {
namespace {

Eigen::Vector3f parse_point(const std::string& where, const std::vector<std::string_view>& fields, size_t first) {
  if (fields.size() < first + 3)
    throw InputError(where + ": expected 3 coordinates, found " + std::to_string(fields.size() - first));
  double xyz[3];
  for (int k = 0; k < 3; ++k) {
    if (!parse_number(fields[first + k], xyz[k]))
      throw InputError(where + ": '" + std::string(fields[first + k]) + "' is not a number");
    if (!std::isfinite(xyz[k])) throw InputError(where + ": coordinate is NaN or infinite");
  }
  return Eigen::Vector3f(float(xyz[0]), float(xyz[1]), float(xyz[2]));
}

PointCloud read_xyz(const std::string& path) {
  MappedFile file(path);
  std::string_view text = file.view();
  PointCloud cloud;
  cloud.points.reserve(text.size() / 24 + 1);
  for_each_line(text, [&](size_t line_number, std::string_view line) {
    auto fields = split_fields(line);
    if (fields.empty() || fields[0][0] == '#') return;
    std::string where = path + ": line " + std::to_string(line_number);
    double ignored;
    // A first line of column names (x,y,z) is a header, not data.
    if (line_number == 1 && !parse_number(fields[0], ignored)) return;
    Eigen::Vector3f p = parse_point(where, fields, 0);
    cloud.points.push_back(p);
    if (fields.size() >= 6) {
      Eigen::Vector3f n;
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        double v = 0;
        ok = ok && parse_number(fields[3 + k], v);
        n[k] = float(v);
      }
      if (ok) cloud.normals.push_back(n);
    }
  });
  return cloud;
}

PointCloud read_obj_vertices(const std::string& path) {
  MappedFile file(path);
  std::string_view text = file.view();
  PointCloud cloud;
  for_each_line(text, [&](size_t line_number, std::string_view line) {
    auto fields = split_fields(line);
    if (fields.empty()) return;
    std::string where = path + ": line " + std::to_string(line_number);
    if (fields[0] == "v")
      cloud.points.push_back(parse_point(where, fields, 1));
    else if (fields[0] == "vn")
      cloud.normals.push_back(parse_point(where, fields, 1));
  });
  return cloud;
}

PointCloud read_off_vertices(const std::string& path) {
  MappedFile file(path);
  std::string_view text = file.view();
  PointCloud cloud;
  enum { kMagic, kCounts, kVertices, kDone } state = kMagic;
  long long vertex_count = 0;
  size_t last_line = 0;
  for_each_line(text, [&](size_t line_number, std::string_view line) {
    last_line = line_number;
    if (state == kDone) return;
    size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    auto fields = split_fields(line);
    if (fields.empty()) return;
    std::string where = path + ": line " + std::to_string(line_number);
    if (state == kMagic) {
      std::string_view magic = fields[0];
      if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF")
        throw InputError(where + ": not an OFF file (no OFF magic)");
      state = kCounts;
      fields.erase(fields.begin());
      if (fields.empty()) return;
    }
    if (state == kCounts) {
      if (!parse_integer(fields[0], vertex_count) || vertex_count < 0) throw InputError(where + ": bad vertex count");
      // Never allocate what the header claims; the text bounds the count.
      cloud.points.reserve(std::min<size_t>(size_t(vertex_count), text.size() / 6 + 1));
      state = vertex_count > 0 ? kVertices : kDone;
      return;
    }
    cloud.points.push_back(parse_point(where, fields, 0));
    if (static_cast<long long>(cloud.points.size()) == vertex_count) state = kDone;
  });
  if (state == kMagic) throw InputError(path + ": not an OFF file (empty)");
  if (static_cast<long long>(cloud.points.size()) < vertex_count)
    throw InputError(path + ": truncated OFF: header claims " + std::to_string(vertex_count) + " vertices, file has " +
                     std::to_string(cloud.points.size()) + " (ends at line " + std::to_string(last_line) + ")");
  return cloud;
}

}  // namespace

PointCloud read_point_cloud(const std::string& path, bool with_normals, size_t sample_size) {
  std::string ext = file_extension(path);
  PointCloud cloud;
  if (ext == "ply")
    cloud = read_ply_cloud(path, with_normals, sample_size);
  else if (ext == "xyz" || ext == "txt" || ext == "csv" || ext == "pts")
    cloud = read_xyz(path);
  else if (ext == "obj")
    cloud = read_obj_vertices(path);
  else if (ext == "off")
    cloud = read_off_vertices(path);
  else
    throw InputError(path + ": unknown point cloud extension '." + ext +
                     "' (expected .ply, .xyz, .txt, .csv, .obj, .off)");
  if (cloud.empty()) throw InputError(path + ": the point cloud is empty");
  // The other formats read every normal; the sample is taken from them.
  if (!with_normals && sample_size > 0 && cloud.oriented.empty()) cloud.oriented = oriented_sample(cloud, sample_size);
  if (cloud.normals.size() != cloud.points.size() || !with_normals) {
    cloud.normals.clear();
    cloud.normals.shrink_to_fit();
  }
  return cloud;
}

void write_point_cloud(const std::string& path, const PointCloud& cloud) {
  std::string ext = file_extension(path);
  if (ext == "ply") return write_ply_cloud(path, cloud);
  if (ext != "xyz" && ext != "txt") throw OutputError(path + ": unknown point cloud extension '." + ext + "'");
  std::string text;
  text.reserve(cloud.size() * 36);
  char line[128];
  for (const auto& p : cloud.points) {
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
    text += line;
  }
  write_text_atomically(path, text);
}

}  // namespace mcquad
