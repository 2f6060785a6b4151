#include "io/skeleton_io.h"

#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "io/file_utils.h"

namespace mcquad {
namespace {

Eigen::Vector3d parse_xyz(const std::string& where, const std::vector<std::string_view>& fields, size_t first) {
  if (fields.size() < first + 3) throw InputError(where + ": expected 3 coordinates");
  Eigen::Vector3d p;
  for (int k = 0; k < 3; ++k) {
    if (!parse_number(fields[first + k], p[k]))
      throw InputError(where + ": '" + std::string(fields[first + k]) + "' is not a number");
  }
  if (!p.allFinite()) throw InputError(where + ": coordinate is NaN or infinite");
  return p;
}

SkeletonData read_obj_skeleton(const std::string& path) {
  MappedFile file(path);
  std::string_view text = file.view();
  SkeletonData skeleton;
  struct PendingLine {
    size_t line_number;
    std::vector<long long> indices;
    size_t nodes_before;
  };
  std::vector<PendingLine> lines;
  for_each_line(text, [&](size_t line_number, std::string_view line) {
    auto fields = split_fields(line);
    if (fields.empty()) return;
    std::string where = path + ": line " + std::to_string(line_number);
    if (fields[0] == "v") {
      skeleton.nodes.push_back(parse_xyz(where, fields, 1));
    } else if (fields[0] == "l") {
      PendingLine pending{line_number, {}, skeleton.nodes.size()};
      for (size_t k = 1; k < fields.size(); ++k) {
        // "l 3/7" style vertex/texture pairs: the vertex index comes first.
        std::string_view field = fields[k].substr(0, fields[k].find('/'));
        long long index;
        if (!parse_integer(field, index))
          throw InputError(where + ": '" + std::string(fields[k]) + "' is not an index");
        pending.indices.push_back(index);
      }
      if (pending.indices.size() < 2) throw InputError(where + ": a line needs at least two vertices");
      lines.push_back(std::move(pending));
    } else if (fields[0] == "f") {
      throw InputError(where + ": skeleton OBJ has a face ('f'); expected only 'v' and 'l' lines");
    }
  });
  for (const auto& line : lines) {
    std::vector<int> resolved;
    for (long long index : line.indices) {
      // Negative indices count back from the vertices defined so far.
      long long zero_based = index > 0 ? index - 1 : static_cast<long long>(line.nodes_before) + index;
      if (index == 0 || zero_based < 0 || zero_based >= static_cast<long long>(skeleton.nodes.size()))
        throw InputError(path + ": line " + std::to_string(line.line_number) + ": vertex index " +
                         std::to_string(index) + " out of range (1.." + std::to_string(skeleton.nodes.size()) + ")");
      resolved.push_back(int(zero_based));
    }
    for (size_t k = 0; k + 1 < resolved.size(); ++k) skeleton.edges.push_back({resolved[k], resolved[k + 1]});
  }
  return skeleton;
}

SkeletonData read_polylines(const std::string& path) {
  MappedFile file(path);
  std::string_view text = file.view();
  SkeletonData skeleton;
  for_each_line(text, [&](size_t line_number, std::string_view line) {
    auto fields = split_fields(line);
    if (fields.empty() || fields[0][0] == '#') return;
    std::string where = path + ": line " + std::to_string(line_number);
    long long n;
    if (!parse_integer(fields[0], n) || n < 0)
      throw InputError(where + ": expected a point count, found '" + std::string(fields[0]) + "'");
    if (n < 2) throw InputError(where + ": a polyline needs at least two points");
    // Compared by division: 3 * n overflows for counts a malformed line may claim.
    if ((fields.size() - 1) % 3 != 0 || (long long)((fields.size() - 1) / 3) != n)
      throw InputError(where + ": polyline claims " + std::to_string(n) + " points but has " +
                       std::to_string(fields.size() - 1) + " coordinates");
    int first = int(skeleton.nodes.size());
    for (long long k = 0; k < n; ++k) skeleton.nodes.push_back(parse_xyz(where, fields, size_t(1 + 3 * k)));
    for (long long k = 0; k + 1 < n; ++k) skeleton.edges.push_back({first + int(k), first + int(k) + 1});
  });
  return skeleton;
}

}  // namespace

SkeletonData read_skeleton(const std::string& path) {
  std::string ext = file_extension(path);
  SkeletonData skeleton;
  if (ext == "obj")
    skeleton = read_obj_skeleton(path);
  else if (ext == "cgal" || ext == "polylines" || ext == "txt" || ext == "polyline")
    skeleton = read_polylines(path);
  else
    throw InputError(path + ": unknown skeleton extension '." + ext +
                     "' (expected .obj, or .cgal/.polylines/.txt for CGAL polylines)");
  if (skeleton.edges.empty()) throw InputError(path + ": the skeleton has no bones (no 'l' lines or polylines)");
  return skeleton;
}

void write_skeleton_obj(const std::string& path, const SkeletonData& skeleton) {
  std::string text = "# skeleton written by mcquad\n";
  char line[160];
  for (const auto& p : skeleton.nodes) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
    text += line;
  }
  for (const auto& e : skeleton.edges) {
    std::snprintf(line, sizeof line, "l %d %d\n", e[0] + 1, e[1] + 1);
    text += line;
  }
  write_text_atomically(path, text);
}

}  // namespace mcquad
