#pragma once

#include "cells/cell_tree.h"
#include "core/point_cloud.h"

namespace mcquad {

//! Fills cells.cell_facing from the scan's own outward normals: for each
//! cell, the direction of the mean of the unit normals of the `oriented`
//! points it holds (the oriented sample is a sample of the cloud's own
//! points), or zero where they disagree (a mean shorter than
//! kLeastAgreement: a cell holding both sides of a thin part), where the
//! sample has none of its points, or where the scan has no normals
//! (`oriented` empty). Robust mode's rays pass
//! through the cells that face away from the vertex casting them
//! (mcq_cell_filter): the far wall of a thin part or the facing wall across
//! a crease is a surface, but not the one the vertex belongs on
//! (docs/DESIGN.md). Cells with a zero facing stay visible to every vertex.
void orient_cells(CellTree& cells, const OrientedSample& oriented);

//! The share of the cells that have a facing (0 without normals).
double facing_fraction(const CellTree& cells);

}  // namespace mcquad
