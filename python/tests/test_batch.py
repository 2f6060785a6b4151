"""Many scans on Dask: three generated scans on a LocalCluster, one of them broken."""
import csv
import json
import shutil
import subprocess
import sys

import pytest

import mcquad
from mcquad import batch


@pytest.fixture(scope="module")
def scans(tmp_path_factory):
    """t.ply (skeleton t.skeleton.obj), fork.ply (fork.skel.obj) and broken.ply (not a PLY file)."""
    directory = tmp_path_factory.mktemp("scans")
    for shape, name, skeleton_suffix in (("t-shape", "t", ".skeleton.obj"), ("y-fork", "fork", ".skel.obj")):
        mcquad.generate(shape, directory, points=20000, seed=2)
        shutil.move(directory / f"{shape}.ply", directory / f"{name}.ply")
        shutil.move(directory / f"{shape}.skeleton.obj", directory / f"{name}{skeleton_suffix}")
    (directory / "broken.ply").write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n")
    shutil.copy(directory / "t.skeleton.obj", directory / "broken.skeleton.obj")
    return [directory / "t.ply", directory / "broken.ply", directory / "fork.ply"]


def test_fit_many_on_a_local_cluster_reports_the_broken_scan(scans, tmp_path):
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        rows = batch.fit_many(scans, tmp_path / "out", client, iterations=8, backend="serial")
    assert [row.scan for row in rows] == [str(s) for s in scans]
    t, broken, fork = rows
    assert t.ok and fork.ok and not broken.ok
    assert "InputError" in broken.error and "broken.ply" in broken.error
    for row, name in ((t, "t"), (fork, "fork")):
        vertices, faces = mcquad.read_mesh(tmp_path / "out" / f"{name}.obj")
        assert row.vertices == len(vertices) > 0 and row.faces == len(faces)
        report = json.loads((tmp_path / "out" / f"{name}.report.json").read_text())
        assert report["parameters"]["iterations"] == 8
        assert row.verdict == ("pass" if report["verdict"]["passed"] else "fail")
    assert not (tmp_path / "out" / "broken.obj").exists()


def test_batch_gives_the_same_mesh_as_a_single_fit(scans, tmp_path):
    rows = batch.fit_many(scans[:1], tmp_path / "out", workers=1, iterations=8, backend="serial")
    assert rows[0].ok
    single = mcquad.fit(scans[0], scans[0].with_name("t.skeleton.obj"), iterations=8, backend="serial")
    single.write(tmp_path / "single.obj")
    assert (tmp_path / "out" / "t.obj").read_bytes() == (tmp_path / "single.obj").read_bytes()


def test_the_batch_command_prints_a_summary_and_fails_for_the_broken_scan(scans, tmp_path):
    run = subprocess.run([sys.executable, "-m", "mcquad.batch", *map(str, scans), "-o", str(tmp_path / "out"),
                          "--workers", "2", "--iterations", "8", "--backend", "serial", "--crossing-guard", "on"],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 1, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0].split()[:4] == ["scan", "vertices", "verdict", "seconds"]
    assert any(line.startswith("broken.ply") and "FAILED" in line for line in lines)
    assert any(line.startswith("t.ply") and ("pass" in line or "fail" in line) for line in lines)
    assert "1 of 3 scans failed" in run.stderr
    with open(tmp_path / "out" / "summary.csv") as table:
        assert [row["ok"] for row in csv.DictReader(table)] == ["True", "False", "True"]


def test_a_scan_without_a_skeleton_is_reported_not_fatal(tmp_path):
    mcquad.generate("t-shape", tmp_path, points=5000)
    (tmp_path / "t-shape.skeleton.obj").unlink()
    rows = batch.fit_many([tmp_path / "t-shape.ply"], tmp_path / "out", workers=1)
    assert not rows[0].ok and "no skeleton beside the scan" in rows[0].error


def test_unknown_options_are_refused_before_any_work(tmp_path):
    with pytest.raises(mcquad.InputError, match="colour"):
        batch.fit_many([], tmp_path, colour="red")
    run = subprocess.run([sys.executable, "-m", "mcquad.batch", "x.ply", "-o", str(tmp_path), "--colour", "red"],
                         capture_output=True, text=True)
    assert run.returncode == 2 and "--colour" in run.stderr
