/* The crossing guard's test of a whole step (host/mesh/crossing_guard.h) on
 * the device, so that the positions come back to the host only when the
 * guard has something to hold back. The host prepends shared/mcq_platform.h
 * and shared/mcq_guard.h (double precision, contraction off: see
 * host/opencl/program_cache.cpp); each kernel sets a bit of `found` for
 * what it finds:
 *   1  a pair of the guard's close triangles intersects;
 *   2  a face turned over or fell under its Jacobian floor;
 *   4  two faces across an edge fold over each other;
 *   8  a vertex went far enough from the close pairs' reference positions
 *      that the list may miss a pair (the host builds it again). */

__kernel void guard_test_pairs(__global const float* positions, __global const uint* triangle_corners,
                               __global const uint* pairs, const uint pair_count, __global uint* found) {
  uint i = get_global_id(0);
  if (i >= pair_count) return;
  mcq_d3 a[3], b[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = mcq_d3_load(positions, triangle_corners[3 * pairs[2 * i] + (uint)k]);
    b[k] = mcq_d3_load(positions, triangle_corners[3 * pairs[2 * i + 1] + (uint)k]);
  }
  if (mcq_guard_boxes_overlap(a, b) && mcq_guard_triangles_intersect(a, b)) atomic_or(found, 1u);
}

__kernel void guard_test_faces(__global const float* positions, __global const uint* faces,
                               __global const float* initial_normals, __global const double* floors,
                               const uint face_count, __global uint* found) {
  uint f = get_global_id(0);
  if (f >= face_count) return;
  if (mcq_guard_face_is_bad(positions, faces, initial_normals, floors, f)) atomic_or(found, 2u);
}

__kernel void guard_test_folds(__global const float* positions, __global const uint* faces,
                               __global const uint* fold_pairs, const uint pair_count, __global uint* found) {
  uint i = get_global_id(0);
  if (i >= pair_count) return;
  if (mcq_guard_faces_fold(positions, faces, fold_pairs[2 * i], fold_pairs[2 * i + 1])) atomic_or(found, 4u);
}

__kernel void guard_test_moved(__global const float* positions, __global const float* references,
                               const double move_limit, const uint vertex_count, __global uint* found) {
  uint v = get_global_id(0);
  if (v >= vertex_count) return;
  mcq_d3 d = mcq_d3_sub(mcq_d3_load(positions, v), mcq_d3_load(references, v));
  double most = fabs(d.x) > fabs(d.y) ? fabs(d.x) : fabs(d.y);
  most = fabs(d.z) > most ? fabs(d.z) : most;
  if (2.0 * most > move_limit) atomic_or(found, 8u);
}

/* After a step with nothing found: the floors rise with the quads, up to
 * the guard's least scaled Jacobian, as CrossingGuard::apply raises them. */
__kernel void guard_raise_floors(__global const float* positions, __global const uint* faces, __global double* floors,
                                 const double least, const uint face_count) {
  uint f = get_global_id(0);
  if (f >= face_count) return;
  mcq_d3 corners[4];
  mcq_guard_quad_corners(positions, faces, f, corners);
  double jacobian = mcq_guard_scaled_jacobian(corners);
  double raised = jacobian < least ? jacobian : least;
  floors[f] = raised > floors[f] ? raised : floors[f];
}
