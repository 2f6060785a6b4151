#include "core/sorted_point_tree.h"

#include <algorithm>
#include <limits>

#include "core/morton.h"

namespace mcquad {
namespace {

//! 21-bit-per-axis Morton codes of the points in their box.
std::vector<uint64_t> morton_codes(const std::vector<Eigen::Vector3f>& points) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : points) box.extend(p);
  const Eigen::Vector3f scale = box.sizes().cwiseMax(1e-30f).cwiseInverse() * float((1 << 21) - 1);
  std::vector<uint64_t> codes(points.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(points.size()); ++i) {
    codes[size_t(i)] = morton_code((points[size_t(i)] - box.min()).cwiseProduct(scale).cwiseMax(0.0f));
  }
  return codes;
}

}  // namespace

SortedPointTree::SortedPointTree(const std::vector<Eigen::Vector3f>& points) : points_(points) {
  if (points.empty()) return;
  nodes_.reserve(2 * (points.size() / kLeafSize + 1));
  nodes_.emplace_back();
  build(0, 0, long(points.size()), morton_codes(points), 64);
}

void SortedPointTree::build(size_t node, long begin, long end, const std::vector<uint64_t>& codes, int bit) {
  if (end - begin <= kLeafSize) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
    for (long i = begin; i < end; ++i) nodes_[node].box.extend(points_[size_t(i)]);
    return;
  }
  // Cut where the highest bit that differs in the range turns on, so that
  // each child is one cell of the Morton grid. In a sorted range that bit
  // falls from parent to child; where it does not (points out of order),
  // or every code is the same, or a child would be empty, cut in the
  // middle. The depth stays under 64 + log2(points) either way.
  long middle = begin + (end - begin) / 2;
  int child_bit = bit;
  uint64_t differing = codes[size_t(begin)] ^ codes[size_t(end - 1)];
  int highest = differing ? 63 - __builtin_clzll(differing) : -1;
  if (highest >= 0 && highest < bit) {
    uint64_t mask = uint64_t(1) << highest;
    long cut = long(std::partition_point(codes.begin() + begin, codes.begin() + end,
                                         [&](uint64_t code) { return (code & mask) == 0; }) -
                    codes.begin());
    if (cut > begin && cut < end) middle = cut, child_bit = highest;
  }
  size_t children = nodes_.size();
  nodes_[node].first = long(children);
  nodes_[node].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build(children, begin, middle, codes, child_bit);
  build(children + 1, middle, end, codes, child_bit);
  nodes_[node].box = nodes_[children].box.merged(nodes_[children + 1].box);
}

std::pair<long, float> SortedPointTree::nearest(const Eigen::Vector3f& query) const {
  long best = -1;
  float best2 = std::numeric_limits<float>::infinity();
  if (nodes_.empty()) return {best, best2};
  std::pair<float, size_t> stack[128];
  int top = 0;
  stack[top++] = {0.0f, 0};
  while (top > 0) {
    auto [distance2, index] = stack[--top];
    if (distance2 > best2) continue;
    const Node& node = nodes_[index];
    if (node.count > 0) {
      for (long i = node.first; i < node.first + node.count; ++i) {
        float d2 = (points_[size_t(i)] - query).squaredNorm();
        if (d2 < best2 || (d2 == best2 && i < best)) best2 = d2, best = i;
      }
      continue;
    }
    size_t left = size_t(node.first), right = left + 1;
    float d_left = nodes_[left].box.squaredExteriorDistance(query),
          d_right = nodes_[right].box.squaredExteriorDistance(query);
    // The nearer child last, so it is taken first.
    if (d_left <= d_right) {
      stack[top++] = {d_right, right};
      stack[top++] = {d_left, left};
    } else {
      stack[top++] = {d_left, left};
      stack[top++] = {d_right, right};
    }
  }
  return {best, best2};
}

}  // namespace mcquad
