"""mcquad: quad meshes from point clouds and their skeletons by a Monte Carlo method.

The functions wrap the C++ library the ``mcquad`` command is built on (not
the command line): numpy arrays in, numpy arrays and the same JSON report out,
the GIL released while the work runs, so fits in threads run side by side.

>>> import mcquad
>>> shape = mcquad.generate("t-shape")
>>> result = mcquad.fit(shape.points, (shape.nodes, shape.edges), seed=1)
>>> result.vertices.shape[1], result.faces.shape[1]
(3, 4)
>>> result.verdict.passed
True

Errors are raised as :class:`InputError` (bad files, arrays or options; also
a ``ValueError``), :class:`UnsupportedError`, :class:`DeviceError` and
:class:`OutputError` (also an ``OSError``), all derived from :class:`Error`,
with the messages the command prints.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import DeviceError, Error, InputError, OutputError, UnsupportedError

__version__: str = _core.__version__

__all__ = [
    "Error", "InputError", "UnsupportedError", "DeviceError", "OutputError",
    "Skeleton", "Shape", "Verdict", "FitResult",
    "ExtractedSkeleton", "extract_skeleton",
    "read_points", "read_skeleton", "read_mesh", "write_mesh",
    "fit", "metrics", "surfaces", "generate", "shape_names",
]

PathLike = Union[str, "os.PathLike[str]"]
ArrayLike = Any  #: anything numpy.asarray turns into the shape asked for
#: progress(label, done, total): a stage's name (e.g. "cells", "evolving") and how far it is.
ProgressCallback = Callable[[str, int, int], None]


class Skeleton(NamedTuple):
    """A skeleton graph: ``nodes`` (M, 3) float64 and ``edges`` (E, 2) int64 of 0-based node indices."""

    nodes: np.ndarray
    edges: np.ndarray


class ExtractedSkeleton(NamedTuple):
    """A skeleton extracted from a cloud (see :func:`extract_skeleton`)."""

    skeleton: Skeleton
    radii: np.ndarray  #: (M,) float64, per node: its distance to the cloud
    report: Dict[str, Any]  #: as ``mcquad skeleton --report`` writes it


class Shape(NamedTuple):
    """A generated test shape (see :func:`generate`)."""

    name: str
    points: np.ndarray
    nodes: np.ndarray
    edges: np.ndarray
    open_ends: int
    independent_cycles: int

    @property
    def skeleton(self) -> Skeleton:
        return Skeleton(self.nodes, self.edges)


@dataclass(frozen=True)
class Verdict:
    """Pass or fail per check of a fitted mesh, each with its figure and threshold."""

    passed: bool
    checks: List[Dict[str, Any]]

    @property
    def failures(self) -> List[Dict[str, Any]]:
        return [check for check in self.checks if not check["passed"]]

    def __bool__(self) -> bool:
        return self.passed


@dataclass
class FitResult:
    """The fitted quad mesh and its report (the JSON report of ``mcquad fit --report``)."""

    vertices: np.ndarray  #: (V, 3) float64
    faces: np.ndarray  #: (F, 4) int64, 0-based vertex indices
    report: Dict[str, Any] = field(repr=False)

    @property
    def verdict(self) -> Verdict:
        v = self.report["verdict"]
        return Verdict(bool(v["passed"]), list(v["checks"]))

    def write(self, path: PathLike) -> None:
        """Writes the mesh by extension (.obj, .off, .ply, .om), atomically, as ``mcquad fit -o`` does."""
        write_mesh(path, self.vertices, self.faces)


def _path(path: PathLike) -> str:
    return os.fspath(path)


def read_points(path: PathLike, normals: bool = False):
    """Reads a point cloud (.ply, .xyz, .txt, .csv, .obj, .off) as an (N, 3) float32 array.

    With ``normals=True``, returns ``(points, normals)``: the file's normals as
    an (N, 3) float32 array, or None when it has none.
    """
    points, point_normals = _core.read_points(_path(path))
    return (points, point_normals) if normals else points


def extract_skeleton(points: Union[PathLike, ArrayLike], *, voxels: int = 0) -> ExtractedSkeleton:
    """A curve skeleton of the cloud alone, as ``mcquad skeleton`` (docs/SKELETON.md).

    Args:
        points: (N, 3) array or the path of a point cloud file; normals are not needed.
        voxels: voxels the cloud is thinned to (0 = a quarter of the points, at most 40,000).

    Raises:
        InputError: fewer than 200 points, or a malformed cloud.
        UnsupportedError: a cloud with no curve skeleton (a sheet, a blob with no limbs).
    """
    array, _, name = _points(points, None)
    nodes, edges, radii, report = _core.extract_skeleton(np.ascontiguousarray(array, dtype=np.float32), name, int(voxels))
    return ExtractedSkeleton(Skeleton(nodes, edges), radii, report)


def read_skeleton(path: PathLike) -> Skeleton:
    """Reads a skeleton (.obj with v/l lines, or CGAL polylines .cgal/.polylines/.txt)."""
    nodes, edges = _core.read_skeleton(_path(path))
    return Skeleton(nodes, edges)


def read_mesh(path: PathLike) -> Tuple[np.ndarray, np.ndarray]:
    """Reads a polygon mesh: vertices (V, 3) float64 and faces (F, k) int64, -1 padding smaller faces."""
    return _core.read_mesh(_path(path))


def write_mesh(path: PathLike, vertices: ArrayLike, faces: ArrayLike) -> None:
    """Writes a mesh by extension (.obj, .off, .ply, .om), atomically."""
    _core.write_mesh(_path(path), np.asarray(vertices), np.asarray(faces))


SkeletonLike = Union[PathLike, Skeleton, Tuple[ArrayLike, ArrayLike], Dict[str, ArrayLike]]


def _points(points: Union[PathLike, ArrayLike], normals: Optional[ArrayLike]) -> Tuple[np.ndarray, Any, str]:
    """The cloud, its normals (given, else the file's, else None) and its name."""
    if isinstance(points, (str, os.PathLike)):
        cloud, file_normals = read_points(points, normals=True)
        return cloud, file_normals if normals is None else np.asarray(normals), _path(points)
    return np.asarray(points), None if normals is None else np.asarray(normals), "points array"


def _skeleton(skeleton: Optional[SkeletonLike]) -> Tuple[np.ndarray, np.ndarray, str]:
    if skeleton is None:  # no nodes and no name: the fit extracts one from the cloud
        return np.zeros((0, 3)), np.zeros((0, 2), dtype=np.int64), ""
    if isinstance(skeleton, (str, os.PathLike)):
        s = read_skeleton(skeleton)
        return s.nodes, s.edges, _path(skeleton)
    if isinstance(skeleton, dict):
        return np.asarray(skeleton["nodes"]), np.asarray(skeleton["edges"]), "skeleton arrays"
    nodes, edges = skeleton
    return np.asarray(nodes), np.asarray(edges), "skeleton arrays"


def fit(
    points: Union[PathLike, ArrayLike],
    skeleton: Optional[SkeletonLike] = None,
    *,
    normals: Optional[ArrayLike] = None,
    ends: str = "auto",
    start_fraction: float = 0.7,
    block_fraction: float = 0.9,
    resolution: float = 0.0,
    target_vertices: int = 0,
    min_junction_angle: float = 75.0,
    junction_inflation: float = 0.85,
    limb_ports: bool = True,
    write_skeleton: str = "",
    backend: str = "auto",
    device: str = "",
    mode: str = "robust",
    relaxation: float = 0.0,
    projection: str = "mean",
    fill_holes: bool = True,
    nearest_plane: bool = False,
    crossing_guard: bool = True,
    held_back_relaxation: float = 0.6,
    own_cells: bool = True,
    local_epsilon: bool = True,
    coarse_to_fine: bool = True,
    refine_uncovered: bool = True,
    hit_band: float = 0.4,
    facing_cells: bool = True,
    min_facing: float = 0.7,
    curvature_correction: bool = True,
    turned_face_rounds: int = 20,
    push_deep: bool = True,
    reach_uncovered: bool = True,
    iterations: int = 20,
    tolerance: float = 0.0,
    seed: int = 1,
    cones: int = 4,
    generators: int = 6,
    alpha_max: float = 10.0,
    samples: int = 10,
    epsilon: float = 0.0,
    leaf_size: int = 0,
    snapshots: str = "",
    surfaces: str = "",
    control_nets: str = "",
    units: str = "mm",
    progress: Optional[ProgressCallback] = None,
) -> FitResult:
    """The whole pipeline, as ``mcquad fit``: initial mesh, Monte Carlo evolution, metrics, verdict.

    Args:
        points: (N, 3) array (float64 is converted to float32, as the readers
            store points) or the path of a point cloud file.
        skeleton: a skeleton file's path, a :class:`Skeleton`, a tuple
            ``(nodes, edges)`` or a dict with those keys (0-based edges);
            None: extracted from the cloud first (:func:`extract_skeleton`).
        normals: the scan's outward normals, (N, 3), for the verdict's inward
            check and robust mode's facing cells (default: the file's, when
            ``points`` is a path that has them; without normals the skeleton
            tells inward and every cell faces every way).
        ends: ``auto`` (decided from the cloud), ``open`` or ``capped``.
        start_fraction: initial mesh radius as a fraction of the local cloud radius (0.05 to 0.95).
        block_fraction: robust mode: junction blocks' radius as a fraction of the local cloud radius
            (0.05 to 0.95; at least the start fraction).
        resolution: target edge length of the refined mesh (0: 16 vertices around a tube).
        target_vertices: refine until at least this many vertices (0: off).
        min_junction_angle: degrees (0 to 120); junctions whose bones fork more
            acutely move to where the cloud's tubes part (0: never).
        junction_inflation: robust mode: the mesh round each junction moves this fraction of the way to the
            cloud along rays from its node before the evolution (0 to 0.95; 0: off).
        limb_ports: robust mode: a limb whose junction face is over 2.5 times as wide as the limb at its root
            (a thin branch off a trunk) starts from a face of its own size inset in that face and lifted out of
            it to the trunk's wall (docs/HARD_CASES.md, "Thin limbs start at their trunk's wall").
        write_skeleton: write the skeleton the mesh is built on here (OBJ).
        backend: ``auto`` (OpenCL if a device exists), ``serial`` or ``opencl``.
        device: OpenCL device index or name (default: ``$MCQUAD_DEVICE``, else the first GPU, else the first device).
        mode: ``robust`` (the improvements over the paper) or ``paper`` (the paper's step exactly).
        relaxation: robust mode: tangential relaxation weight before each step (0 to 1; 0: off).
        projection: robust mode: a cell's distance along a ray from its samples, ``mean`` or ``min`` (the paper's).
        fill_holes: robust mode: vertices that find no cell take their neighbours' offset.
        nearest_plane: robust mode: vertices that find no cell while the cloud is within epsilon move along the
            scan's normal at their nearest point to its level (off by default; docs/DESIGN.md, "Blind vertices").
        crossing_guard: robust mode: shorten moves that make faces cross or fold after each step.
        held_back_relaxation: robust mode: relaxation weight for the vertices the guard held back (0 to 1).
        own_cells: robust mode: a vertex sees only the cells of the bones near its own.
        local_epsilon: robust mode: epsilon and the ray reach scale with the local radius.
        coarse_to_fine: robust mode, finer than the default resolution: evolve the default resolution's mesh
            first, then refine it and evolve again.
        refine_uncovered: robust mode, at the default resolution: where the fit leaves the cloud uncovered (the
            verdict's bound), refine the fitted mesh once and evolve again.
        hit_band: robust mode: a ray averages every cell within this fraction of epsilon of its first hit (0 to 1).
        facing_cells: robust mode, on a scan with normals: rays pass through cells whose scan normals face away
            from the vertex.
        min_facing: robust mode: the least cosine of the angle between a cell's scan normal and the vertex
            normal for a ray to hit the cell (-1 to 0.95).
        curvature_correction: robust mode: correct each sample's projection by the mesh's curvature at the
            vertex, so vertices settle on a curved surface and not inside it.
        turned_face_rounds: robust mode, on a scan with normals: at most this many rounds of smoothing the
            faces turned against the scan's normals after the evolution (0: off).
        push_deep: robust mode, on a scan with normals, with the smoothing of turned faces: push vertices left
            deep below the scan out first; the pushed fit is kept where it turns no more area against the scan.
        reach_uncovered: robust mode: after the evolution, cloud points it left more than a sixth of epsilon
            from the mesh pull it; the fit so reached is kept where its cloud -> mesh p95 is lower and, on a
            scan with normals, the area it turns against them stays within the verdict's bound or grows not
            at all.
        iterations: maximal number of iterations.
        tolerance: stop when the error level improves by less than this fraction (0: never).
        seed: random seed; the same seed gives the same mesh, bit for bit, as ``mcquad fit --seed``.
        cones: c, number of cones (1 to 64).
        generators: r, rays per cone (1 to 64).
        alpha_max: maximal cone half angle, degrees (0 to 89).
        samples: m, random samples per hit cell (1 to 1024).
        epsilon: feasibility bound and ray reach (0: 0.6 x the median local radius).
        leaf_size: maximal points per cell (0: 6, growing in proportion above 2 million points).
        snapshots: write the mesh after every iteration into this directory.
        surfaces: also write the final mesh as B-spline surfaces (.step, .stp, .iges, .igs).
        control_nets: also write the surfaces' control nets (.obj, .off, .ply, .om).
        units: the length unit the CAD file declares (mm, cm, m, um, in, ft); coordinates are written as they are.
        progress: called as ``progress(label, done, total)`` at every stage's start
            (0 of 1) and end (1 of 1), and as long stages advance.

    Returns:
        :class:`FitResult` with ``vertices``, ``faces``, ``report``, ``verdict`` and ``write(path)``.

    Raises:
        InputError, UnsupportedError, DeviceError, OutputError.
    """
    options = {name: value for name, value in locals().items() if name in _FIT_OPTIONS}
    return _fit(points, normals, skeleton, options, progress)


_FIT_OPTIONS = frozenset(_core.fit_defaults())


def _fit(points, normals, skeleton, options: Dict[str, Any], progress: Optional[ProgressCallback]) -> FitResult:
    cloud, cloud_normals, points_name = _points(points, normals)
    nodes, edges, skeleton_name = _skeleton(skeleton)
    vertices, faces, report = _core.fit(cloud, cloud_normals, nodes, edges, options, points_name, skeleton_name,
                                        progress)
    return FitResult(vertices, faces, report)


def metrics(
    vertices: ArrayLike,
    faces: ArrayLike,
    points: Union[PathLike, ArrayLike],
    skeleton: Optional[SkeletonLike] = None,
    *,
    normals: Optional[ArrayLike] = None,
    leaf_size: int = 0,
) -> Dict[str, Any]:
    """Distances both ways, error level, topology, defects and verdict of a mesh, as ``mcquad metrics``.

    Inward faces are told by the cloud's normals (``normals``, else the file's), else by the skeleton. With a
    skeleton, the distance checks and open ends are judged too. Returns the same dict as ``mcquad metrics --json``.
    """
    cloud, cloud_normals, _ = _points(points, normals)
    nodes = edges = None
    if skeleton is not None:
        nodes, edges, _ = _skeleton(skeleton)
    return _core.metrics(np.asarray(vertices), np.asarray(faces), cloud, cloud_normals, nodes, edges, leaf_size)


def surfaces(
    vertices: ArrayLike,
    faces: ArrayLike,
    output: PathLike,
    *,
    points: Optional[Union[PathLike, ArrayLike]] = None,
    control_nets: str = "",
    tangent_tolerance: float = 1.0,
    units: str = "mm",
) -> Dict[str, Any]:
    """B-spline surfaces of a quad mesh written as STEP or IGES (``output``), as ``mcquad surfaces``.

    With ``points``, the surfaces' distance to the cloud is measured too. ``units`` is the length unit
    the file declares (mm, cm, m, um, in, ft); the coordinates are written as they are. Returns the surface report.
    """
    cloud = None if points is None else _points(points, None)[0]
    return _core.surfaces(np.asarray(vertices), np.asarray(faces), _path(output), cloud, control_nets,
                          float(tangent_tolerance), units)


def generate(
    name: str,
    directory: Optional[PathLike] = None,
    *,
    points: int = 0,
    noise: float = 0.0,
    seed: int = 1,
    angle: float = 0.0,
    branch_radius: float = 0.2,
    arms: int = 4,
    outliers: float = 0.0,
    density_ratio: float = 1.0,
    holes: int = 0,
) -> Shape:
    """A synthetic cloud with its skeleton, as ``mcquad generate`` (names: :func:`shape_names`).

    With ``directory``, also writes NAME.ply, NAME.skeleton.obj and NAME.surface.json there.
    """
    options = {k: v for k, v in locals().items() if k not in ("name", "directory")}
    d = _core.generate(name, None if directory is None else _path(directory), options)
    return Shape(d["name"], d["points"], d["nodes"], d["edges"], d["open_ends"], d["independent_cycles"])


def shape_names() -> List[Tuple[str, str]]:
    """The generator's shapes, each with a line describing it."""
    return list(_core.shape_names())
