/* The crossing guard's tests of one face or one pair of triangles (host/mesh/
 * crossing_guard.h), in double precision, written once for the host's guard
 * and the device's test of a whole step (kernels/guard.cl). The device
 * program that includes this enables cl_khr_fp64 and turns contraction off,
 * so both sides round every operation alike and give the same answers. */
#ifndef MCQ_GUARD_H
#define MCQ_GUARD_H

typedef struct {
  double x, y, z;
} mcq_d3;

MCQ_FN mcq_d3 mcq_d3_make(double x, double y, double z) {
  mcq_d3 v;
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}
MCQ_FN mcq_d3 mcq_d3_load(const MCQ_GLOBAL float* a, mcq_uint i) {
  return mcq_d3_make((double)a[3 * i], (double)a[3 * i + 1], (double)a[3 * i + 2]);
}
MCQ_FN mcq_d3 mcq_d3_sub(mcq_d3 a, mcq_d3 b) { return mcq_d3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
MCQ_FN double mcq_d3_dot(mcq_d3 a, mcq_d3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
MCQ_FN mcq_d3 mcq_d3_cross(mcq_d3 a, mcq_d3 b) {
  return mcq_d3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
MCQ_FN double mcq_d3_norm(mcq_d3 a) { return MCQ_SQRT(mcq_d3_dot(a, a)); }

/* Whether every corner of triangle t lies strictly on one side of the plane
 * of triangle p: then they cannot meet (the cheap rejection most
 * neighbouring pairs on a smooth surface take). */
MCQ_FN int mcq_guard_strictly_one_side(const mcq_d3* p, const mcq_d3* t) {
  mcq_d3 normal = mcq_d3_cross(mcq_d3_sub(p[1], p[0]), mcq_d3_sub(p[2], p[0]));
  double d0 = mcq_d3_dot(normal, mcq_d3_sub(t[0], p[0]));
  double d1 = mcq_d3_dot(normal, mcq_d3_sub(t[1], p[0]));
  double d2 = mcq_d3_dot(normal, mcq_d3_sub(t[2], p[0]));
  return (d0 > 0.0 && d1 > 0.0 && d2 > 0.0) || (d0 < 0.0 && d1 < 0.0 && d2 < 0.0);
}

/* Moller-Trumbore on the segment p + s (q - p), s in [0, 1], against
 * triangle t; a segment (nearly) parallel to the triangle does not hit it. */
MCQ_FN int mcq_guard_segment_hits_triangle(mcq_d3 p, mcq_d3 q, const mcq_d3* t) {
  const double eps = 1e-12;
  mcq_d3 d = mcq_d3_sub(q, p), e1 = mcq_d3_sub(t[1], t[0]), e2 = mcq_d3_sub(t[2], t[0]);
  mcq_d3 h = mcq_d3_cross(d, e2);
  double det = mcq_d3_dot(e1, h);
  if (MCQ_FABS(det) < eps * mcq_d3_norm(e1) * mcq_d3_norm(e2) * mcq_d3_norm(d)) return 0;
  double inv = 1.0 / det;
  mcq_d3 s = mcq_d3_sub(p, t[0]);
  double u = inv * mcq_d3_dot(s, h);
  if (u < 0.0 || u > 1.0) return 0;
  mcq_d3 qv = mcq_d3_cross(s, e1);
  double v = inv * mcq_d3_dot(d, qv);
  if (v < 0.0 || u + v > 1.0) return 0;
  double along = inv * mcq_d3_dot(e2, qv);
  return along >= 0.0 && along <= 1.0;
}

/* Whether two triangles intersect: an edge of one crosses the other. */
MCQ_FN int mcq_guard_triangles_intersect(const mcq_d3* a, const mcq_d3* b) {
  if (mcq_guard_strictly_one_side(a, b) || mcq_guard_strictly_one_side(b, a)) return 0;
  for (int k = 0; k < 3; ++k) {
    if (mcq_guard_segment_hits_triangle(a[k], a[(k + 1) % 3], b)) return 1;
    if (mcq_guard_segment_hits_triangle(b[k], b[(k + 1) % 3], a)) return 1;
  }
  return 0;
}

/* Whether the two triangles' bounding boxes overlap (touching counts). */
MCQ_FN int mcq_guard_boxes_overlap(const mcq_d3* a, const mcq_d3* b) {
  double lo_a[3], hi_a[3], lo_b[3], hi_b[3];
  for (int axis = 0; axis < 3; ++axis) {
    lo_a[axis] = hi_a[axis] = axis == 0 ? a[0].x : (axis == 1 ? a[0].y : a[0].z);
    lo_b[axis] = hi_b[axis] = axis == 0 ? b[0].x : (axis == 1 ? b[0].y : b[0].z);
    for (int k = 1; k < 3; ++k) {
      double ca = axis == 0 ? a[k].x : (axis == 1 ? a[k].y : a[k].z);
      double cb = axis == 0 ? b[k].x : (axis == 1 ? b[k].y : b[k].z);
      lo_a[axis] = ca < lo_a[axis] ? ca : lo_a[axis];
      hi_a[axis] = ca > hi_a[axis] ? ca : hi_a[axis];
      lo_b[axis] = cb < lo_b[axis] ? cb : lo_b[axis];
      hi_b[axis] = cb > hi_b[axis] ? cb : hi_b[axis];
    }
    if (lo_a[axis] > hi_b[axis] || lo_b[axis] > hi_a[axis]) return 0;
  }
  return 1;
}

/* A quad's unit normal: its vector area (c2 - c0) x (c3 - c1) normalized;
 * zero for a degenerate quad. */
MCQ_FN mcq_d3 mcq_guard_quad_normal(const mcq_d3* c) {
  mcq_d3 n = mcq_d3_cross(mcq_d3_sub(c[2], c[0]), mcq_d3_sub(c[3], c[1]));
  double length = mcq_d3_norm(n);
  return length > 0.0 ? mcq_d3_make(n.x / length, n.y / length, n.z / length) : n;
}

/* Whether two faces' normals (any lengths) are more than 120 degrees apart:
 * the faces fold over each other. */
MCQ_FN int mcq_guard_normals_fold(mcq_d3 a, mcq_d3 b) {
  return mcq_d3_dot(a, b) < -0.5 * mcq_d3_norm(a) * mcq_d3_norm(b);
}

/* A quad's scaled Jacobian: over its corners, the least sine of the corner's
 * angle, signed by the quad's normal (1 for a square, 0 at a corner of 0 or
 * 180 degrees, negative when a corner turns inside out). */
MCQ_FN double mcq_guard_scaled_jacobian(const mcq_d3* c) {
  mcq_d3 normal = mcq_guard_quad_normal(c);
  double jacobian = 1.0;
  for (int k = 0; k < 4; ++k) {
    mcq_d3 to_next = mcq_d3_sub(c[(k + 1) % 4], c[k]), to_previous = mcq_d3_sub(c[(k + 3) % 4], c[k]);
    double lengths = mcq_d3_norm(to_next) * mcq_d3_norm(to_previous);
    double corner = lengths > 0.0 ? mcq_d3_dot(mcq_d3_cross(to_next, to_previous), normal) / lengths : 0.0;
    jacobian = corner < jacobian ? corner : jacobian;
  }
  return jacobian;
}

/* The four corners of quad f at `positions`. */
MCQ_FN void mcq_guard_quad_corners(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL mcq_uint* faces, mcq_uint f,
                                   mcq_d3* corners) {
  for (int k = 0; k < 4; ++k) corners[k] = mcq_d3_load(positions, faces[4 * f + (mcq_uint)k]);
}

/* Whether quad f has turned over (its normal more than 90 degrees from
 * `initial_normals`' one, unit floats) or lost shape (its scaled Jacobian
 * under `floors`' value for it, less a rounding allowance). */
MCQ_FN int mcq_guard_face_is_bad(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL mcq_uint* faces,
                                 const MCQ_GLOBAL float* initial_normals, const MCQ_GLOBAL double* floors, mcq_uint f) {
  mcq_d3 corners[4];
  mcq_guard_quad_corners(positions, faces, f, corners);
  if (mcq_d3_dot(mcq_guard_quad_normal(corners), mcq_d3_load(initial_normals, f)) < 0.0) return 1;
  return mcq_guard_scaled_jacobian(corners) < floors[f] - 1e-6;
}

/* Whether quads f and g fold over each other (normals over 120 degrees apart). */
MCQ_FN int mcq_guard_faces_fold(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL mcq_uint* faces, mcq_uint f,
                                mcq_uint g) {
  mcq_d3 cf[4], cg[4];
  mcq_guard_quad_corners(positions, faces, f, cf);
  mcq_guard_quad_corners(positions, faces, g, cg);
  return mcq_guard_normals_fold(mcq_guard_quad_normal(cf), mcq_guard_quad_normal(cg));
}

#endif
