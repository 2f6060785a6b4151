/* OpenCL kernels of the Monte Carlo evolution. The host prepends
 * shared/mcq_platform.h, shared/mcq_philox.h, shared/mcq_cell_tree.h and
 * shared/mcq_monte_carlo.h (see host/opencl/program_cache.cpp), so these
 * kernels are thin loops over the same functions the serial path calls. */

/* One Jacobi step: every vertex reads the old positions and normals and
 * writes its new position; the normals are updated by update_normals after. */
__kernel void evolve_vertices(
    __global const float* positions, __global const float* normals, __global const float* initial_positions,
    __global const float* initial_normals, __global float* new_positions, __global const uint* faces,
    __global const uint* vertex_face_offsets, __global const uint* vertex_faces, __global const uint* boundary,
    __global const float* node_bounds, __global const int* node_children, __global const uint* cell_offsets,
    __global const float* points, __global const float* cell_centroids, __global const float* cell_normals,
    __global const float* cell_facing, const float bounds_inset, __global const uint* cell_bones,
    __global const uint* vertex_bones, __global const float* vertex_scale, __global const uint* visible_offsets,
    __global const uint* visible_bones, const mcq_step_params params, const uint vertex_count) {
  uint v = get_global_id(0);
  if (v >= vertex_count) return;
  mcq_topology mesh = {faces, vertex_face_offsets, vertex_faces, boundary};
  mcq_cells cells = {node_bounds,    node_children, cell_offsets, points,
                     cell_centroids, cell_normals,  cell_facing,  bounds_inset};
  mcq_regions regions = {cell_bones, vertex_bones, vertex_scale, visible_offsets, visible_bones};
  uint feasible;
  mcq_store3(new_positions, v,
             mcq_evolve_vertex(positions, normals, initial_positions, initial_normals, mesh, cells, regions, v, params,
                               &feasible));
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
                            __global const float* cell_normals, const float bounds_inset, __global float* errors,
                            __global int* nearest_cells, const uint vertex_count) {
  uint v = get_global_id(0);
  if (v >= vertex_count) return;
  mcq_cells cells = {node_bounds, node_children, cell_offsets, points, cell_centroids, cell_normals, 0, bounds_inset};
  int nearest_cell = nearest_cells[v];
  errors[v] = mcq_vertex_error(cells, mcq_load3(positions, v), &nearest_cell);
  nearest_cells[v] = nearest_cell;
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
