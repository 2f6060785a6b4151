/* OpenCL kernels of the Monte Carlo evolution. The host prepends
 * shared/mcq_platform.h, shared/mcq_philox.h, shared/mcq_cell_tree.h and
 * shared/mcq_monte_carlo.h (see host/opencl/program_cache.cpp), so these
 * kernels are thin loops over the same functions the serial path calls. */

/* One Jacobi step: every vertex reads the old positions and normals and
 * writes its new position; the normals are updated by update_normals after. */
__kernel void evolve_vertices(__global const float* positions, __global const float* normals,
                              __global const float* initial_positions, __global const float* initial_normals,
                              __global float* new_positions,
                              __global const uint* faces, __global const uint* vertex_face_offsets,
                              __global const uint* vertex_faces, __global const uint* boundary,
                              __global const float* node_bounds, __global const int* node_children,
                              __global const uint* cell_offsets, __global const float* points,
                              __global const uint* cell_bones, __global const uint* vertex_bones,
                              __global const float* vertex_scale, __global const uint* visible_offsets,
                              __global const uint* visible_bones, const mcq_step_params params,
                              const uint vertex_count) {
  uint v = get_global_id(0);
  if (v >= vertex_count) return;
  mcq_regions regions;
  regions.cell_bones = cell_bones;
  regions.vertex_bones = vertex_bones;
  regions.vertex_scale = vertex_scale;
  regions.visible_offsets = visible_offsets;
  regions.visible_bones = visible_bones;
  uint feasible;
  mcq_store3(new_positions, v,
             mcq_evolve_vertex(positions, normals, initial_positions, initial_normals, faces, vertex_face_offsets,
                               vertex_faces, boundary, node_bounds, node_children, cell_offsets, points, regions, v,
                               params, &feasible));
}

__kernel void relax_tangentially(__global const float* positions, __global const float* normals,
                                 __global const uint* faces, __global const uint* vertex_face_offsets,
                                 __global const uint* vertex_faces, __global const uint* boundary,
                                 __global float* new_positions, const float weight, const uint vertex_count) {
  uint v = get_global_id(0);
  if (v >= vertex_count) return;
  mcq_store3(new_positions, v,
             mcq_relaxed_position(positions, normals, faces, vertex_face_offsets, vertex_faces, boundary, v, weight));
}

__kernel void update_normals(__global const float* positions, __global const uint* faces,
                             __global const uint* vertex_face_offsets, __global const uint* vertex_faces,
                             __global float* normals, const uint vertex_count) {
  uint v = get_global_id(0);
  if (v >= vertex_count) return;
  mcq_store3(normals, v, mcq_vertex_normal(positions, faces, vertex_face_offsets, vertex_faces, v));
}

__kernel void vertex_errors(__global const float* positions, __global const float* node_bounds,
                            __global const int* node_children, __global const uint* cell_offsets,
                            __global const float* points, __global const float* cell_centroids,
                            __global const float* cell_normals, __global float* errors,
                            const uint vertex_count) {
  uint v = get_global_id(0);
  if (v >= vertex_count) return;
  errors[v] = mcq_vertex_error(node_bounds, node_children, cell_offsets, points, cell_centroids, cell_normals,
                               mcq_load3(positions, v));
}

/* Sums `count` floats into partial sums, one per work-group, by a tree
 * reduction in local memory; called twice (many groups, then one) so only a
 * single float crosses to the host. */
__kernel void reduce_sum(__global const float* values, __global float* partial_sums, __local float* scratch,
                         const uint count) {
  uint local_id = get_local_id(0);
  uint group_size = get_local_size(0);
  float sum = 0.0f;
  for (uint i = get_global_id(0); i < count; i += get_global_size(0)) sum += values[i];
  scratch[local_id] = sum;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = group_size / 2; stride > 0; stride /= 2) {
    if (local_id < stride) scratch[local_id] += scratch[local_id + stride];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (local_id == 0) partial_sums[get_group_id(0)] = scratch[0];
}

/* Test hooks: expose single shared functions so tests can compare them with
 * the host build of the same code. */
/* One work-item per origin: its `rays` consecutive directions traced as
 * packets, as the step does, seeing the cells of the `visible_count` bones
 * in `visible` (0: all). */
__kernel void test_ray_hits(__global const float* origins, __global const float* directions, const float reach,
                            __global const float* node_bounds, __global const int* node_children,
                            __global const uint* cell_bones, __global const uint* visible, const uint visible_count,
                            __global int* cells, const uint rays, const uint origin_count) {
  mcq_cell_filter filter;
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
