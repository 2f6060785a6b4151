"""Many scans at once: one fit per scan as a Dask task.

    python -m mcquad.batch SCANS... -o OUT [--scheduler ADDRESS] [--workers N] [fit options]

Each task reads its own scan and its skeleton (NAME.skeleton.obj or
NAME.skel.obj beside the scan), fits it and writes OUT/NAME.obj and
OUT/NAME.report.json; a scan that fails is reported in the summary and does
not stop the others. Without ``--scheduler`` the tasks run on a
``dask.distributed.LocalCluster``; with one, on that cluster (every worker
needs mcquad installed and the scans' paths readable).

Exit status: 0 when every scan was fitted, 1 when any failed, 2 for bad arguments.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import os
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Sequence

from . import _core

SKELETON_SUFFIXES = (".skeleton.obj", ".skel.obj")


@dataclass
class ScanResult:
    """One row of the summary."""

    scan: str
    ok: bool
    vertices: int = 0
    faces: int = 0
    verdict: str = ""  #: "pass", "fail" (a check failed; see the report) or "" when the fit failed
    failed_checks: str = ""
    seconds: float = 0.0
    mesh: str = ""
    report: str = ""
    error: str = ""


def scan_name(scan: Path) -> str:
    """The scan's file name without its extension: OUT/NAME.obj is written for it."""
    return scan.name[: -len(scan.suffix)] if scan.suffix else scan.name


def find_skeleton(scan: Path) -> Optional[Path]:
    """NAME.skeleton.obj or NAME.skel.obj beside the scan, if there is one."""
    for suffix in SKELETON_SUFFIXES:
        candidate = scan.with_name(scan_name(scan) + suffix)
        if candidate.is_file():
            return candidate
    return None


def fit_one(scan: str, out_dir: str, options: Dict[str, Any]) -> ScanResult:
    """A Dask task: fits one scan and writes its mesh and report. Never raises for mcquad's own errors."""
    import mcquad  # imported on the worker

    start = time.perf_counter()
    path = Path(scan)
    name = scan_name(path)
    row = ScanResult(scan=str(path), ok=False)
    try:
        skeleton = find_skeleton(path)
        if skeleton is None:
            raise mcquad.InputError(
                f"{path}: no skeleton beside the scan ({name}.skeleton.obj or {name}.skel.obj); "
                "automatic skeleton extraction is not available in this version")
        result = mcquad.fit(str(path), str(skeleton), **options)
        mesh_path = Path(out_dir) / f"{name}.obj"
        report_path = Path(out_dir) / f"{name}.report.json"
        result.write(mesh_path)
        _write_atomically(report_path, json.dumps(result.report, indent=2) + "\n")
        verdict = result.verdict
        row.ok = True
        row.vertices, row.faces = int(result.vertices.shape[0]), int(result.faces.shape[0])
        row.verdict = "pass" if verdict.passed else "fail"
        row.failed_checks = " ".join(check["name"] for check in verdict.failures)
        row.mesh, row.report = str(mesh_path), str(report_path)
    except mcquad.Error as error:
        row.error = f"{type(error).__name__}: {error}"
    row.seconds = time.perf_counter() - start
    return row


def _write_atomically(path: Path, text: str) -> None:
    temporary = path.with_name(path.name + ".tmp")
    temporary.write_text(text)
    os.replace(temporary, path)


def fit_many(
    paths: Iterable[os.PathLike | str],
    out_dir: os.PathLike | str,
    client: Any = None,
    *,
    workers: Optional[int] = None,
    **options: Any,
) -> List[ScanResult]:
    """Fits every scan in ``paths`` as one Dask task each; returns one :class:`ScanResult` per scan, in order.

    Args:
        paths: point cloud files; each one's skeleton is found beside it (see :func:`find_skeleton`).
        out_dir: where NAME.obj and NAME.report.json go (created if missing).
        client: a ``dask.distributed.Client``; None starts a ``LocalCluster`` for the batch and closes it after.
        workers: worker processes of that local cluster (None: Dask's default).
        **options: fit options, as for :func:`mcquad.fit` (e.g. ``seed=2, iterations=10``).
    """
    from dask.distributed import Client, LocalCluster

    unknown = set(options) - set(_core.fit_defaults())
    if unknown:
        raise _core.InputError("unknown fit option(s): " + ", ".join(sorted(unknown)))
    scans = [str(p) for p in paths]
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise _core.OutputError(f"{out}: cannot create directory: {error.strerror}") from error
    own_cluster = client is None
    if own_cluster:
        # One thread a worker: each fit runs its own OpenMP threads.
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        futures = client.map(fit_one, scans, out_dir=str(out), options=options, pure=False)
        rows = []
        for scan, future in zip(scans, futures):
            try:
                rows.append(future.result())
            except Exception as error:  # a worker died or the task raised something not mcquad's
                rows.append(ScanResult(scan=scan, ok=False, error=f"{type(error).__name__}: {error}"))
        return rows
    finally:
        if own_cluster:
            client.close()
            cluster.close()


def summary_table(rows: Sequence[ScanResult]) -> str:
    """The rows as an aligned text table: scan, vertices, verdict, time, and what failed."""
    header = ("scan", "vertices", "verdict", "seconds", "notes")
    lines = [header] + [
        (Path(r.scan).name, str(r.vertices) if r.ok else "-", r.verdict if r.ok else "FAILED", f"{r.seconds:.2f}",
         r.failed_checks if r.ok else r.error)
        for r in rows
    ]
    widths = [max(len(line[i]) for line in lines) for i in range(len(header) - 1)]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(line, widths)) + "  " + line[-1] for line in lines)


def write_summary(rows: Sequence[ScanResult], out_dir: Path) -> Path:
    """OUT/summary.csv, one row per scan with every field."""
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=list(asdict(rows[0]).keys()) if rows else ["scan"])
    writer.writeheader()
    for row in rows:
        writer.writerow(asdict(row))
    path = out_dir / "summary.csv"
    _write_atomically(path, buffer.getvalue())
    return path


def _option_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m mcquad.batch",
        description="Fit many scans on a Dask cluster, one task per scan (skeleton: NAME.skeleton.obj or "
        "NAME.skel.obj beside each scan).")
    parser.add_argument("scans", nargs="+", help="point cloud files")
    parser.add_argument("-o", "--output", required=True, help="output directory")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    parser.add_argument("--workers", type=int, help="worker processes of the local cluster")
    fit_options = parser.add_argument_group("fit options (as mcquad fit; defaults as there)")
    for name, default in sorted(_core.fit_defaults().items()):
        flag = "--" + name.replace("_", "-")
        if isinstance(default, bool):
            fit_options.add_argument(flag, dest=name, choices=("on", "off"), help=f"default: {'on' if default else 'off'}")
        else:
            fit_options.add_argument(flag, dest=name, type=type(default), help=f"default: {default!r}")
    return parser


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = vars(_option_parser().parse_args(argv))
    scans, out_dir, scheduler, workers = args.pop("scans"), Path(args.pop("output")), args.pop("scheduler"), args.pop("workers")
    options = {k: (v == "on" if isinstance(_core.fit_defaults()[k], bool) else v) for k, v in args.items() if v is not None}
    client = None
    if scheduler:
        from dask.distributed import Client

        client = Client(scheduler)
    try:
        rows = fit_many(scans, out_dir, client, workers=workers, **options)
    except _core.Error as error:
        print(f"mcquad.batch: error: {error}", file=sys.stderr)
        return 2
    finally:
        if client is not None:
            client.close()
    print(summary_table(rows))
    print(f"summary: {write_summary(rows, out_dir)}")
    failed = sum(not r.ok for r in rows)
    if failed:
        print(f"mcquad.batch: {failed} of {len(rows)} scans failed", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
