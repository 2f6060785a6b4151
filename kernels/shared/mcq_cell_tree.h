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

/* Entry parameter of the half-line origin + t*dir (t >= 0) into node's box,
 * or a negative value when it misses. An origin inside the box enters at 0. */
MCQ_FN float mcq_ray_box_entry(const MCQ_GLOBAL float* node_bounds, int node, mcq_vec3 origin,
                               mcq_vec3 inv_dir) {
  const MCQ_GLOBAL float* b = node_bounds + 6 * node;
  float tx1 = (b[0] - origin.x) * inv_dir.x, tx2 = (b[3] - origin.x) * inv_dir.x;
  float ty1 = (b[1] - origin.y) * inv_dir.y, ty2 = (b[4] - origin.y) * inv_dir.y;
  float tz1 = (b[2] - origin.z) * inv_dir.z, tz2 = (b[5] - origin.z) * inv_dir.z;
  float t_enter = MCQ_FMAX(MCQ_FMAX(MCQ_FMIN(tx1, tx2), MCQ_FMIN(ty1, ty2)), MCQ_FMIN(tz1, tz2));
  float t_exit = MCQ_FMIN(MCQ_FMIN(MCQ_FMAX(tx1, tx2), MCQ_FMAX(ty1, ty2)), MCQ_FMAX(tz1, tz2));
  if (t_exit < 0.0f || t_enter > t_exit) return -1.0f;
  return MCQ_FMAX(t_enter, 0.0f);
}

/* A direction component of exactly zero would make 0 * inf = NaN in the slab
 * test; a tiny signed stand-in keeps the test exact for practical purposes. */
MCQ_FN float mcq_safe_inverse(float d) {
  return 1.0f / (MCQ_FABS(d) > 1e-20f ? d : MCQ_COPYSIGN(1e-20f, d));
}

/* The first cell whose box the half-line enters within `reach`, -1 when
 * none. Among cells entered at the same distance (a vertex inside several
 * padded boxes enters them all at 0) the first one the traversal reaches
 * wins: children are visited nearer first, the left one on equal entry, so
 * the choice is deterministic and whole subtrees entered no sooner than the
 * best hit are skipped. */
MCQ_FN int mcq_first_cell_hit(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children,
                              mcq_vec3 origin, mcq_vec3 dir, float reach, float* entry) {
  mcq_vec3 inv_dir = mcq_make_vec3(mcq_safe_inverse(dir.x), mcq_safe_inverse(dir.y), mcq_safe_inverse(dir.z));
  int stack_node[MCQ_STACK_SIZE];
  float stack_t[MCQ_STACK_SIZE];
  int top = 0;
  float best_t = reach;
  int best_cell = -1;
  float t_root = mcq_ray_box_entry(node_bounds, 0, origin, inv_dir);
  if (t_root < 0.0f || t_root > reach) return -1;
  stack_node[0] = 0;
  stack_t[0] = t_root;
  top = 1;
  while (top > 0) {
    --top;
    int node = stack_node[top];
    float t = stack_t[top];
    if (best_cell >= 0 ? t >= best_t : t > best_t) continue;
    int left = node_children[2 * node];
    if (left < 0) {
      best_t = t;
      best_cell = -1 - left;
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
  return best_cell;
}

MCQ_FN float mcq_box_distance_squared(const MCQ_GLOBAL float* node_bounds, int node, mcq_vec3 q) {
  const MCQ_GLOBAL float* b = node_bounds + 6 * node;
  float dx = MCQ_FMAX(MCQ_FMAX(b[0] - q.x, q.x - b[3]), 0.0f);
  float dy = MCQ_FMAX(MCQ_FMAX(b[1] - q.y, q.y - b[4]), 0.0f);
  float dz = MCQ_FMAX(MCQ_FMAX(b[2] - q.z, q.z - b[5]), 0.0f);
  return dx * dx + dy * dy + dz * dz;
}

/* The cell holding the cloud point nearest to q (ties to the lower point
 * index, i.e. the lower cell); the squared distance goes to *distance2. */
MCQ_FN int mcq_nearest_point_cell(const MCQ_GLOBAL float* node_bounds, const MCQ_GLOBAL int* node_children,
                                  const MCQ_GLOBAL mcq_uint* cell_offsets, const MCQ_GLOBAL float* points,
                                  mcq_vec3 q, float* distance2) {
  int stack_node[MCQ_STACK_SIZE];
  float stack_d[MCQ_STACK_SIZE];
  int top = 1;
  stack_node[0] = 0;
  stack_d[0] = mcq_box_distance_squared(node_bounds, 0, q);
  float best_d = MCQ_INFINITY;
  mcq_uint best_point = 0xFFFFFFFFu;
  int best_cell = -1;
  while (top > 0) {
    --top;
    int node = stack_node[top];
    if (stack_d[top] > best_d) continue;
    int left = node_children[2 * node];
    if (left < 0) {
      int cell = -1 - left;
      for (mcq_uint p = cell_offsets[cell]; p < cell_offsets[cell + 1]; ++p) {
        mcq_vec3 d = mcq_sub(mcq_load3(points, p), q);
        float d2 = mcq_dot(d, d);
        if (d2 < best_d || (d2 == best_d && p < best_point)) {
          best_d = d2;
          best_point = p;
          best_cell = cell;
        }
      }
      continue;
    }
    int right = node_children[2 * node + 1];
    float dl = mcq_box_distance_squared(node_bounds, left, q);
    float dr = mcq_box_distance_squared(node_bounds, right, q);
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
  return best_cell;
}

#endif
