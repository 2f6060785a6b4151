/* Test hooks, not in the production program: each exposes one shared
 * function so that tests compare it with the host build of the same code.
 * tests/ embeds this file and builds it after the shared headers
 * (test_program in tests/evolution_fixture.h). */

/* One work-item per origin: its `rays` consecutive directions traced as
 * packets, as the step does, seeing the cells of the `visible_count` bones
 * in `visible` (0: all). */
__kernel void test_ray_hits(__global const float* origins, __global const float* directions, const float reach,
                            __global const float* node_bounds, __global const int* node_children,
                            __global const uint* cell_bones, __global const uint* visible, const uint visible_count,
                            __global int* cells, const uint rays, const uint origin_count) {
  mcq_cell_filter filter = mcq_no_cell_filter();
  filter.cell_bones = cell_bones;
  filter.visible = visible;
  filter.count = visible_count;
  uint i = get_global_id(0);
  if (i >= origin_count) return;
  for (uint first = 0; first < rays; first += MCQ_PACKET_SIZE) {
    int count = rays - first < MCQ_PACKET_SIZE ? (int)(rays - first) : MCQ_PACKET_SIZE;
    float x[MCQ_PACKET_SIZE], y[MCQ_PACKET_SIZE], z[MCQ_PACKET_SIZE], entries[MCQ_PACKET_SIZE];
    int hits[MCQ_PACKET_SIZE];
    for (int k = 0; k < count; ++k) {
      mcq_vec3 d = mcq_load3(directions, i * rays + first + (uint)k);
      x[k] = d.x;
      y[k] = d.y;
      z[k] = d.z;
    }
    mcq_first_cell_hits(node_bounds, node_children, filter, mcq_load3(origins, i), x, y, z, count, reach, 0.0f, hits,
                        entries, 0, 0);
    for (int k = 0; k < count; ++k) cells[i * rays + first + (uint)k] = hits[k];
  }
}

__kernel void test_philox(__global const uint* counters, __global const uint* keys, __global uint* out,
                          const uint count) {
  uint i = get_global_id(0);
  if (i >= count) return;
  mcq_philox_block c;
  for (int k = 0; k < 4; ++k) c.v[k] = counters[4 * i + k];
  mcq_philox_block r = mcq_philox4x32_10(c, keys[2 * i], keys[2 * i + 1]);
  for (int k = 0; k < 4; ++k) out[4 * i + k] = r.v[k];
}

__kernel void test_ray_directions(__global const float* normals, const uint cones, const uint generators,
                                  const float alpha_max, __global float* directions, const uint count) {
  uint i = get_global_id(0);
  if (i >= count) return;
  mcq_vec3 n = mcq_load3(normals, i);
  mcq_vec3 ia, ja;
  mcq_cone_frame(n, &ia, &ja);
  uint rays = mcq_ray_count(cones, generators);
  for (uint k = 0; k < rays; ++k)
    mcq_store3(directions, i * rays + k, mcq_ray_direction(n, ia, ja, k, cones, generators, alpha_max));
}
