/* Philox4x32-10 counter-based random number generator (Salmon, Moraes, Dror,
 * Shaw: "Parallel random numbers: as easy as 1, 2, 3", SC'11). Stateless:
 * the same (key, counter) gives the same four words on every device, which is
 * what makes the serial and OpenCL paths draw identical samples. */
#ifndef MCQ_PHILOX_H
#define MCQ_PHILOX_H

typedef struct {
  mcq_uint v[4];
} mcq_philox_block;

MCQ_FN mcq_uint mcq_mulhilo32(mcq_uint a, mcq_uint b, mcq_uint* hi) {
  mcq_ulong product = (mcq_ulong)a * (mcq_ulong)b;
  *hi = (mcq_uint)(product >> 32);
  return (mcq_uint)product;
}

MCQ_FN mcq_philox_block mcq_philox4x32_10(mcq_philox_block counter, mcq_uint key0, mcq_uint key1) {
  const mcq_uint m0 = 0xD2511F53u, m1 = 0xCD9E8D57u;
  const mcq_uint w0 = 0x9E3779B9u, w1 = 0xBB67AE85u;
  mcq_philox_block c = counter;
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      key0 += w0;
      key1 += w1;
    }
    mcq_uint hi0, hi1;
    mcq_uint lo0 = mcq_mulhilo32(m0, c.v[0], &hi0);
    mcq_uint lo1 = mcq_mulhilo32(m1, c.v[2], &hi1);
    mcq_philox_block next;
    next.v[0] = hi1 ^ c.v[1] ^ key0;
    next.v[1] = lo1;
    next.v[2] = hi0 ^ c.v[3] ^ key1;
    next.v[3] = lo0;
    c = next;
  }
  return c;
}

/* Uniform integer in [0, range) from one 32-bit word (multiply-shift; bias
 * below 2^-32 * range, negligible for cell sizes). */
MCQ_FN mcq_uint mcq_uniform_below(mcq_uint word, mcq_uint range) {
  return (mcq_uint)(((mcq_ulong)word * (mcq_ulong)range) >> 32);
}

#endif
