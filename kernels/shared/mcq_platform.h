/* Portability layer for the code shared by the C++ serial path and the OpenCL
 * kernels. Everything under kernels/shared/ compiles as OpenCL C 1.2 and as
 * C++17 (host/core/shared_math.h includes it inside a namespace), so the
 * two backends run the same per-vertex arithmetic and cannot drift apart.
 * Only float arithmetic is used: the device works in float. */
#ifndef MCQ_PLATFORM_H
#define MCQ_PLATFORM_H

#ifdef __OPENCL_C_VERSION__
#define MCQ_GLOBAL __global
#define MCQ_FN static inline
typedef uint mcq_uint;
typedef ulong mcq_ulong;
#define MCQ_SQRT(x) sqrt(x)
#define MCQ_FABS(x) fabs(x)
#define MCQ_SIN(x) sin(x)
#define MCQ_COS(x) cos(x)
#define MCQ_COPYSIGN(x, y) copysign(x, y)
#define MCQ_INFINITY INFINITY
#else
#define MCQ_GLOBAL
#define MCQ_FN static inline
typedef std::uint32_t mcq_uint;
typedef std::uint64_t mcq_ulong;
#define MCQ_SQRT(x) std::sqrt(x)
#define MCQ_FABS(x) std::fabs(x)
#define MCQ_SIN(x) std::sin(x)
#define MCQ_COS(x) std::cos(x)
#define MCQ_COPYSIGN(x, y) std::copysign(x, y)
#define MCQ_INFINITY std::numeric_limits<float>::infinity()
#endif

/* min/max as plain comparisons, identical on host and device (no NaN ever
 * reaches them: directions use safe inverses) and inlined, unlike libm's. */

/* Traversal stack depth; the host refuses trees deeper than this. */
#define MCQ_MAX_TREE_DEPTH 46
#define MCQ_STACK_SIZE 48

MCQ_FN float mcq_min(float a, float b) { return a < b ? a : b; }
MCQ_FN float mcq_max(float a, float b) { return a > b ? a : b; }
#define MCQ_FMIN(a, b) mcq_min(a, b)
#define MCQ_FMAX(a, b) mcq_max(a, b)

typedef struct {
  float x, y, z;
} mcq_vec3;

MCQ_FN mcq_vec3 mcq_make_vec3(float x, float y, float z) {
  mcq_vec3 v;
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}
MCQ_FN mcq_vec3 mcq_load3(const MCQ_GLOBAL float* a, mcq_uint i) {
  return mcq_make_vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
}
MCQ_FN void mcq_store3(MCQ_GLOBAL float* a, mcq_uint i, mcq_vec3 v) {
  a[3 * i] = v.x;
  a[3 * i + 1] = v.y;
  a[3 * i + 2] = v.z;
}
MCQ_FN mcq_vec3 mcq_add(mcq_vec3 a, mcq_vec3 b) { return mcq_make_vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
MCQ_FN mcq_vec3 mcq_sub(mcq_vec3 a, mcq_vec3 b) { return mcq_make_vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
MCQ_FN mcq_vec3 mcq_scale(mcq_vec3 a, float s) { return mcq_make_vec3(a.x * s, a.y * s, a.z * s); }
MCQ_FN float mcq_dot(mcq_vec3 a, mcq_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
MCQ_FN mcq_vec3 mcq_cross(mcq_vec3 a, mcq_vec3 b) {
  return mcq_make_vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
MCQ_FN float mcq_length(mcq_vec3 a) { return MCQ_SQRT(mcq_dot(a, a)); }
/* Returns the zero vector for a zero-length input, so callers can detect it. */
MCQ_FN mcq_vec3 mcq_normalize(mcq_vec3 a) {
  float len = mcq_length(a);
  return len > 0.0f ? mcq_scale(a, 1.0f / len) : mcq_make_vec3(0.0f, 0.0f, 0.0f);
}

#endif
