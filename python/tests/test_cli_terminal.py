"""Progress on a terminal: the command names each stage while it runs (and keeps the ones over a
second with their time); on a pipe it prints none of it."""
import os
import pty
import subprocess


def run_with_terminal_stderr(command):
    leader, follower = pty.openpty()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=follower)
    os.close(follower)
    chunks = []
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the follower closed: the process is done
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(leader)
    assert process.wait(timeout=300) == 0
    return b"".join(chunks).decode(errors="replace")


def test_stages_show_on_a_terminal_and_not_on_a_pipe(cli, t_shape):
    command = [cli, "fit", str(t_shape / "t-shape.ply"), str(t_shape / "t-shape.skeleton.obj"), "-o",
               str(t_shape / "terminal.obj"), "--backend", "serial", "--iterations", "40"]
    terminal = run_with_terminal_stderr(command)
    for stage in ("read_points ...", "initial_mesh ...", "cells ...", "evolution ...", "metrics ..."):
        assert stage in terminal, terminal
    assert "evolving: 100%" in terminal
    piped = subprocess.run(command, capture_output=True, text=True, check=True)
    assert "..." not in piped.stderr and "evolving" not in piped.stderr, piped.stderr
