"""Shared plumbing of the sweep examples: command line, output folder, timing, figures.

Every example takes ``--quick`` (the short version CI runs), ``--out DIR`` (default
``target/python-examples/<name>``) and ``--write-docs`` (the full version, its figures into
``docs/``). Physics comes from the ``raceway`` package only; this module holds no formula.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
DOCS = ROOT / "docs"


def arguments(name: str, doc: str) -> argparse.Namespace:
    """Parse the common options; ``args.out`` is the output folder (created)."""
    p = argparse.ArgumentParser(description=doc.strip().splitlines()[0])
    p.add_argument("--quick", action="store_true", help="short version (CI)")
    p.add_argument("--out", type=Path, default=None, help="output folder")
    p.add_argument(
        "--write-docs", action="store_true", help="full version; figures into docs/"
    )
    args = p.parse_args()
    if args.quick and args.write_docs:
        p.error("--quick and --write-docs exclude each other")
    if args.out is None:
        args.out = ROOT / "target" / "python-examples" / name
    args.out.mkdir(parents=True, exist_ok=True)
    return args


def figure_path(args: argparse.Namespace, stem: str) -> Path:
    """Where a figure goes: docs/python-examples-<stem>.png with --write-docs, else the
    output folder."""
    if args.write_docs:
        return DOCS / f"python-examples-{stem}.png"
    return args.out / f"{stem}.png"


def load_average() -> str:
    """The 1, 5 and 15-minute load averages, to print beside any timing."""
    return " ".join(f"{v:.2f}" for v in os.getloadavg())


def pyplot():
    """matplotlib's pyplot on the file-only Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig, path: Path) -> None:
    """Write a figure and free it."""
    fig.savefig(path, dpi=110)
    fig.clf()
    pyplot().close(fig)
    print(f"wrote {path}")


class Clock:
    """Thread CPU time of this thread (the Rust calls release the GIL but run on it) and
    the load average beside it: the machine is shared, so the wall clock is no measure."""

    def __init__(self) -> None:
        self.cpu0 = time.thread_time()

    def report(self, what: str) -> str:
        cpu = time.thread_time() - self.cpu0
        return f"{what}: thread CPU time {cpu:.2f} s (load average {load_average()})"


def check(ok: bool, message: str) -> None:
    """A physics check of the example: print it, and fail the run when it does not hold."""
    print(("check ok: " if ok else "CHECK FAILED: ") + message)
    if not ok:
        raise SystemExit(1)
