"""The package's numpy face: round trips, the same mesh as the command, errors, progress, the GIL."""
import inspect
import os
import json
import re
import subprocess
import threading

import numpy as np
import pytest

import mcquad
from mcquad import _core


def test_read_points_returns_the_generated_cloud(t_shape):
    shape = mcquad.generate("t-shape", points=20000, seed=4)
    points = mcquad.read_points(t_shape / "t-shape.ply")
    assert points.dtype == np.float32 and points.shape == (20000, 3)
    np.testing.assert_array_equal(points, shape.points)


def test_read_skeleton_gives_nodes_and_zero_based_edges(t_shape):
    skeleton = mcquad.read_skeleton(t_shape / "t-shape.skeleton.obj")
    shape = mcquad.generate("t-shape", points=20000, seed=4)
    assert skeleton.nodes.shape[1] == 3 and skeleton.edges.shape[1] == 2
    assert skeleton.edges.min() == 0 and skeleton.edges.max() == len(skeleton.nodes) - 1
    np.testing.assert_allclose(skeleton.nodes, shape.nodes, rtol=1e-9)
    np.testing.assert_array_equal(skeleton.edges, shape.edges)


def test_mesh_round_trip_keeps_vertices_and_face_order(tmp_path):
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], float)
    faces = np.array([[0, 1, 2, 3], [1, 4, 5, 2]])
    mcquad.write_mesh(tmp_path / "m.obj", vertices, faces)
    read_vertices, read_faces = mcquad.read_mesh(tmp_path / "m.obj")
    np.testing.assert_array_equal(read_vertices, vertices)
    np.testing.assert_array_equal(read_faces, faces)


def test_fit_from_arrays_gives_the_cli_mesh_byte_for_byte(t_shape, tmp_path, cli):
    cli_mesh, cli_report = tmp_path / "cli.obj", tmp_path / "cli.json"
    subprocess.run([cli, "fit", str(t_shape / "t-shape.ply"), str(t_shape / "t-shape.skeleton.obj"), "-o", str(cli_mesh),
                    "--seed", "7", "--backend", "serial", "--report", str(cli_report)], check=True, capture_output=True)
    points, normals = mcquad.read_points(t_shape / "t-shape.ply", normals=True)
    skeleton = mcquad.read_skeleton(t_shape / "t-shape.skeleton.obj")
    result = mcquad.fit(points.astype(np.float64), (skeleton.nodes, skeleton.edges), normals=normals, seed=7,
                        backend="serial")
    result.write(tmp_path / "python.obj")
    assert (tmp_path / "python.obj").read_bytes() == cli_mesh.read_bytes()
    report = json.loads(cli_report.read_text())
    assert result.report["metrics"]["inward_measured_against"] == "scan normals"
    assert result.report["metrics"] == report["metrics"]
    assert result.report["verdict"] == report["verdict"]
    # Without normals the skeleton tells inward and no cell faces any way: the
    # mesh is the one the normals give with the facing cells off.
    by_skeleton = mcquad.fit(points, (skeleton.nodes, skeleton.edges), seed=7, backend="serial")
    assert by_skeleton.report["metrics"]["inward_measured_against"] == "skeleton"
    assert by_skeleton.report["cells"]["facing_fraction"] == 0
    assert result.report["cells"]["facing_fraction"] > 0.99
    unfaced = mcquad.fit(points, (skeleton.nodes, skeleton.edges), normals=normals, seed=7, backend="serial",
                         facing_cells=False)
    np.testing.assert_array_equal(by_skeleton.vertices, unfaced.vertices)
    assert result.report["parameters"] == report["parameters"]


def test_fit_from_paths_equals_fit_from_arrays(t_shape):
    by_path = mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", iterations=3, backend="serial")
    shape = mcquad.generate("t-shape", points=20000, seed=4)
    points, normals = mcquad.read_points(t_shape / "t-shape.ply", normals=True)
    np.testing.assert_array_equal(points, shape.points)
    by_array = mcquad.fit(shape.points, shape.skeleton, normals=normals, iterations=3, backend="serial")
    np.testing.assert_array_equal(by_path.vertices, by_array.vertices)
    np.testing.assert_array_equal(by_path.faces, by_array.faces)
    assert by_path.report["inputs"]["points"].endswith("t-shape.ply")
    assert by_array.report["inputs"]["points"] == "points array"


def test_result_is_a_quad_mesh_with_a_verdict(t_shape):
    result = mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", backend="serial")
    assert result.vertices.dtype == np.float64 and result.vertices.shape[1] == 3
    assert result.faces.shape[1] == 4 and result.faces.min() == 0 and result.faces.max() == len(result.vertices) - 1
    names = {check["name"] for check in result.verdict.checks}
    assert {"intersecting_face_pairs", "folded_edges", "uncovered_cloud", "mesh_off_cloud", "inward_faces",
            "open_ends", "error_level"} <= names
    assert result.verdict.passed, result.verdict.failures


def test_verdict_fails_a_mesh_that_did_not_reach_the_cloud(t_shape):
    result = mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", iterations=0, backend="serial")
    assert not result.verdict.passed
    assert "uncovered_cloud" in {check["name"] for check in result.verdict.failures}


def test_signature_defaults_are_the_librarys(cli):
    defaults = _core.fit_defaults()
    parameters = inspect.signature(mcquad.fit).parameters
    options = {name: p.default for name, p in parameters.items() if p.kind is inspect.Parameter.KEYWORD_ONLY}
    options.pop("progress")
    options.pop("normals")  # an input beside the points, not an option
    assert options == defaults
    help_text = subprocess.run([cli, "fit", "--help"], check=True, capture_output=True, text=True).stdout
    for name in ("iterations", "cones", "samples", "hit_band", "start_fraction", "alpha_max"):
        flag = "--" + name.replace("_", "-")
        line = next(line for line in help_text.splitlines() if line.strip().startswith(flag))
        assert float(re.search(r"=(\S+)", line).group(1)) == pytest.approx(float(defaults[name])), line
    for name in inspect.signature(mcquad.fit).parameters:
        if name not in ("points", "skeleton"):
            assert f"{name}:" in mcquad.fit.__doc__, f"{name} is not documented"


@pytest.mark.parametrize("points, message", [
    (np.zeros((0, 3)), "the point cloud is empty"),
    (np.array([[0, 0, 0], [1, np.nan, 0]]), "point 1 has a NaN or infinite coordinate"),
    (np.zeros((5, 2)), "must have shape (N, 3), not (5, 2)"),
])
def test_bad_points_raise_input_error_naming_the_problem(points, message):
    nodes, edges = np.array([[0, 0, 0], [1, 0, 0]], float), np.array([[0, 1]])
    with pytest.raises(mcquad.InputError, match=message.replace("(", r"\(").replace(")", r"\)")) as raised:
        mcquad.fit(points, (nodes, edges))
    assert isinstance(raised.value, ValueError) and isinstance(raised.value, mcquad.Error)
    assert str(raised.value).startswith("points array: ")


def test_bad_skeleton_and_options_raise_input_error(t_shape):
    points = mcquad.read_points(t_shape / "t-shape.ply")
    with pytest.raises(mcquad.InputError, match="edge 0 names node 5, but there are 2 nodes"):
        mcquad.fit(points, (np.zeros((2, 3)), np.array([[0, 5]])))
    skeleton = t_shape / "t-shape.skeleton.obj"
    with pytest.raises(mcquad.InputError, match="mode: 'fast' is not one of robust, paper"):
        mcquad.fit(points, skeleton, mode="fast")
    with pytest.raises(mcquad.InputError, match=r"cones: 0\.0+ is outside \[1"):
        mcquad.fit(points, skeleton, cones=0)
    with pytest.raises(mcquad.InputError, match="unknown option 'colour'"):
        _core.fit(points, None, np.zeros((2, 3)), np.array([[0, 1]]), {"colour": 1}, "p", "s")
    with pytest.raises(mcquad.InputError, match="3 normals for 20000 points"):
        mcquad.fit(points, skeleton, normals=np.zeros((3, 3)))


def test_files_that_are_not_there_or_broken_name_the_file(tmp_path):
    with pytest.raises(mcquad.InputError, match="missing.ply"):
        mcquad.read_points(tmp_path / "missing.ply")
    (tmp_path / "broken.xyz").write_text("1 2 3\n4 five 6\n")
    with pytest.raises(mcquad.InputError, match=r"broken.xyz.*'five' is not a number"):
        mcquad.read_points(tmp_path / "broken.xyz")


def test_unwritable_output_raises_output_error(tmp_path):
    vertices, faces = np.eye(4, 3), np.array([[0, 1, 2, 3]])
    with pytest.raises(mcquad.OutputError) as raised:
        mcquad.write_mesh(tmp_path / "no-such-directory" / "m.obj", vertices, faces)
    assert isinstance(raised.value, OSError)
    with pytest.raises(mcquad.OutputError, match=r"m.xyz: unknown mesh extension '.xyz' \(expected .obj"):
        mcquad.write_mesh(tmp_path / "m.xyz", vertices, faces)
    mcquad.write_mesh(tmp_path / "m.stl", vertices, faces)  # triangulated
    assert (tmp_path / "m.stl").stat().st_size == 84 + 2 * 50


def test_no_skeleton_extracts_one_and_bad_clouds_are_refused_clearly(t_shape):
    extracted = mcquad.extract_skeleton(t_shape / "t-shape.ply")
    assert (extracted.report["junctions"], extracted.report["ends"]) == (1, 3)
    assert extracted.radii.shape == (len(extracted.skeleton.nodes),)
    assert np.all(np.abs(extracted.radii - 1.0) < 0.25)
    fitted = mcquad.fit(t_shape / "t-shape.ply", iterations=2, backend="serial")
    assert fitted.report["skeleton_extraction"]["junctions"] == 1
    with pytest.raises(mcquad.InputError, match="100 points are too few"):
        mcquad.fit(np.random.default_rng(1).random((100, 3)))


def test_progress_reports_every_stage_and_the_iterations(t_shape):
    events = []
    mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", iterations=4, backend="serial",
               progress=lambda label, done, total: events.append((label, done, total)))
    labels = [label for label, _, _ in events]
    for stage in ("sort_points", "radius", "initial_mesh", "cells", "evolution", "metrics"):
        assert (stage, 0, 1) in events and (stage, 1, 1) in events, stage
    assert ("evolving", 4, 4) in events
    assert labels.index("initial_mesh") < labels.index("evolving") < labels.index("metrics")


def test_an_exception_in_the_progress_callback_stops_the_fit(t_shape):
    def stop(label, done, total):
        if label == "cells":
            raise KeyboardInterrupt("stop")
    with pytest.raises(KeyboardInterrupt):
        mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", backend="serial", progress=stop)


def test_the_gil_is_released_while_fitting(t_shape):
    points = mcquad.read_points(t_shape / "t-shape.ply")
    skeleton = mcquad.read_skeleton(t_shape / "t-shape.skeleton.obj")
    worker = threading.Thread(target=lambda: mcquad.fit(points, skeleton, backend="serial", iterations=10))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1  # runs only while the fit does not hold the GIL
    worker.join()
    assert ticks > 1000


def test_metrics_equal_the_cli_metrics(t_shape, tmp_path, cli):
    result = mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", iterations=5, backend="serial")
    result.write(tmp_path / "m.obj")
    subprocess.run([cli, "metrics", str(tmp_path / "m.obj"), str(t_shape / "t-shape.ply"), "--skeleton",
                    str(t_shape / "t-shape.skeleton.obj"), "--json", str(tmp_path / "m.json")],
                   check=True, capture_output=True)
    expected = json.loads((tmp_path / "m.json").read_text())
    vertices, faces = mcquad.read_mesh(tmp_path / "m.obj")  # as the command reads it, rounded as OBJ writes it
    measured = mcquad.metrics(vertices, faces, t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj")
    assert measured == expected
    # The fit measures its own, spatially sorted copy of the cloud: the
    # sampled spacing and the sums' order differ, the counts do not.
    unrounded = mcquad.metrics(result.vertices, result.faces, t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj")
    fitted = result.report["metrics"]
    for key in ("mesh", "intersecting_face_pairs", "folded_edges", "inward_faces", "quad_shape"):
        assert unrounded[key] == fitted[key], key
    assert unrounded["cloud_to_mesh"]["mean"] == pytest.approx(fitted["cloud_to_mesh"]["mean"], rel=1e-9)
    assert unrounded["cloud_spacing"] == pytest.approx(fitted["cloud_spacing"], rel=0.01)


def test_surfaces_write_step_and_measure_against_the_cloud(t_shape, tmp_path):
    result = mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", iterations=5, backend="serial")
    report = mcquad.surfaces(result.vertices, result.faces, tmp_path / "t.step", points=t_shape / "t-shape.ply", units="m")
    assert (tmp_path / "t.step").read_text().startswith("ISO-10303-21")
    assert report["cad_file"]["units"] == "m" and "SI_UNIT($,.METRE.)" in (tmp_path / "t.step").read_text()
    assert report["cad_file"]["faces_read_back"] > 0
    assert report["checks"]["distance_to_cloud"]["p95"] > 0


def test_generate_knows_its_shapes_and_refuses_others():
    names = [name for name, _ in mcquad.shape_names()]
    assert "t-shape" in names and "torus-knot" in names
    with pytest.raises(mcquad.InputError, match="no-such-shape"):
        mcquad.generate("no-such-shape")


def test_the_opencl_backend_runs_from_python(t_shape):
    """On PoCL in CI (MCQUAD_REQUIRE_OPENCL=1 there); skipped where no OpenCL device exists."""
    try:
        result = mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", backend="opencl", iterations=5)
    except mcquad.DeviceError as error:
        if os.environ.get("MCQUAD_REQUIRE_OPENCL") == "1":
            raise
        pytest.skip(f"no OpenCL device: {error}")
    assert result.report["backend"]["name"] == "opencl"
    serial = mcquad.fit(t_shape / "t-shape.ply", t_shape / "t-shape.skeleton.obj", backend="serial", iterations=5)
    # The same per-vertex code on both: float rounding apart, the same mesh.
    np.testing.assert_allclose(result.vertices, serial.vertices, atol=1e-4)


def test_turned_faces_are_smoothed_and_reported(tmp_path):
    """A planar junction of five arms turns faces in its creases; robust mode smooths them after the
    evolution (turned_face_rounds), and the report says how many there were and are."""
    mcquad.generate("planar-star", tmp_path, points=20000, seed=1, arms=5)
    cloud, skeleton = tmp_path / "planar-star.ply", tmp_path / "planar-star.skeleton.obj"
    smoothed = mcquad.fit(cloud, skeleton, backend="serial")
    turned = smoothed.report["evolution"]["turned_faces"]
    assert turned["faces_before"] > 0
    assert turned["faces_after"] < turned["faces_before"]
    assert smoothed.report["parameters"]["turned_face_rounds"] == 20
    left_alone = mcquad.fit(cloud, skeleton, backend="serial", turned_face_rounds=0)
    assert "turned_faces" not in left_alone.report["evolution"]
    assert left_alone.report["metrics"]["inward_area_fraction"] > smoothed.report["metrics"]["inward_area_fraction"]


def test_deep_vertices_are_pushed_out_across_the_scans_holes(tmp_path):
    """A T with three holes in its scan: the hole filling leaves the middle of each hole inside;
    robust mode pushes those vertices out (push_deep), keeps that fit where it turns no more area
    against the scan, and the report says so; push_deep=False leaves the fit as the evolution made it."""
    mcquad.generate("t-shape", tmp_path, points=20000, seed=1, holes=3)
    cloud, skeleton = tmp_path / "t-shape.ply", tmp_path / "t-shape.skeleton.obj"
    pushed = mcquad.fit(cloud, skeleton, backend="serial")
    assert pushed.report["parameters"]["push_deep"] is True
    turned = pushed.report["evolution"]["turned_faces"]
    assert turned["deep_push_rounds"] > 0
    assert turned["deep_push_kept"] is True
    plain = mcquad.fit(cloud, skeleton, backend="serial", push_deep=False)
    assert plain.report["parameters"]["push_deep"] is False
    assert plain.report["evolution"]["turned_faces"]["deep_push_rounds"] == 0
    assert not np.array_equal(pushed.vertices, plain.vertices)
    inward = pushed.report["metrics"]["inward_area_fraction"], plain.report["metrics"]["inward_area_fraction"]
    assert inward[0] <= inward[1]


def test_the_reach_for_the_uncovered_cloud_is_reported_and_can_be_turned_off(tmp_path):
    """Robust mode pulls the mesh toward the cloud the evolution left uncovered (reach_uncovered):
    the report says what was pulled and whether that fit was kept; reach_uncovered=False leaves it out."""
    mcquad.generate("blob-limbs", tmp_path, points=20000, seed=1)
    cloud, skeleton = tmp_path / "blob-limbs.ply", tmp_path / "blob-limbs.skeleton.obj"
    reached = mcquad.fit(cloud, skeleton, backend="serial")
    assert reached.report["parameters"]["reach_uncovered"] is True
    reach = reached.report["evolution"]["uncovered_reach"]
    assert reach["uncovered_points_before"] > 0
    assert reach["rounds"] > 0
    assert isinstance(reach["kept"], bool)
    plain = mcquad.fit(cloud, skeleton, backend="serial", reach_uncovered=False)
    assert plain.report["parameters"]["reach_uncovered"] is False
    assert "uncovered_reach" not in plain.report["evolution"]
