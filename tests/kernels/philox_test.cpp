#include <gtest/gtest.h>

#include "core/shared_math.h"

namespace mcquad {
namespace {

using device::mcq_philox_block;

mcq_philox_block block(uint32_t a, uint32_t b, uint32_t c, uint32_t d) { return mcq_philox_block{{a, b, c, d}}; }

// Known-answer vectors published with Random123 (kat_vectors, philox4x32 10 rounds).
TEST(Philox, MatchesPublishedKnownAnswers) {
  struct Case {
    mcq_philox_block counter;
    uint32_t key0, key1;
    mcq_philox_block expected;
  } cases[] = {
      {block(0, 0, 0, 0), 0, 0, block(0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8)},
      {block(0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff), 0xffffffff, 0xffffffff,
       block(0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd)},
      {block(0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344), 0xa4093822, 0x299f31d0,
       block(0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1)},
  };
  for (const auto& c : cases) {
    mcq_philox_block got = device::mcq_philox4x32_10(c.counter, c.key0, c.key1);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(got.v[k], c.expected.v[k]) << "word " << k;
  }
}

TEST(Philox, UniformBelowCoversTheRangeEvenly) {
  std::vector<int> histogram(7, 0);
  for (uint32_t i = 0; i < 70000; ++i) {
    mcq_philox_block r = device::mcq_philox4x32_10(block(i, 0, 0, 0), 42, 0);
    uint32_t k = device::mcq_uniform_below(r.v[0], 7);
    ASSERT_LT(k, 7u);
    ++histogram[k];
  }
  for (int count : histogram) EXPECT_NEAR(count, 10000, 400);
}

TEST(Philox, SampleIndexMatchesTheStreamUsedByTheStep) {
  // mcq_cell_distance draws sample s from word s % 4 of counter
  // (vertex, ray, s / 4); mcq_sample_index is its documented definition.
  for (uint32_t s = 0; s < 10; ++s) {
    mcq_philox_block r = device::mcq_philox4x32_10(block(5, 3, s / 4, 0), 9, 2);
    EXPECT_EQ(device::mcq_sample_index(9, 2, 5, 3, s, 1000), device::mcq_uniform_below(r.v[s % 4], 1000));
  }
}

}  // namespace
}  // namespace mcquad
