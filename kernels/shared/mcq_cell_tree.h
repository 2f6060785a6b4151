/* Queries over the flattened cell tree (host/cells/cell_tree.h builds it).
 *
 * Layout, structure of arrays:
 *   node_bounds[6*i .. 6*i+5]  tight box of node i: min x,y,z then max x,y,z
 *   node_children[2*i], [2*i+1] children of an inner node; a leaf stores
 *                                -1 - cell in [2*i] and -1 in [2*i+1]
 *   cell_offsets[c] .. cell_offsets[c+1]  the cell's points in `points`
 *   points[3*p ..]               cloud points reordered by cell
 * Node 0 is the root. */
#ifndef MCQ_CELL_TREE_H
#define MCQ_CELL_TREE_H

/* Which cells a traversal may hit, in robust mode (host/cells/skeleton_regions.h,
 * host/cells/cell_facing.h): a cell is visible when its bone, cell_bones[cell],
 * is among the `count` bones in `visible` (with count 0 every bone is), and,
 * with `facing` set, when the scan's outward direction over the cell,
 * facing[cell] (unit, or zero where unknown), is within the angle whose
 * cosine is min_facing of `normal`. Unknown cells stay visible. */
typedef struct {
  const MCQ_GLOBAL mcq_uint* cell_bones;
  const MCQ_GLOBAL mcq_uint* visible;
  mcq_uint count;
  const MCQ_GLOBAL float* facing;
  mcq_vec3 normal;
  float min_facing;
} mcq_cell_filter;

MCQ_FN mcq_cell_filter mcq_no_cell_filter(void) {
  mcq_cell_filter filter;
  filter.cell_bones = 0;
  filter.visible = 0;
  filter.count = 0u;
  filter.facing = 0;
  filter.normal = mcq_make_vec3(0.0f, 0.0f, 0.0f);
  filter.min_facing = 0.0f;
  return filter;
}

MCQ_FN int mcq_cell_is_visible(mcq_cell_filter filter, int cell) {
  if (filter.facing) {
    mcq_vec3 f = mcq_load3(filter.facing, (mcq_uint)cell);
    if (mcq_dot(f, filter.normal) < filter.min_facing * mcq_dot(f, f)) return 0;
  }
  if (filter.count == 0u) return 1;
  mcq_uint bone = filter.cell_bones[cell];
  for (mcq_uint k = 0; k < filter.count; ++k)
    if (filter.visible[k] == bone) return 1;
  return 0;
}

/* Parameters [*t_enter, *t_exit] of the whole line origin + t*dir (t of
 * either sign) inside the box [lo, hi] (corners relative to the origin);
 * returns 0 when the line misses it. */
MCQ_FN int mcq_line_box_interval(mcq_vec3 lo, mcq_vec3 hi, mcq_vec3 inv_dir, float* t_enter, float* t_exit) {
  float tx1 = lo.x * inv_dir.x, tx2 = hi.x * inv_dir.x;
  float ty1 = lo.y * inv_dir.y, ty2 = hi.y * inv_dir.y;
  float tz1 = lo.z * inv_dir.z, tz2 = hi.z * inv_dir.z;
  *t_enter = MCQ_FMAX(MCQ_FMAX(MCQ_FMIN(tx1, tx2), MCQ_FMIN(ty1, ty2)), MCQ_FMIN(tz1, tz2));
  *t_exit = MCQ_FMIN(MCQ_FMIN(MCQ_FMAX(tx1, tx2), MCQ_FMAX(ty1, ty2)), MCQ_FMAX(tz1, tz2));
  return *t_enter <= *t_exit;
}

/* Entry parameter of a half-line into a box whose line interval is
 * [t_enter, t_exit], or -1 when it misses; an origin inside the box enters
 * at 0. | rather than ||: no branch, so loops over rays vectorize. */
MCQ_FN float mcq_half_line_entry(float t_enter, float t_exit) {
  return ((t_exit < 0.0f) | (t_enter > t_exit)) ? -1.0f : MCQ_FMAX(t_enter, 0.0f);
}

/* The corners of node's box relative to `origin`, as the slab tests take them. */
MCQ_FN void mcq_node_corners(const MCQ_GLOBAL float* node_bounds, int node, mcq_vec3 origin, mcq_vec3* lo,
                             mcq_vec3* hi) {
  const MCQ_GLOBAL float* b = node_bounds + 6 * node;
  *lo = mcq_make_vec3(b[0] - origin.x, b[1] - origin.y, b[2] - origin.z);
  *hi = mcq_make_vec3(b[3] - origin.x, b[4] - origin.y, b[5] - origin.z);
}

/* Entry parameter of the half-line origin + t*dir (t >= 0) into node's box,
 * or a negative value when it misses. */
MCQ_FN float mcq_ray_box_entry(const MCQ_GLOBAL float* node_bounds, int node, mcq_vec3 origin, mcq_vec3 inv_dir) {
  mcq_vec3 lo, hi;
  mcq_node_corners(node_bounds, node, origin, &lo, &hi);
  float t_enter, t_exit;
  mcq_line_box_interval(lo, hi, inv_dir, &t_enter, &t_exit);
  return mcq_half_line_entry(t_enter, t_exit);
}

/* A direction component of exactly zero would make 0 * inf = NaN in the slab
 * test; a tiny signed stand-in keeps the test exact for practical purposes. */
MCQ_FN float mcq_safe_inverse(float d) { return 1.0f / (MCQ_FABS(d) > 1e-20f ? d : MCQ_COPYSIGN(1e-20f, d)); }

/* The componentwise mcq_safe_inverse of a ray direction, as the slab tests take it. */
MCQ_FN mcq_vec3 mcq_inverse_direction(mcq_vec3 dir) {
  return mcq_make_vec3(mcq_safe_inverse(dir.x), mcq_safe_inverse(dir.y), mcq_safe_inverse(dir.z));
}

/* "No cell" while searching: above every cell index, so the tie rule below
 * needs no special case; reported as -1. */
#define MCQ_NO_CELL 0x7FFFFFFF

/* Whether entering `cell` at t beats the best hit so far: the first cell
 * entered within reach, and among cells entered at the same distance (a
 * vertex inside several padded boxes enters them all at 0) the lowest cell
 * index. The rule does not depend on the order of the traversal, so the
 * single-ray and the packet traversals below give the same cell. */
MCQ_FN int mcq_hit_is_better(float t, int cell, float best_t, int best_cell) {
  return (t >= 0.0f) & ((t < best_t) | ((t == best_t) & (cell < best_cell)));
}

/* The first visible cell whose box the half-line enters within `reach`
 * (ties as in mcq_hit_is_better), -1 when none; invisible cells are passed
 * through as if absent; the entry distance goes to *entry. The
 * reference for the packet traversal; tests compare the two. */
MCQ_FN int mcq_first_cell_hit(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children,
                              mcq_cell_filter filter, mcq_vec3 origin, mcq_vec3 dir, float reach, float* entry) {
  mcq_vec3 inv_dir = mcq_inverse_direction(dir);
  int stack_node[MCQ_STACK_SIZE];
  float stack_t[MCQ_STACK_SIZE];
  float best_t = reach;
  int best_cell = MCQ_NO_CELL;
  float t_root = mcq_ray_box_entry(node_bounds, 0, origin, inv_dir);
  int top = 0;
  if (t_root >= 0.0f && t_root <= reach) {
    stack_node[0] = 0;
    stack_t[0] = t_root;
    top = 1;
  }
  while (top > 0) {
    --top;
    int node = stack_node[top];
    float t = stack_t[top];
    if (t > best_t) continue; /* equal entries may still hold a lower cell */
    int left = node_children[2 * node];
    if (left < 0) {
      if (mcq_hit_is_better(t, -1 - left, best_t, best_cell) && mcq_cell_is_visible(filter, -1 - left)) {
        best_t = t;
        best_cell = -1 - left;
      }
      continue;
    }
    int right = node_children[2 * node + 1];
    float tl = mcq_ray_box_entry(node_bounds, left, origin, inv_dir);
    float tr = mcq_ray_box_entry(node_bounds, right, origin, inv_dir);
    /* Push the farther child first so the nearer one is popped next. */
    int near_node = left, far_node = right;
    float near_t = tl, far_t = tr;
    if (tr >= 0.0f && (tl < 0.0f || tr < tl)) {
      near_node = right;
      far_node = left;
      near_t = tr;
      far_t = tl;
    }
    if (far_t >= 0.0f && far_t <= best_t && top < MCQ_STACK_SIZE) {
      stack_node[top] = far_node;
      stack_t[top] = far_t;
      ++top;
    }
    if (near_t >= 0.0f && near_t <= best_t && top < MCQ_STACK_SIZE) {
      stack_node[top] = near_node;
      stack_t[top] = near_t;
      ++top;
    }
  }
  *entry = best_t;
  return best_cell == MCQ_NO_CELL ? -1 : best_cell;
}

/* Most cells a ray's band gathers (mcq_cells_in_band). */
#define MCQ_BAND_CELLS 16

/* How far the box interval [t_enter, t_exit] lies from t (0 when it holds t). */
MCQ_FN float mcq_interval_gap(float t_enter, float t_exit, float t) {
  return MCQ_FMAX(MCQ_FMAX(t_enter - t, t - t_exit), 0.0f);
}

/* Gap (mcq_interval_gap) between `center` and where the line origin +
 * t*dir crosses node's box; infinite when it misses the box. */
MCQ_FN float mcq_line_box_gap(const MCQ_GLOBAL float* node_bounds, int node, mcq_vec3 origin, mcq_vec3 inv_dir,
                              float center) {
  mcq_vec3 lo, hi;
  mcq_node_corners(node_bounds, node, origin, &lo, &hi);
  float t_enter, t_exit;
  if (!mcq_line_box_interval(lo, hi, inv_dir, &t_enter, &t_exit)) return MCQ_INFINITY;
  return mcq_interval_gap(t_enter, t_exit, center);
}

/* Inserts `item` with key (gap, item) into the list of `found` items sorted
 * by that key, keeping at most `capacity` (the largest drops out); returns
 * the new length. */
MCQ_FN int mcq_insert_nearest(int* items, float* gaps, int found, int capacity, int item, float gap) {
  int at = found < capacity ? found : capacity;
  while (at > 0 && (gaps[at - 1] > gap || (gaps[at - 1] == gap && items[at - 1] > item))) {
    if (at < capacity) {
      gaps[at] = gaps[at - 1];
      items[at] = items[at - 1];
    }
    --at;
  }
  if (at >= capacity) return found;
  gaps[at] = gap;
  items[at] = item;
  return found < capacity ? found + 1 : found;
}

/* Robust mode's band of a ray: the visible cells whose box the line
 * origin + t*dir crosses for some t in [center - band, center + band]
 * (behind the origin too), into cells[], returning how many. When more than
 * MCQ_BAND_CELLS qualify, those nearest to the center along the line are kept
 * (ties to the lower index), so the result does not depend on the order of
 * the traversal. The reference for the packet version below; tests compare
 * the two. */
MCQ_FN int mcq_cells_in_band(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children,
                             mcq_cell_filter filter, mcq_vec3 origin, mcq_vec3 dir, float center, float band,
                             int* cells) {
  mcq_vec3 inv_dir = mcq_inverse_direction(dir);
  float gaps[MCQ_BAND_CELLS];
  int found = 0;
  int stack_node[MCQ_STACK_SIZE];
  int top = 1;
  stack_node[0] = 0;
  while (top > 0) {
    int node = stack_node[--top];
    float gap = mcq_line_box_gap(node_bounds, node, origin, inv_dir, center);
    if (gap > band) continue;
    int left = node_children[2 * node];
    if (left < 0) {
      if (mcq_cell_is_visible(filter, -1 - left))
        found = mcq_insert_nearest(cells, gaps, found, MCQ_BAND_CELLS, -1 - left, gap);
      continue;
    }
    if (top + 2 > MCQ_STACK_SIZE) continue;
    stack_node[top++] = left;
    stack_node[top++] = node_children[2 * node + 1];
  }
  return found;
}

/* Ray `dir`'s band (as mcq_cells_in_band) among the candidate leaves that
 * mcq_first_cell_hits gathered for its packet. */
MCQ_FN int mcq_band_of_ray(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children, const int* leaves,
                           int candidates, mcq_vec3 origin, mcq_vec3 dir, float center, float band, int* cells) {
  mcq_vec3 inv_dir = mcq_inverse_direction(dir);
  float gaps[MCQ_BAND_CELLS];
  int found = 0;
  for (int k = 0; k < candidates; ++k) {
    float gap = mcq_line_box_gap(node_bounds, leaves[k], origin, inv_dir, center);
    if (gap <= band)
      found = mcq_insert_nearest(cells, gaps, found, MCQ_BAND_CELLS, -1 - node_children[2 * leaves[k]], gap);
  }
  return found;
}

/* Rays traced together by mcq_first_cell_hits; a vertex's 26 fit in one. */
#define MCQ_PACKET_SIZE 32

/* Most leaves a packet gathers for its rays' bands (mcq_first_cell_hits). */
#define MCQ_BAND_CANDIDATES 64

/* Whether the line interval [t_enter, t_exit] of a box may still hold a ray's
 * first hit (entered by t <= best) or, with band > 0, a cell of its band
 * (crossed within band of a first hit in [0, best]). */
MCQ_FN int mcq_box_wanted(float t_enter, float t_exit, float best, float band) {
  return (t_enter <= t_exit) & (t_exit >= -band) & (t_enter <= best + band);
}

/* Whether some ray of the packet wants the box [lo, hi] (corners relative
 * to the origin), by mcq_box_wanted. A straight loop, so it vectorizes. */
MCQ_FN int mcq_packet_wants_box(mcq_vec3 lo, mcq_vec3 hi, const float* inv_x, const float* inv_y, const float* inv_z,
                                const float* entries, int count, float band) {
  int wanted = 0;
  for (int r = 0; r < count; ++r) {
    float t_enter, t_exit;
    mcq_line_box_interval(lo, hi, mcq_make_vec3(inv_x[r], inv_y[r], inv_z[r]), &t_enter, &t_exit);
    wanted |= mcq_box_wanted(t_enter, t_exit, entries[r], band);
  }
  return wanted;
}

/* Compacts the packet's band candidates to those some ray's current window
 * still wants (mcq_box_wanted); returns how many remain. */
MCQ_FN int mcq_drop_unwanted_leaves(const MCQ_GLOBAL float* node_bounds, mcq_vec3 origin, const float* inv_x,
                                    const float* inv_y, const float* inv_z, const float* entries, int count, float band,
                                    int* leaves, int found) {
  int kept = 0;
  for (int k = 0; k < found; ++k) {
    mcq_vec3 lo, hi;
    mcq_node_corners(node_bounds, leaves[k], origin, &lo, &hi);
    if (mcq_packet_wants_box(lo, hi, inv_x, inv_y, inv_z, entries, count, band)) leaves[kept++] = leaves[k];
  }
  return kept;
}

/* mcq_first_cell_hit for `count` (<= MCQ_PACKET_SIZE) rays from one origin,
 * with the same result for every ray. A vertex's rays fan out from one point
 * within a narrow cone, so they visit nearly the same nodes: the packet walks
 * the tree once and tests each node against all rays in straight loops that
 * compilers vectorize (PoCL's and GCC's alike), instead of one divergent walk
 * per ray. A node is entered when any ray may still find a better hit in it.
 * dir_x/y/z hold the directions; cells (-1: no hit) and entries receive the
 * results.
 *
 * With band > 0 (robust mode's bands, mcq_cells_in_band) the same walk also
 * gathers into leaves[] (node indices; their number goes to *candidates)
 * every visible leaf that may lie in some ray's band: crossed by its line
 * within band of [0, its best hit so far]. Since the best hit only comes
 * nearer, the final bands are among them; mcq_band_of_ray picks each ray's.
 * Should more than MCQ_BAND_CANDIDATES qualify, the list first drops those
 * no ray's current window still wants, then new ones. One walk for both
 * costs far less than a second walk from the root. */
MCQ_FN void mcq_first_cell_hits(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children,
                                mcq_cell_filter filter, mcq_vec3 origin, const float* dir_x, const float* dir_y,
                                const float* dir_z, int count, float reach, float band, int* cells, float* entries,
                                int* leaves, int* candidates) {
  float inv_x[MCQ_PACKET_SIZE], inv_y[MCQ_PACKET_SIZE], inv_z[MCQ_PACKET_SIZE];
  float mean_x = 0.0f, mean_y = 0.0f, mean_z = 0.0f;
  for (int r = 0; r < count; ++r) {
    inv_x[r] = mcq_safe_inverse(dir_x[r]);
    inv_y[r] = mcq_safe_inverse(dir_y[r]);
    inv_z[r] = mcq_safe_inverse(dir_z[r]);
    mean_x += dir_x[r];
    mean_y += dir_y[r];
    mean_z += dir_z[r];
    entries[r] = reach;
    cells[r] = MCQ_NO_CELL;
  }
  band = MCQ_FMAX(band, 0.0f);
  int found = 0;
  int stack_node[MCQ_STACK_SIZE];
  int top = 1;
  stack_node[0] = 0;
  while (top > 0) {
    int node = stack_node[--top];
    mcq_vec3 lo, hi;
    mcq_node_corners(node_bounds, node, origin, &lo, &hi);
    int left = node_children[2 * node];
    /* A leaf updates the rays it serves better; an inner node is entered
     * when some ray may still find a better hit (or a band cell) in it.
     * Straight loops over the rays, so they vectorize. */
    if (left < 0) {
      int cell = -1 - left;
      if (!mcq_cell_is_visible(filter, cell)) continue;
      int wanted = 0;
      for (int r = 0; r < count; ++r) {
        float t_enter, t_exit;
        mcq_line_box_interval(lo, hi, mcq_make_vec3(inv_x[r], inv_y[r], inv_z[r]), &t_enter, &t_exit);
        wanted |= mcq_box_wanted(t_enter, t_exit, entries[r], band);
        float t = mcq_half_line_entry(t_enter, t_exit);
        int better = mcq_hit_is_better(t, cell, entries[r], cells[r]);
        entries[r] = better ? t : entries[r];
        cells[r] = better ? cell : cells[r];
      }
      if (band > 0.0f && wanted) {
        if (found == MCQ_BAND_CANDIDATES)
          found =
              mcq_drop_unwanted_leaves(node_bounds, origin, inv_x, inv_y, inv_z, entries, count, band, leaves, found);
        if (found < MCQ_BAND_CANDIDATES) leaves[found++] = node;
      }
      continue;
    }
    if (!mcq_packet_wants_box(lo, hi, inv_x, inv_y, inv_z, entries, count, band) || top + 2 > MCQ_STACK_SIZE) continue;
    /* Visit first the child the packet's mean direction reaches first. */
    int right = node_children[2 * node + 1];
    const MCQ_GLOBAL float* bl = node_bounds + 6 * left;
    const MCQ_GLOBAL float* br = node_bounds + 6 * right;
    float towards_right = (br[0] + br[3] - bl[0] - bl[3]) * mean_x + (br[1] + br[4] - bl[1] - bl[4]) * mean_y +
                          (br[2] + br[5] - bl[2] - bl[5]) * mean_z;
    stack_node[top++] = towards_right >= 0.0f ? right : left;
    stack_node[top++] = towards_right >= 0.0f ? left : right;
  }
  for (int r = 0; r < count; ++r) cells[r] = cells[r] == MCQ_NO_CELL ? -1 : cells[r];
  if (candidates) *candidates = found;
}

/* The squared distance from q to node's box shrunk by `inset` on every side. */
MCQ_FN float mcq_inset_box_distance_squared(const MCQ_GLOBAL float* node_bounds, int node, float inset, mcq_vec3 q) {
  const MCQ_GLOBAL float* b = node_bounds + 6 * node;
  float dx = MCQ_FMAX(MCQ_FMAX(b[0] + inset - q.x, q.x - (b[3] - inset)), 0.0f);
  float dy = MCQ_FMAX(MCQ_FMAX(b[1] + inset - q.y, q.y - (b[4] - inset)), 0.0f);
  float dz = MCQ_FMAX(MCQ_FMAX(b[2] + inset - q.z, q.z - (b[5] - inset)), 0.0f);
  return dx * dx + dy * dy + dz * dz;
}

/* The nearest of `cell`'s points to q so far: *best_d, *best_point and
 * *best_cell move to a nearer point (ties to the lower point index). */
MCQ_FN void mcq_nearest_in_cell(const MCQ_GLOBAL mcq_uint* cell_offsets, const MCQ_GLOBAL float* points, int cell,
                                mcq_vec3 q, float* best_d, mcq_uint* best_point, int* best_cell) {
  for (mcq_uint p = cell_offsets[cell]; p < cell_offsets[cell + 1]; ++p) {
    mcq_vec3 d = mcq_sub(mcq_load3(points, p), q);
    float d2 = mcq_dot(d, d);
    if (d2 < *best_d || (d2 == *best_d && p < *best_point)) {
      *best_d = d2;
      *best_point = p;
      *best_cell = cell;
    }
  }
}

/* The cloud point nearest to q (ties to the lower point index, i.e. the
 * lower cell), 0xFFFFFFFF in an empty tree; its cell goes to *cell and the
 * squared distance to *distance2.
 * `inset`: how far inside every box its points lie at least (the rays'
 * padding, 0 for tight boxes); the search prunes on the boxes shrunk by it,
 * which on the knot visits a third of the leaves the padded boxes do.
 * `start_cell` (-1: none) is a guess, such as the answer for where the
 * vertex stood one step before: its points bound the search from the start,
 * so far fewer boxes pass. The answer is the same with any guess: no box
 * that holds a point at least as near as the best so far is pruned. */
MCQ_FN mcq_uint mcq_nearest_point(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children,
                                  const MCQ_GLOBAL mcq_uint* cell_offsets, const MCQ_GLOBAL float* points, float inset,
                                  mcq_vec3 q, int start_cell, float* distance2, int* cell) {
  int stack_node[MCQ_STACK_SIZE];
  float stack_d[MCQ_STACK_SIZE];
  int top = 1;
  stack_node[0] = 0;
  stack_d[0] = mcq_inset_box_distance_squared(node_bounds, 0, inset, q);
  float best_d = MCQ_INFINITY;
  mcq_uint best_point = 0xFFFFFFFFu;
  int best_cell = -1;
  if (start_cell >= 0) mcq_nearest_in_cell(cell_offsets, points, start_cell, q, &best_d, &best_point, &best_cell);
  while (top > 0) {
    --top;
    int node = stack_node[top];
    if (stack_d[top] > best_d) continue;
    int left = node_children[2 * node];
    if (left < 0) {
      mcq_nearest_in_cell(cell_offsets, points, -1 - left, q, &best_d, &best_point, &best_cell);
      continue;
    }
    int right = node_children[2 * node + 1];
    float dl = mcq_inset_box_distance_squared(node_bounds, left, inset, q);
    float dr = mcq_inset_box_distance_squared(node_bounds, right, inset, q);
    int near_node = dl <= dr ? left : right, far_node = dl <= dr ? right : left;
    float near_d = MCQ_FMIN(dl, dr), far_d = MCQ_FMAX(dl, dr);
    if (far_d <= best_d && top < MCQ_STACK_SIZE) {
      stack_node[top] = far_node;
      stack_d[top] = far_d;
      ++top;
    }
    if (near_d <= best_d && top < MCQ_STACK_SIZE) {
      stack_node[top] = near_node;
      stack_d[top] = near_d;
      ++top;
    }
  }
  *distance2 = best_d;
  *cell = best_cell;
  return best_point;
}

/* The cell holding the cloud point nearest to q (mcq_nearest_point), -1 in
 * an empty tree. */
MCQ_FN int mcq_nearest_point_cell(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children,
                                  const MCQ_GLOBAL mcq_uint* cell_offsets, const MCQ_GLOBAL float* points, float inset,
                                  mcq_vec3 q, int start_cell, float* distance2) {
  int cell;
  mcq_nearest_point(node_bounds, node_children, cell_offsets, points, inset, q, start_cell, distance2, &cell);
  return cell;
}

#endif
