/* The per-vertex Monte Carlo step of the paper (section 3), its vertex normals
 * and its error level, written once for the serial path and the kernels. */
#ifndef MCQ_MONTE_CARLO_H
#define MCQ_MONTE_CARLO_H

/* Parameters of one step; only 4-byte fields so the layout is identical on
 * the host and on any OpenCL device (passed by value as a kernel argument). */
typedef struct {
  mcq_uint cones;      /* c */
  mcq_uint generators; /* r, rays per cone */
  mcq_uint samples;    /* m, random points per hit cell */
  mcq_uint seed;
  mcq_uint iteration;
  float alpha_max;          /* radians */
  float epsilon;            /* feasibility bound |d| < epsilon */
  float reach;              /* rays look for cells up to this distance */
  mcq_uint fold_guard;      /* 1: shorten steps that would fold a face (robust mode), 0: the paper's step */
  float relaxation;         /* weight of the tangential relaxation before the step; 0: none (the paper) */
  mcq_uint mean_projection; /* 1: a cell's d is the mean of its samples' projections; 0: their minimum (the paper) */
  mcq_uint fill_holes;      /* 1: a vertex no ray finds a feasible cell for takes its neighbours' offset */
  mcq_uint own_cells;       /* 1: a vertex sees only the cells of the bones near its own (skeleton regions) */
  mcq_uint local_epsilon;   /* 1: epsilon and reach scale with the vertex's local radius (skeleton regions) */
  float band; /* > 0: a ray's d averages every cell within this distance of its first hit; 0: the first cell (the paper)
               */
  mcq_uint facing_cells; /* 1: rays pass through cells whose scan normals face away from the vertex's normal */
  float min_facing;      /* with facing_cells, the least dot(cell facing, vertex normal) of a cell a ray may hit */
  mcq_uint curvature_correction; /* 1: each sample's projection is corrected by the mesh's curvature at the vertex;
                                    2: by the curvature of the mesh the evolution started from */
  mcq_uint nearest_plane;        /* 1: a vertex no ray finds a feasible cell for, with the cloud within epsilon,
                                    moves along the scan's normal at its nearest cloud point to that point's level */
} mcq_step_params;

/* Robust mode's skeleton regions, as laid out by host/cells/skeleton_regions.h. */
typedef struct {
  const MCQ_GLOBAL mcq_uint* cell_bones;
  const MCQ_GLOBAL mcq_uint* vertex_bones;
  const MCQ_GLOBAL float* vertex_scale;
  const MCQ_GLOBAL mcq_uint* visible_offsets;
  const MCQ_GLOBAL mcq_uint* visible_bones;
} mcq_regions;

/* The flat cell tree, as laid out by host/cells/cell_tree.h (cells_view). */
typedef struct {
  const MCQ_GLOBAL float* node_bounds;
  const MCQ_GLOBAL int* node_children;
  const MCQ_GLOBAL mcq_uint* cell_offsets;
  const MCQ_GLOBAL float* points;
  const MCQ_GLOBAL float* cell_centroids;
  const MCQ_GLOBAL float* cell_normals;
  const MCQ_GLOBAL float* cell_facing;
  /* How far inside every node's box its points lie at least: the boxes'
   * padding less a rounding margin (CellTree::bounds_inset). */
  float bounds_inset;
} mcq_cells;

/* The quad mesh's connectivity, as laid out by host/mesh/mesh_arrays.h
 * (topology_view). */
typedef struct {
  const MCQ_GLOBAL mcq_uint* faces;
  const MCQ_GLOBAL mcq_uint* vertex_face_offsets;
  const MCQ_GLOBAL mcq_uint* vertex_faces;
  const MCQ_GLOBAL mcq_uint* boundary;
} mcq_topology;

/* A symmetric 3x3 matrix: the shape operator of mcq_vertex_shape_operator. */
typedef struct {
  float xx, xy, xz, yy, yz, zz;
} mcq_shape_operator;

MCQ_FN float mcq_shape_quadratic(mcq_shape_operator k, mcq_vec3 x) {
  return k.xx * x.x * x.x + k.yy * x.y * x.y + k.zz * x.z * x.z +
         2.0f * (k.xy * x.x * x.y + k.xz * x.x * x.z + k.yz * x.y * x.z);
}

/* The cells vertex v, of normal n, may hit: with params.facing_cells those
 * whose scan normals do not face away from n, and with params.own_cells those
 * of the bones near its own; else all. */
MCQ_FN mcq_cell_filter mcq_vertex_cell_filter(mcq_regions regions, const MCQ_GLOBAL float* cell_facing, mcq_uint v,
                                              mcq_vec3 n, mcq_step_params params) {
  mcq_cell_filter filter = mcq_no_cell_filter();
  if (params.facing_cells) {
    filter.facing = cell_facing;
    filter.normal = n;
    filter.min_facing = params.min_facing;
  }
  if (!params.own_cells) return filter;
  mcq_uint bone = regions.vertex_bones[v];
  filter.cell_bones = regions.cell_bones;
  filter.visible = regions.visible_bones + regions.visible_offsets[bone];
  filter.count = regions.visible_offsets[bone + 1] - regions.visible_offsets[bone];
  return filter;
}

/* How much vertex v's epsilon, ray reach and band are scaled: its bone's
 * radius over the median with params.local_epsilon, else 1. */
MCQ_FN float mcq_vertex_scale(mcq_regions regions, mcq_uint v, mcq_step_params params) {
  return params.local_epsilon ? regions.vertex_scale[v] : 1.0f;
}

/* Orthonormal frame (i', j', k' = n) of the paper's cones. The helper axis is
 * the world axis least parallel to n: the paper's fixed (1,0,0) degenerates
 * when n is parallel to x. */
MCQ_FN void mcq_cone_frame(mcq_vec3 n, mcq_vec3* i_axis, mcq_vec3* j_axis) {
  float ax = MCQ_FABS(n.x), ay = MCQ_FABS(n.y), az = MCQ_FABS(n.z);
  mcq_vec3 e = mcq_make_vec3(1.0f, 0.0f, 0.0f);
  if (ay < ax && ay <= az)
    e = mcq_make_vec3(0.0f, 1.0f, 0.0f);
  else if (az < ax && az < ay)
    e = mcq_make_vec3(0.0f, 0.0f, 1.0f);
  *j_axis = mcq_normalize(mcq_cross(n, e));
  *i_axis = mcq_cross(*j_axis, n);
}

/* Number of rays per vertex: the axis plus r generators on each of c cones. */
MCQ_FN mcq_uint mcq_ray_count(mcq_uint cones, mcq_uint generators) { return cones * generators + 1; }

/* Unit direction of ray k: k = 0 is the axis n; k = 1 + (l-1)*r + g is
 * generator g of cone l, at half angle l*alpha_max/c and azimuth 2*pi*g/r. */
MCQ_FN mcq_vec3 mcq_ray_direction(mcq_vec3 n, mcq_vec3 i_axis, mcq_vec3 j_axis, mcq_uint ray, mcq_uint cones,
                                  mcq_uint generators, float alpha_max) {
  if (ray == 0) return n;
  mcq_uint l = (ray - 1) / generators + 1;
  mcq_uint g = (ray - 1) % generators;
  float alpha = (float)l * alpha_max / (float)cones;
  float azimuth = 6.28318530717958647692f * (float)g / (float)generators;
  float s = MCQ_SIN(alpha);
  mcq_vec3 radial = mcq_add(mcq_scale(i_axis, MCQ_COS(azimuth)), mcq_scale(j_axis, MCQ_SIN(azimuth)));
  return mcq_add(mcq_scale(radial, s), mcq_scale(n, MCQ_COS(alpha)));
}

/* Index of random sample `sample` of `ray` of `vertex` inside a cell of
 * `count` points: Philox keyed by (seed, iteration), counter (vertex, ray,
 * sample / 4), word sample % 4. */
MCQ_FN mcq_uint mcq_sample_index(mcq_uint seed, mcq_uint iteration, mcq_uint vertex, mcq_uint ray, mcq_uint sample,
                                 mcq_uint count) {
  mcq_philox_block counter;
  counter.v[0] = vertex;
  counter.v[1] = ray;
  counter.v[2] = sample / 4u;
  counter.v[3] = 0u;
  mcq_philox_block words = mcq_philox4x32_10(counter, seed, iteration);
  return mcq_uniform_below(words.v[sample % 4u], count);
}

/* The cell's distance d along the ray from m random points a_l of the cell:
 * the paper's minimal projection d_j = min_l (a_l - q) . dir, or with
 * params.mean_projection (robust mode) their mean. The minimum is biased
 * toward the vertex by the cell's spread along the ray: by the curvature
 * across the cell, and by about 1.5 sigma under noise of sigma along the
 * normal (the least of 10 samples); the mean estimates the cell's middle,
 * unbiased, and averages the noise away (docs/DESIGN.md). `stream` tells
 * apart the cells of one ray's band, so each draws its own samples. */
MCQ_FN float mcq_cell_distance(const MCQ_GLOBAL mcq_uint* cell_offsets, const MCQ_GLOBAL float* points, int cell,
                               mcq_vec3 q, mcq_vec3 dir, mcq_shape_operator shape, mcq_step_params params,
                               mcq_uint vertex, mcq_uint ray, mcq_uint stream) {
  mcq_uint first = cell_offsets[cell];
  mcq_uint count = cell_offsets[cell + 1] - first;
  float d = MCQ_INFINITY, sum = 0.0f;
  /* Draw four samples per Philox call. */
  for (mcq_uint block = 0; block * 4u < params.samples; ++block) {
    mcq_philox_block counter;
    counter.v[0] = vertex;
    counter.v[1] = ray;
    counter.v[2] = block;
    counter.v[3] = stream;
    mcq_philox_block words = mcq_philox4x32_10(counter, params.seed, params.iteration);
    for (mcq_uint w = 0; w < 4u && block * 4u + w < params.samples; ++w) {
      mcq_uint p = first + mcq_uniform_below(words.v[w], count);
      mcq_vec3 offset = mcq_sub(mcq_load3(points, p), q);
      float projection = mcq_dot(offset, dir);
      /* On a convex surface of shape operator K the ray meets it x.K.x / 2
       * beyond a point x off the ray (x: its offset from the ray's line),
       * while x stays well within the radius of curvature; the correction
       * stops growing at a normal curvature of 0.3 / |x|, where that model
       * no longer holds. Concave directions get none: correcting them too
       * sank the junctions' creases (docs/DESIGN.md). With `shape` zero
       * (the correction off) this is the plain projection. */
      mcq_vec3 off_ray = mcq_sub(offset, mcq_scale(dir, projection));
      float length = MCQ_SQRT(mcq_dot(off_ray, off_ray));
      projection += 0.5f * MCQ_FMIN(MCQ_FMAX(mcq_shape_quadratic(shape, off_ray), 0.0f), 0.3f * length);
      d = MCQ_FMIN(d, projection);
      sum += projection;
    }
  }
  return params.mean_projection ? sum / (float)params.samples : d;
}

/* A ray's distance d to the cloud with robust mode's band (params.band >
 * 0): the mean d of every cell the line crosses within the band around its
 * first hit, behind the vertex too (`cells`, from mcq_band_of_ray), instead
 * of the first cell's alone. Under noise the cloud is a shell several cells
 * thick, and the first cell a ray enters is its innermost layer: a vertex
 * settles at that layer's middle, about 1.2 sigma inside at 10 % noise.
 * The band averages the whole thickness, from both sides of a vertex that
 * sits inside the shell, so it settles at the shell's middle
 * (docs/DESIGN.md). */
MCQ_FN float mcq_band_distance(const MCQ_GLOBAL mcq_uint* cell_offsets, const MCQ_GLOBAL float* points,
                               const int* cells, int count, mcq_vec3 q, mcq_vec3 dir, mcq_shape_operator shape,
                               mcq_step_params params, mcq_uint vertex, mcq_uint ray) {
  /* The ray's m samples are shared among its band's cells (rounded up), so a
   * band costs about as many samples as the paper's single cell. */
  mcq_step_params shared = params;
  shared.samples = (params.samples + (mcq_uint)count - 1u) / (mcq_uint)count;
  float sum = 0.0f;
  for (int k = 0; k < count; ++k)
    sum += mcq_cell_distance(cell_offsets, points, cells[k], q, dir, shape, shared, vertex, ray, (mcq_uint)k);
  return sum / (float)count;
}

/* The paper's displacement of one vertex along its normal: the mean of the
 * feasible minimal projections (|d| < epsilon) over all rays, 0 with none.
 * *feasible receives how many rays were feasible. Robust mode's regions
 * limit the cells the rays see and scale epsilon and the reach; `shape` is
 * the mesh's shape operator at the vertex for the curvature correction
 * (zero without it). */
MCQ_FN float mcq_vertex_displacement(mcq_cells cells, mcq_regions regions, mcq_vec3 q, mcq_vec3 n,
                                     mcq_shape_operator shape, mcq_uint vertex, mcq_step_params params,
                                     mcq_uint* feasible) {
  const MCQ_GLOBAL float* node_bounds = cells.node_bounds;
  const MCQ_GLOBAL int* node_children = cells.node_children;
  const MCQ_GLOBAL mcq_uint* cell_offsets = cells.cell_offsets;
  const MCQ_GLOBAL float* points = cells.points;
  *feasible = 0u;
  mcq_cell_filter filter = mcq_vertex_cell_filter(regions, cells.cell_facing, vertex, n, params);
  float scale = mcq_vertex_scale(regions, vertex, params);
  float epsilon = params.epsilon * scale, reach = params.reach * scale, band = params.band * scale;
  if (mcq_dot(n, n) == 0.0f) return 0.0f;
  mcq_vec3 i_axis, j_axis;
  mcq_cone_frame(n, &i_axis, &j_axis);
  float sum = 0.0f;
  mcq_uint rays = mcq_ray_count(params.cones, params.generators);
  /* Rays go through the tree in packets; the default 26 make one. */
  for (mcq_uint first = 0; first < rays; first += MCQ_PACKET_SIZE) {
    int count = rays - first < MCQ_PACKET_SIZE ? (int)(rays - first) : MCQ_PACKET_SIZE;
    float dir_x[MCQ_PACKET_SIZE], dir_y[MCQ_PACKET_SIZE], dir_z[MCQ_PACKET_SIZE], entries[MCQ_PACKET_SIZE];
    int hits[MCQ_PACKET_SIZE];
    for (int k = 0; k < count; ++k) {
      mcq_vec3 dir =
          mcq_ray_direction(n, i_axis, j_axis, first + (mcq_uint)k, params.cones, params.generators, params.alpha_max);
      dir_x[k] = dir.x;
      dir_y[k] = dir.y;
      dir_z[k] = dir.z;
    }
    int leaves[MCQ_BAND_CANDIDATES], candidates = 0;
    mcq_first_cell_hits(node_bounds, node_children, filter, q, dir_x, dir_y, dir_z, count, reach, band, hits, entries,
                        leaves, &candidates);
    for (int k = 0; k < count; ++k) {
      if (hits[k] < 0) continue;
      mcq_vec3 dir = mcq_make_vec3(dir_x[k], dir_y[k], dir_z[k]);
      mcq_uint ray = first + (mcq_uint)k;
      int in_band[MCQ_BAND_CELLS], banded = 0;
      if (band > 0.0f)
        banded = mcq_band_of_ray(node_bounds, node_children, leaves, candidates, q, dir, entries[k], band, in_band);
      /* banded is 0 with the band off; on, the first hit is in its band unless
       * more than MCQ_BAND_CANDIDATES leaves qualified, and the first cell
       * alone stands in if none is left. */
      float d = banded > 0
                    ? mcq_band_distance(cell_offsets, points, in_band, banded, q, dir, shape, params, vertex, ray)
                    : mcq_cell_distance(cell_offsets, points, hits[k], q, dir, shape, params, vertex, ray, 0u);
      if (MCQ_FABS(d) < epsilon) {
        sum += d;
        *feasible += 1u;
      }
    }
  }
  return *feasible > 0u ? sum / (float)(*feasible) : 0.0f;
}

/* The corner (0 to 3) at which `vertex` sits in quad `face`; 4 when it is
 * not one of its corners. The corners before and after it, (c + 1) % 4 and
 * (c + 3) % 4, are the vertex's edge neighbours; (c + 2) % 4 is its
 * diagonal corner. */
MCQ_FN mcq_uint mcq_corner_of(const MCQ_GLOBAL mcq_uint* faces, mcq_uint face, mcq_uint vertex) {
  mcq_uint c = 0;
  while (c < 4u && faces[4 * face + c] != vertex) ++c;
  return c;
}

/* Area-weighted average unit normal of a vertex: the sum of its quads' vector
 * areas (half the cross product of the diagonals, exact for planar quads and
 * well defined for bent ones), normalized. Zero when degenerate. */
MCQ_FN mcq_vec3 mcq_vertex_normal(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL mcq_uint* faces,
                                  const MCQ_GLOBAL mcq_uint* vertex_face_offsets,
                                  const MCQ_GLOBAL mcq_uint* vertex_faces, mcq_uint vertex) {
  mcq_vec3 sum = mcq_make_vec3(0.0f, 0.0f, 0.0f);
  for (mcq_uint k = vertex_face_offsets[vertex]; k < vertex_face_offsets[vertex + 1]; ++k) {
    mcq_uint f = vertex_faces[k];
    mcq_vec3 p0 = mcq_load3(positions, faces[4 * f]);
    mcq_vec3 p1 = mcq_load3(positions, faces[4 * f + 1]);
    mcq_vec3 p2 = mcq_load3(positions, faces[4 * f + 2]);
    mcq_vec3 p3 = mcq_load3(positions, faces[4 * f + 3]);
    sum = mcq_add(sum, mcq_scale(mcq_cross(mcq_sub(p2, p0), mcq_sub(p3, p1)), 0.5f));
  }
  return mcq_normalize(sum);
}

/* Vector area of face f with vertex `moved` placed at p. */
MCQ_FN mcq_vec3 mcq_face_area_with(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL mcq_uint* faces, mcq_uint f,
                                   mcq_uint moved, mcq_vec3 p) {
  mcq_vec3 c[4];
  for (int k = 0; k < 4; ++k) {
    mcq_uint v = faces[4 * f + k];
    c[k] = v == moved ? p : mcq_load3(positions, v);
  }
  return mcq_cross(mcq_sub(c[2], c[0]), mcq_sub(c[3], c[1]));
}

/* Robust mode's guard: the largest of 1, 1/2, 1/4 of the step from q to
 * `target` that turns no face around the vertex by more than 60 degrees
 * (its neighbours where they were), else 0. At concave creases, vertices
 * from both sides move along their normals into the crease; unguarded they
 * fold their quads and cross each other there (the paper's own caveat). */
MCQ_FN float mcq_fold_safe_fraction(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL mcq_uint* faces,
                                    const MCQ_GLOBAL mcq_uint* vertex_face_offsets,
                                    const MCQ_GLOBAL mcq_uint* vertex_faces, mcq_uint vertex, mcq_vec3 q,
                                    mcq_vec3 target) {
  float fraction = 1.0f;
  for (int attempt = 0; attempt < 3; ++attempt, fraction *= 0.5f) {
    mcq_vec3 p = mcq_add(q, mcq_scale(mcq_sub(target, q), fraction));
    int folds = 0;
    for (mcq_uint k = vertex_face_offsets[vertex]; k < vertex_face_offsets[vertex + 1]; ++k) {
      mcq_uint f = vertex_faces[k];
      mcq_vec3 before = mcq_face_area_with(positions, faces, f, vertex, q);
      mcq_vec3 after = mcq_face_area_with(positions, faces, f, vertex, p);
      if (mcq_dot(before, after) <= 0.5f * mcq_length(before) * mcq_length(after)) folds = 1;
    }
    if (!folds) return fraction;
  }
  return 0.0f;
}

/* How far vertex v has moved along its initial normal since the start. */
MCQ_FN float mcq_offset(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL float* initial_positions,
                        const MCQ_GLOBAL float* initial_normals, mcq_uint v) {
  return mcq_dot(mcq_sub(mcq_load3(positions, v), mcq_load3(initial_positions, v)), mcq_load3(initial_normals, v));
}

/* The mesh's shape operator at a vertex of normal n, as a symmetric 3x3
 * matrix K in space (zero along n), so that x.K.x / |x|^2 is the normal
 * curvature along a tangent direction x (positive where convex). Fitted by
 * least squares to the heights along n of the vertex's edge neighbours and
 * diagonal corners (which, unlike the edges of a regular vertex, span the
 * twist term too): h = h0 - (a u^2 + 2 b u v + c v^2) / 2 in mcq_cone_frame,
 * each weighted by 1 / t^4 (t: its tangential distance) so that each counts
 * alike in curvature. The height h0 is free: the vertex's own place does not
 * enter, or a vertex standing out of its ring would see its ring as convex
 * and be pushed further out. Each direction's curvature is capped at that of
 * a sphere of 2.5 edges' radius: a round tube or cap is 16 edges round at the
 * default resolution, and a junction block's sharper corner is not the
 * surface's. Robust mode's curvature correction uses it (docs/DESIGN.md). */
MCQ_FN mcq_shape_operator mcq_vertex_shape_operator(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL mcq_uint* faces,
                                                    const MCQ_GLOBAL mcq_uint* vertex_face_offsets,
                                                    const MCQ_GLOBAL mcq_uint* vertex_faces, mcq_uint vertex,
                                                    mcq_vec3 q, mcq_vec3 n) {
  mcq_shape_operator k = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  mcq_vec3 u_axis, v_axis;
  mcq_cone_frame(n, &u_axis, &v_axis);
  /* Weighted sums for the normal equations of h = h0 + f.(a, b, c) with
   * f = -(u^2 / 2, u v, v^2 / 2); h0 is eliminated by centring on the
   * weighted means. */
  float sw = 0.0f, sf0 = 0.0f, sf1 = 0.0f, sf2 = 0.0f, sh = 0.0f;
  float s00 = 0.0f, s01 = 0.0f, s02 = 0.0f, s11 = 0.0f, s12 = 0.0f, s22 = 0.0f, s0h = 0.0f, s1h = 0.0f, s2h = 0.0f;
  float lengths = 0.0f, edges = 0.0f;
  for (mcq_uint f = vertex_face_offsets[vertex]; f < vertex_face_offsets[vertex + 1]; ++f) {
    mcq_uint face = vertex_faces[f], c = mcq_corner_of(faces, face, vertex);
    if (c == 4u) continue;
    for (mcq_uint step = 1u; step <= 3u; ++step) {
      mcq_vec3 e = mcq_sub(mcq_load3(positions, faces[4 * face + (c + step) % 4u]), q);
      float u = mcq_dot(e, u_axis), v = mcq_dot(e, v_axis), t2 = u * u + v * v;
      if (!(t2 > 0.0f)) continue;
      if (step != 2u) {
        lengths += MCQ_SQRT(mcq_dot(e, e));
        edges += 1.0f;
      }
      float w = 1.0f / (t2 * t2), h = mcq_dot(e, n);
      float f0 = -0.5f * u * u, f1 = -u * v, f2 = -0.5f * v * v;
      sw += w, sf0 += w * f0, sf1 += w * f1, sf2 += w * f2, sh += w * h;
      s00 += w * f0 * f0, s01 += w * f0 * f1, s02 += w * f0 * f2, s11 += w * f1 * f1, s12 += w * f1 * f2;
      s22 += w * f2 * f2, s0h += w * f0 * h, s1h += w * f1 * h, s2h += w * f2 * h;
    }
  }
  if (edges == 0.0f) return k;
  /* Centred (covariance) form: m = S_ff - S_f S_f' / S_w, r = S_fh - S_f S_h / S_w. */
  float m00 = s00 - sf0 * sf0 / sw, m01 = s01 - sf0 * sf1 / sw, m02 = s02 - sf0 * sf2 / sw;
  float m11 = s11 - sf1 * sf1 / sw, m12 = s12 - sf1 * sf2 / sw, m22 = s22 - sf2 * sf2 / sw;
  float r0 = s0h - sf0 * sh / sw, r1 = s1h - sf1 * sh / sw, r2 = s2h - sf2 * sh / sw;
  float det = m00 * (m11 * m22 - m12 * m12) - m01 * (m01 * m22 - m12 * m02) + m02 * (m01 * m12 - m11 * m02);
  /* Each term of m is dimensionless; a ring that spans too few directions
   * for the three terms leaves m singular. */
  float trace = m00 + m11 + m22;
  if (!(MCQ_FABS(det) > 1e-6f * trace * trace * trace)) return k;
  float a = (r0 * (m11 * m22 - m12 * m12) - m01 * (r1 * m22 - m12 * r2) + m02 * (r1 * m12 - m11 * r2)) / det;
  float b = (m00 * (r1 * m22 - m12 * r2) - r0 * (m01 * m22 - m12 * m02) + m02 * (m01 * r2 - r1 * m02)) / det;
  float c = (m00 * (m11 * r2 - r1 * m12) - m01 * (m01 * r2 - r1 * m02) + r0 * (m01 * m12 - m11 * m02)) / det;
  float cap = 0.4f * edges / lengths;
  a = MCQ_FMIN(a, cap), c = MCQ_FMIN(c, cap), b = MCQ_FMAX(MCQ_FMIN(b, cap), -cap);
  /* K = a u u' + b (u v' + v u') + c v v' */
  k.xx = a * u_axis.x * u_axis.x + 2.0f * b * u_axis.x * v_axis.x + c * v_axis.x * v_axis.x;
  k.yy = a * u_axis.y * u_axis.y + 2.0f * b * u_axis.y * v_axis.y + c * v_axis.y * v_axis.y;
  k.zz = a * u_axis.z * u_axis.z + 2.0f * b * u_axis.z * v_axis.z + c * v_axis.z * v_axis.z;
  k.xy = a * u_axis.x * u_axis.y + b * (u_axis.x * v_axis.y + v_axis.x * u_axis.y) + c * v_axis.x * v_axis.y;
  k.xz = a * u_axis.x * u_axis.z + b * (u_axis.x * v_axis.z + v_axis.x * u_axis.z) + c * v_axis.x * v_axis.z;
  k.yz = a * u_axis.y * u_axis.z + b * (u_axis.y * v_axis.z + v_axis.y * u_axis.z) + c * v_axis.y * v_axis.z;
  return k;
}

/* Robust mode's hole filling: the mean offset of the vertex's edge
 * neighbours (each counted twice, once per face on either side of the edge)
 * laid along its own initial normal from its initial position. Where the
 * scan has a hole, no ray of its vertices finds a feasible cell; instead of
 * staying where the initial mesh put them (a dent of about 0.3 r), they take
 * the offset the surrounding vertices found. Over the iterations the offsets
 * diffuse across the hole, so the mesh spans it at the height of its rim,
 * following the initial mesh's shape rather than flattening it the way an
 * average of positions would. */
MCQ_FN mcq_vec3 mcq_hole_position(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL float* initial_positions,
                                  const MCQ_GLOBAL float* initial_normals, const MCQ_GLOBAL mcq_uint* faces,
                                  const MCQ_GLOBAL mcq_uint* vertex_face_offsets,
                                  const MCQ_GLOBAL mcq_uint* vertex_faces, mcq_uint vertex) {
  float sum = 0.0f, count = 0.0f;
  for (mcq_uint k = vertex_face_offsets[vertex]; k < vertex_face_offsets[vertex + 1]; ++k) {
    mcq_uint f = vertex_faces[k], c = mcq_corner_of(faces, f, vertex);
    if (c == 4u) continue;
    sum += mcq_offset(positions, initial_positions, initial_normals, faces[4 * f + (c + 1u) % 4u]);
    sum += mcq_offset(positions, initial_positions, initial_normals, faces[4 * f + (c + 3u) % 4u]);
    count += 2.0f;
  }
  if (count == 0.0f) return mcq_load3(positions, vertex);
  return mcq_add(mcq_load3(initial_positions, vertex), mcq_scale(mcq_load3(initial_normals, vertex), sum / count));
}

/* Robust mode's blind vertices: where no ray of a vertex finds a feasible
 * cell but the cloud is within epsilon of it, the scan has no hole there;
 * the vertex's cone misses the cloud. That happens in a slit the mesh
 * leaves in a concave crease, whose walls face each other while the
 * cloud's crease lies up the slit, beside their cones (docs/DESIGN.md).
 * Such a vertex moves onto the tangent plane at its nearest cloud point,
 * along that plane's normal: up the slit to the crease's level, and at the
 * rim of a hole onto the surface beside it. The normal is the scan's over
 * the point's cell (cell_facing), else the cell's least-squares plane's
 * where it holds at least 4 points: about a quarter of the cells hold one
 * point and have no plane. Returns 1 and sets *target when the nearest point is
 * within epsilon, its cell belongs to a bone the vertex may see and has a
 * normal; 0 otherwise (a hole, or no normal known there). */
MCQ_FN int mcq_nearest_plane_position(mcq_cells cells, mcq_regions regions, mcq_uint vertex, mcq_vec3 q,
                                      mcq_step_params params, mcq_vec3* target) {
  float epsilon = params.epsilon * mcq_vertex_scale(regions, vertex, params), d2;
  int cell;
  mcq_uint point = mcq_nearest_point(cells.node_bounds, cells.node_children, cells.cell_offsets, cells.points,
                                     cells.bounds_inset, q, -1, &d2, &cell);
  if (cell < 0 || !(d2 < epsilon * epsilon)) return 0;
  /* The bones only: with no facing array the filter has no facing test. */
  mcq_cell_filter bones = mcq_vertex_cell_filter(regions, 0, vertex, mcq_make_vec3(0.0f, 0.0f, 0.0f), params);
  if (!mcq_cell_is_visible(bones, cell)) return 0;
  mcq_vec3 t = mcq_load3(cells.cell_facing, (mcq_uint)cell);
  if (mcq_dot(t, t) == 0.0f) {
    if (cells.cell_offsets[cell + 1] - cells.cell_offsets[cell] < 4u) return 0;
    t = mcq_load3(cells.cell_normals, (mcq_uint)cell);
  }
  *target = mcq_add(q, mcq_scale(t, mcq_dot(t, mcq_sub(mcq_load3(cells.points, point), q))));
  return 1;
}

/* One vertex's new position: the paper's move along the normal; with no
 * feasible ray, the tangent plane at its nearest cloud point where the
 * cloud is within epsilon (params.nearest_plane), else, in a hole
 * (params.fill_holes), the neighbours' offset; any of them shortened by the
 * fold guard when the step asks for it. An open end's rim counts: its rays
 * that leave the tube past the cloud's cut find nothing, and a rim left
 * where the initial mesh put it stays a notch 0.3 r deep. */
MCQ_FN mcq_vec3 mcq_evolve_vertex(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL float* normals,
                                  const MCQ_GLOBAL float* initial_positions, const MCQ_GLOBAL float* initial_normals,
                                  mcq_topology mesh, mcq_cells cells, mcq_regions regions, mcq_uint vertex,
                                  mcq_step_params params, mcq_uint* feasible) {
  mcq_vec3 q = mcq_load3(positions, vertex);
  mcq_vec3 n = mcq_load3(normals, vertex);
  mcq_shape_operator shape = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  if (params.curvature_correction == 1u && !mesh.boundary[vertex])
    shape = mcq_vertex_shape_operator(positions, mesh.faces, mesh.vertex_face_offsets, mesh.vertex_faces, vertex, q, n);
  if (params.curvature_correction == 2u && !mesh.boundary[vertex])
    shape = mcq_vertex_shape_operator(initial_positions, mesh.faces, mesh.vertex_face_offsets, mesh.vertex_faces,
                                      vertex, mcq_load3(initial_positions, vertex), mcq_load3(initial_normals, vertex));
  float delta = mcq_vertex_displacement(cells, regions, q, n, shape, vertex, params, feasible);
  mcq_vec3 target = mcq_add(q, mcq_scale(n, delta));
  int blind =
      *feasible == 0u && params.nearest_plane && mcq_nearest_plane_position(cells, regions, vertex, q, params, &target);
  int in_hole = *feasible == 0u && params.fill_holes && !blind;
  if (in_hole)
    target = mcq_hole_position(positions, initial_positions, initial_normals, mesh.faces, mesh.vertex_face_offsets,
                               mesh.vertex_faces, vertex);
  if (params.fold_guard && (delta != 0.0f || in_hole || blind))
    target =
        mcq_add(q, mcq_scale(mcq_sub(target, q), mcq_fold_safe_fraction(positions, mesh.faces, mesh.vertex_face_offsets,
                                                                        mesh.vertex_faces, vertex, q, target)));
  return target;
}

/* Robust mode's tangential relaxation: the vertex moves toward the mean of
 * its edge neighbours, within its tangent plane (so toward evenly spread,
 * well-shaped quads without leaving the surface). Vertices on an open
 * boundary stay. Every edge neighbour of an inner vertex is counted twice
 * (once per face on each side of the edge), so the mean is unweighted. */
MCQ_FN mcq_vec3 mcq_relaxed_position(const MCQ_GLOBAL float* positions, const MCQ_GLOBAL float* normals,
                                     const MCQ_GLOBAL mcq_uint* faces, const MCQ_GLOBAL mcq_uint* vertex_face_offsets,
                                     const MCQ_GLOBAL mcq_uint* vertex_faces, const MCQ_GLOBAL mcq_uint* boundary,
                                     mcq_uint vertex, float weight) {
  mcq_vec3 q = mcq_load3(positions, vertex);
  if (boundary[vertex]) return q;
  mcq_vec3 sum = mcq_make_vec3(0.0f, 0.0f, 0.0f);
  float count = 0.0f;
  for (mcq_uint k = vertex_face_offsets[vertex]; k < vertex_face_offsets[vertex + 1]; ++k) {
    mcq_uint f = vertex_faces[k], c = mcq_corner_of(faces, f, vertex);
    if (c == 4u) continue;
    sum = mcq_add(sum, mcq_load3(positions, faces[4 * f + (c + 1u) % 4u]));
    sum = mcq_add(sum, mcq_load3(positions, faces[4 * f + (c + 3u) % 4u]));
    count += 2.0f;
  }
  if (count == 0.0f) return q;
  mcq_vec3 n = mcq_load3(normals, vertex);
  mcq_vec3 pull = mcq_sub(mcq_scale(sum, 1.0f / count), q);
  mcq_vec3 tangential = mcq_sub(pull, mcq_scale(n, mcq_dot(pull, n)));
  return mcq_add(q, mcq_scale(tangential, weight));
}

/* The paper's e_i: distance from q to the least-squares plane of the cell
 * holding q's nearest cloud point. *nearest_cell: in, a guess at that cell
 * (-1: none; mcq_nearest_point_cell), out, the cell, for the next step's
 * guess: a vertex moves little in a step (the knot's serial error level
 * 13 % faster, docs/PERFORMANCE.md). */
MCQ_FN float mcq_vertex_error(mcq_cells cells, mcq_vec3 q, int* nearest_cell) {
  float d2;
  int cell = mcq_nearest_point_cell(cells.node_bounds, cells.node_children, cells.cell_offsets, cells.points,
                                    cells.bounds_inset, q, *nearest_cell, &d2);
  *nearest_cell = cell;
  if (cell < 0) return 0.0f;
  mcq_vec3 g = mcq_load3(cells.cell_centroids, (mcq_uint)cell);
  mcq_vec3 t = mcq_load3(cells.cell_normals, (mcq_uint)cell);
  return MCQ_FABS(mcq_dot(t, mcq_sub(q, g)));
}

#endif
