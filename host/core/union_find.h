#pragma once

#include <algorithm>
#include <numeric>
#include <vector>

namespace mcquad {

//! Disjoint sets over 0..n-1 with path halving. The smaller index always
//! leads its set, so the leaders (and whatever is numbered by them) do not
//! depend on the order of the joins.
class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), size_t(0)); }
  size_t find(size_t v) {
    while (parent_[v] != v) v = parent_[v] = parent_[parent_[v]];
    return v;
  }
  void join(size_t a, size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<size_t> parent_;
};

}  // namespace mcquad
