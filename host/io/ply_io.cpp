#include "io/ply_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <sstream>

#include "core/errors.h"
#include "io/file_utils.h"

namespace mcquad {
namespace {

enum class PlyFormat { kAscii, kBinaryLittle, kBinaryBig };

struct PlyProperty {
  std::string name;
  int size = 0;     // bytes of the scalar (or of each list item)
  char kind = 'f';  // 'i' signed, 'u' unsigned, 'f' floating
  bool is_list = false;
  int count_size = 0;  // bytes of the list length
  char count_kind = 'u';
};

struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> properties;
  bool has_lists() const {
    for (const auto& p : properties)
      if (p.is_list) return true;
    return false;
  }
  size_t fixed_stride() const {
    size_t stride = 0;
    for (const auto& p : properties) stride += p.size;
    return stride;
  }
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;
};

bool scalar_type(const std::string& type, int& size, char& kind) {
  static const std::array<std::pair<const char*, std::pair<int, char>>, 16> kTypes{{
      {"char", {1, 'i'}},
      {"int8", {1, 'i'}},
      {"uchar", {1, 'u'}},
      {"uint8", {1, 'u'}},
      {"short", {2, 'i'}},
      {"int16", {2, 'i'}},
      {"ushort", {2, 'u'}},
      {"uint16", {2, 'u'}},
      {"int", {4, 'i'}},
      {"int32", {4, 'i'}},
      {"uint", {4, 'u'}},
      {"uint32", {4, 'u'}},
      {"float", {4, 'f'}},
      {"float32", {4, 'f'}},
      {"double", {8, 'f'}},
      {"float64", {8, 'f'}},
  }};
  for (const auto& [name, info] : kTypes) {
    if (type == name) {
      size = info.first;
      kind = info.second;
      return true;
    }
  }
  return false;
}

PlyHeader parse_header(const std::string& path, std::string_view bytes) {
  auto fail = [&](size_t line, const std::string& what) -> InputError {
    return InputError(path + ": PLY header line " + std::to_string(line) + ": " + what);
  };
  if (bytes.compare(0, 3, "ply") != 0) throw InputError(path + ": not a PLY file (no 'ply' magic)");
  // A header is small: look for its end in the first megabyte only.
  size_t end = bytes.substr(0, size_t(1) << 20).find("end_header");
  if (end == std::string::npos) throw InputError(path + ": truncated PLY header (no end_header)");
  size_t body = bytes.find('\n', end);
  if (body == std::string::npos) throw InputError(path + ": truncated PLY header (end_header not terminated)");
  PlyHeader header;
  header.body_offset = body + 1;
  bool have_format = false;
  std::istringstream lines(std::string(bytes.substr(0, end)));
  std::string line;
  size_t number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || keyword == "ply" || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string format, version;
      words >> format >> version;
      if (format == "ascii")
        header.format = PlyFormat::kAscii;
      else if (format == "binary_little_endian")
        header.format = PlyFormat::kBinaryLittle;
      else if (format == "binary_big_endian")
        header.format = PlyFormat::kBinaryBig;
      else
        throw fail(number, "unknown format '" + format + "'");
      have_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      std::string count;
      words >> element.name >> count;
      long long value;
      if (element.name.empty() || !parse_integer(count, value) || value < 0)
        throw fail(number, "bad element declaration '" + line + "'");
      element.count = static_cast<unsigned long long>(value);
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty()) throw fail(number, "property before any element");
      PlyProperty property;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> property.name;
        char item_kind;
        if (!scalar_type(count_type, property.count_size, property.count_kind) ||
            !scalar_type(item_type, property.size, item_kind) || property.count_kind == 'f')
          throw fail(number, "bad list property '" + line + "'");
        property.kind = item_kind;
        property.is_list = true;
      } else {
        words >> property.name;
        if (!scalar_type(type, property.size, property.kind))
          throw fail(number, "unknown property type '" + type + "'");
      }
      if (property.name.empty()) throw fail(number, "property without a name");
      header.elements.back().properties.push_back(property);
    } else {
      throw fail(number, "unknown keyword '" + keyword + "'");
    }
  }
  if (!have_format) throw InputError(path + ": PLY header has no format line");
  return header;
}

//! Reads scalars from a binary body with the file's byte order.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view bytes, size_t offset, bool big_endian)
      : bytes_(bytes), offset_(offset), swap_(big_endian) {}

  size_t remaining() const { return bytes_.size() - offset_; }
  size_t offset() const { return offset_; }
  void skip(size_t n) { offset_ += n; }

  double read(int size, char kind) {
    double value = decode_at(bytes_.data() + offset_, size, kind, swap_);
    offset_ += size_t(size);
    return value;
  }

  //! The scalar of `size` bytes and `kind` at `at`, bytes swapped first when
  //! the file's byte order is not this machine's.
  static double decode_at(const char* at, int size, char kind, bool swap) {
    unsigned char raw[8];
    std::memcpy(raw, at, size_t(size));
    if (swap)
      for (int i = 0; i < size / 2; ++i) std::swap(raw[i], raw[size - 1 - i]);
    return decode(raw, size, kind);
  }

  static double decode(const unsigned char* raw, int size, char kind) {
    switch (size) {
      case 1:
        return kind == 'i' ? double(static_cast<int8_t>(raw[0])) : double(raw[0]);
      case 2: {
        uint16_t v;
        std::memcpy(&v, raw, 2);
        return kind == 'i' ? double(static_cast<int16_t>(v)) : double(v);
      }
      case 4: {
        if (kind == 'f') {
          float f;
          std::memcpy(&f, raw, 4);
          return f;
        }
        uint32_t v;
        std::memcpy(&v, raw, 4);
        return kind == 'i' ? double(static_cast<int32_t>(v)) : double(v);
      }
      default: {
        double d;
        std::memcpy(&d, raw, 8);
        return d;
      }
    }
  }

 private:
  std::string_view bytes_;
  size_t offset_;
  bool swap_;
};

struct VertexColumns {
  int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1;
  //! 0: normals (when read) go to cloud.normals; k: every k-th goes to cloud.oriented.
  unsigned long long sample_stride = 0;
};

//! The columns, with the stride that keeps about `oriented_sample` normals (0: all or none).
VertexColumns find_columns(const std::string& path, const PlyElement& vertex, bool with_normals,
                           size_t oriented_sample);

VertexColumns find_columns(const std::string& path, const PlyElement& vertex, bool with_normals,
                           size_t oriented_sample) {
  VertexColumns c;
  for (size_t i = 0; i < vertex.properties.size(); ++i) {
    const auto& p = vertex.properties[i];
    int* slot = p.name == "x"    ? &c.x
                : p.name == "y"  ? &c.y
                : p.name == "z"  ? &c.z
                : p.name == "nx" ? &c.nx
                : p.name == "ny" ? &c.ny
                : p.name == "nz" ? &c.nz
                                 : nullptr;
    if (slot && !p.is_list) *slot = static_cast<int>(i);
  }
  if (c.x < 0 || c.y < 0 || c.z < 0) throw InputError(path + ": PLY vertex element lacks x, y or z");
  if (!with_normals && oriented_sample == 0) c.nx = c.ny = c.nz = -1;
  if (!with_normals && oriented_sample > 0)
    c.sample_stride = std::max<unsigned long long>(1, (vertex.count + oriented_sample - 1) / oriented_sample);
  return c;
}

void store_vertex(const std::string& path, PointCloud& cloud, const VertexColumns& c, const double* values,
                  unsigned long long index) {
  Eigen::Vector3d p(values[c.x], values[c.y], values[c.z]);
  if (!p.allFinite()) throw InputError(path + ": vertex " + std::to_string(index) + ": coordinate is NaN or infinite");
  cloud.points.emplace_back(p.cast<float>());
  if (c.nx < 0 || c.ny < 0 || c.nz < 0) return;
  Eigen::Vector3f n(static_cast<float>(values[c.nx]), static_cast<float>(values[c.ny]),
                    static_cast<float>(values[c.nz]));
  if (c.sample_stride == 0)
    cloud.normals.push_back(n);
  else if (index % c.sample_stride == 0)
    add_oriented_point(cloud.oriented, cloud.points.back(), n);
}

void skip_binary_element(const std::string& path, const PlyElement& element, BinaryCursor& cursor) {
  if (!element.has_lists()) {
    size_t need = element.fixed_stride();
    if (need != 0 && element.count > cursor.remaining() / need)
      throw InputError(path + ": truncated PLY: element '" + element.name + "' claims " +
                       std::to_string(element.count) + " entries, more than the file holds");
    cursor.skip(need * element.count);
    return;
  }
  for (unsigned long long i = 0; i < element.count; ++i) {
    for (const auto& p : element.properties) {
      size_t need = p.is_list ? p.count_size : p.size;
      if (cursor.remaining() < need)
        throw InputError(path + ": truncated PLY in element '" + element.name + "' entry " + std::to_string(i));
      if (!p.is_list) {
        cursor.skip(p.size);
        continue;
      }
      double n = cursor.read(p.count_size, p.count_kind);
      if (n < 0 || n * p.size > double(cursor.remaining()))
        throw InputError(path + ": truncated PLY in element '" + element.name + "' entry " + std::to_string(i));
      cursor.skip(static_cast<size_t>(n) * p.size);
    }
  }
}

//! One scalar column of a fixed-size binary record.
struct BinaryColumn {
  size_t offset = 0;  //!< bytes from the record's start
  int size = 0;
  char kind = 'f';
};

//! The columns of `element`'s fixed-size records, in property order.
std::vector<BinaryColumn> binary_columns(const PlyElement& element) {
  std::vector<BinaryColumn> columns;
  size_t offset = 0;
  for (const auto& p : element.properties) {
    columns.push_back({offset, p.size, p.kind});
    offset += size_t(p.size);
  }
  return columns;
}

double read_column(const char* record, const BinaryColumn& column, bool swap) {
  return BinaryCursor::decode_at(record + column.offset, column.size, column.kind, swap);
}

//! The vertex records at `body`: only the wanted columns are decoded, a
//! chunk of records at a time on all cores, and the mapped pages of each
//! chunk are dropped once read (at 10^8 points the file is 2.4 GB, twice
//! the points it holds; it took 12 s one value at a time).
void read_binary_vertex_records(const std::string& path, const char* body, const PlyElement& element,
                                const VertexColumns& wanted, bool swap, const std::function<void(size_t)>& done_before,
                                PointCloud& cloud) {
  const std::vector<BinaryColumn> columns = binary_columns(element);
  const size_t stride = element.fixed_stride(), count = size_t(element.count);
  auto vector_at = [&](size_t i, int a, int b, int c) {
    const char* record = body + i * stride;
    return Eigen::Vector3d(read_column(record, columns[size_t(a)], swap), read_column(record, columns[size_t(b)], swap),
                           read_column(record, columns[size_t(c)], swap));
  };
  const bool normals = wanted.nx >= 0 && wanted.ny >= 0 && wanted.nz >= 0;
  cloud.points.resize(count);
  if (normals && wanted.sample_stride == 0) cloud.normals.resize(count);
  constexpr size_t kChunk = size_t(1) << 20;
  for (size_t begin = 0; begin < count; begin += kChunk) {
    const long end = long(std::min(count, begin + kChunk));
    long bad = end;
#pragma omp parallel for schedule(static) reduction(min : bad)
    for (long i = long(begin); i < end; ++i) {
      Eigen::Vector3d p = vector_at(size_t(i), wanted.x, wanted.y, wanted.z);
      if (!p.allFinite()) bad = std::min(bad, i);
      cloud.points[size_t(i)] = p.cast<float>();
      if (normals && wanted.sample_stride == 0)
        cloud.normals[size_t(i)] = vector_at(size_t(i), wanted.nx, wanted.ny, wanted.nz).cast<float>();
    }
    if (bad < end) throw InputError(path + ": vertex " + std::to_string(bad) + ": coordinate is NaN or infinite");
    if (normals && wanted.sample_stride > 0) {
      size_t stride_k = size_t(wanted.sample_stride);
      for (size_t i = (begin + stride_k - 1) / stride_k * stride_k; i < size_t(end); i += stride_k)
        add_oriented_point(cloud.oriented, cloud.points[i],
                           vector_at(i, wanted.nx, wanted.ny, wanted.nz).cast<float>());
    }
    done_before(size_t(end) * stride);
  }
}

PointCloud read_binary_vertices(const std::string& path, std::string_view bytes, const PlyHeader& header,
                                bool with_normals, size_t oriented_sample, const MappedFile& file) {
  BinaryCursor cursor(bytes, header.body_offset, header.format == PlyFormat::kBinaryBig);
  PointCloud cloud;
  for (const auto& element : header.elements) {
    if (element.name != "vertex") {
      skip_binary_element(path, element, cursor);
      continue;
    }
    if (element.has_lists()) throw InputError(path + ": PLY vertex element with list properties is not supported");
    VertexColumns columns = find_columns(path, element, with_normals, oriented_sample);
    size_t stride = element.fixed_stride();
    if (element.count > cursor.remaining() / stride)
      throw InputError(path + ": truncated PLY: header claims " + std::to_string(element.count) + " vertices of " +
                       std::to_string(stride) + " bytes but only " + std::to_string(cursor.remaining()) +
                       " bytes follow");
    const size_t body = cursor.offset();
    read_binary_vertex_records(
        path, bytes.data() + body, element, columns, header.format == PlyFormat::kBinaryBig,
        [&](size_t read) { file.release_before(body + read); }, cloud);
    return cloud;
  }
  throw InputError(path + ": PLY has no vertex element");
}

PointCloud read_ascii_vertices(const std::string& path, std::string_view bytes, const PlyHeader& header,
                               bool with_normals, size_t oriented_sample) {
  std::string_view body = bytes.substr(header.body_offset);
  PointCloud cloud;
  size_t element_index = 0;
  unsigned long long entry = 0;
  const PlyElement* element = nullptr;
  std::optional<VertexColumns> columns;
  std::vector<double> values;
  size_t header_lines = 0;
  for (char ch : bytes.substr(0, header.body_offset))
    if (ch == '\n') ++header_lines;
  auto advance_element = [&]() {
    while (element_index < header.elements.size() && header.elements[element_index].count == 0) ++element_index;
    element = element_index < header.elements.size() ? &header.elements[element_index] : nullptr;
    entry = 0;
    if (element && element->name == "vertex") {
      columns = find_columns(path, *element, with_normals, oriented_sample);
      // Never trust the header's count for an allocation: cap by what the body can hold.
      cloud.points.reserve(std::min<unsigned long long>(element->count, body.size() / 6 + 1));
    }
  };
  advance_element();
  bool done = false;
  for_each_line(body, [&](size_t line_number, std::string_view line) {
    if (done || !element) return;
    auto fields = split_fields(line);
    if (fields.empty()) return;
    std::string where = path + ": line " + std::to_string(header_lines + line_number);
    if (element->name == "vertex") {
      values.assign(element->properties.size(), 0.0);
      if (fields.size() < element->properties.size())
        throw InputError(where + ": vertex " + std::to_string(entry) + " has " + std::to_string(fields.size()) +
                         " values, expected " + std::to_string(element->properties.size()));
      for (size_t k = 0; k < element->properties.size(); ++k)
        if (!parse_number(fields[k], values[k]))
          throw InputError(where + ": '" + std::string(fields[k]) + "' is not a number");
      store_vertex(where, cloud, *columns, values.data(), entry);
    }
    if (++entry == element->count) {
      if (element->name == "vertex") done = true;
      ++element_index;
      advance_element();
    }
  });
  bool has_vertex = false;
  for (const auto& e : header.elements) has_vertex = has_vertex || e.name == "vertex";
  if (!has_vertex) throw InputError(path + ": PLY has no vertex element");
  for (const auto& e : header.elements) {
    if (e.name == "vertex" && cloud.points.size() < e.count)
      throw InputError(path + ": truncated PLY: header claims " + std::to_string(e.count) + " vertices, file has " +
                       std::to_string(cloud.points.size()));
  }
  return cloud;
}

}  // namespace

PointCloud read_ply_cloud(const std::string& path, bool with_normals, size_t oriented_sample) {
  MappedFile file(path);
  std::string_view bytes = file.view();
  PlyHeader header = parse_header(path, bytes);
  PointCloud cloud = header.format == PlyFormat::kAscii
                         ? read_ascii_vertices(path, bytes, header, with_normals, oriented_sample)
                         : read_binary_vertices(path, bytes, header, with_normals, oriented_sample, file);
  if (cloud.normals.size() != cloud.points.size()) cloud.normals.clear();
  return cloud;
}

void write_ply_cloud(const std::string& path, const PointCloud& cloud) {
  bool with_normals = cloud.normals.size() == cloud.points.size() && !cloud.points.empty();
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by mcquad\nelement vertex " +
                       std::to_string(cloud.size()) + "\nproperty float x\nproperty float y\nproperty float z\n";
  if (with_normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  header += "end_header\n";
  std::string bytes = header;
  size_t stride = with_normals ? 24 : 12;
  bytes.resize(header.size() + stride * cloud.size());
  char* out = bytes.data() + header.size();
  static_assert(sizeof(float) == 4);
  for (size_t i = 0; i < cloud.size(); ++i, out += stride) {
    std::memcpy(out, cloud.points[i].data(), 12);
    if (with_normals) std::memcpy(out + 12, cloud.normals[i].data(), 12);
  }
  write_text_atomically(path, bytes);
}

}  // namespace mcquad
