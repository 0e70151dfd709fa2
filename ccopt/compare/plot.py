"""A plot of the variants over the contour (matplotlib, a figure outside pyplot).

Left: the whole part, programmed contour in grey and every variant's feed
path. Right: a close-up of the first lead-in (where the variants differ most).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ccopt.atomic import write_with_atomic
from ccopt.compare.parts import FEED_ROLES
from ccopt.compare.leads import find_leads
from ccopt.errors import ProgramError
from ccopt.geometry.curve import bernstein
from ccopt.toolpath import programmed_path


def _xy(path):
    pts = []
    for s in path.segments:
        if s.role in FEED_ROLES and s.length > 0:
            g = s.geom
            n = max(2, min(400, int(np.ceil(g.length / 0.05)) + 1))
            cps = getattr(g, "control_points", None)
            if cps is not None:
                P = np.asarray(cps, float)
                pts.append(bernstein(np.linspace(0, 1, 4 * n), len(P) - 1) @ P)
            else:
                pts.append(np.asarray(g.point(np.linspace(0.0, g.length, n))).reshape(-1, 2))
            pts.append(np.full((1, 2), np.nan))
    return np.vstack(pts) if pts else np.zeros((0, 2))


#: The plot formats ``ccopt compare -o`` writes, by suffix (lower case).
PLOT_SUFFIXES = (".png", ".svg", ".pdf")


def check_plot_name(out) -> None:
    """A :class:`~ccopt.errors.ProgramError` naming ``out`` unless its suffix is
    one of :data:`PLOT_SUFFIXES` (checked before the comparison runs)."""
    if Path(out).suffix.lower() not in PLOT_SUFFIXES:
        raise ProgramError(f"compare -o writes a plot: use one of {', '.join(PLOT_SUFFIXES)} "
                           f"(the table as JSON: --json)", str(out))


def plot_comparison(comparison, out, title: str | None = None) -> str:
    """Write the plot to ``out`` (PNG/SVG/PDF by suffix, :data:`PLOT_SUFFIXES`;
    atomically: :func:`ccopt.atomic.write_with_atomic`); returns the file name."""
    check_plot_name(out)
    # deferred: matplotlib is heavy and optional (only plots need it). A
    # Figure of its own, not pyplot: writing the file neither chooses nor
    # changes the backend of a notebook or program that calls this (its
    # figures still show inline), and nothing is left open.
    from matplotlib.figure import Figure

    prog = comparison.program
    contour = programmed_path(prog)
    fig = Figure(figsize=(13, 6))
    axes = fig.subplots(1, 2)
    cxy = _xy_all(contour)
    ref = comparison.reference
    focus = None
    if ref is not None:
        leads = find_leads(ref)
        if leads:
            focus = np.asarray(ref.segments[leads[0].host].start, float)
    for ax, zoom in zip(axes, (False, True)):
        ax.plot(cxy[:, 0], cxy[:, 1], color="0.6", lw=2.5, label="programmed contour")
        for row in comparison:
            if row.toolpath is None:
                continue
            xy = _xy(row.toolpath)
            dur = row.figures.get("duration")
            lab = row.name + (f" ({dur:.3f} s)" if dur is not None else "")
            ax.plot(xy[:, 0], xy[:, 1], lw=1.0, label=lab)
        ax.set_aspect("equal")
        ax.grid(True, lw=0.3)
        if zoom and focus is not None:
            r = max(comparison.reference.radius, 1.0) * 2.5
            ax.set_xlim(focus[0] - r, focus[0] + r)
            ax.set_ylim(focus[1] - r, focus[1] + r)
            ax.set_title("first lead-in, close up")
    axes[0].set_title(title or f"{prog.file}: variants")
    axes[0].legend(fontsize=7, loc="best")
    fig.tight_layout()
    fmt = Path(out).suffix.lower()[1:]
    write_with_atomic(out, lambda p: fig.savefig(p, format=fmt, dpi=120))
    return str(out)


def _xy_all(path):
    pts = []
    for s in path.segments:
        if s.length > 0 and s.role.value != "rapid":
            g = s.geom
            n = max(2, min(400, int(np.ceil(g.length / 0.05)) + 1))
            pts.append(np.asarray(g.point(np.linspace(0.0, g.length, n))).reshape(-1, 2))
            pts.append(np.full((1, 2), np.nan))
    return np.vstack(pts) if pts else np.zeros((0, 2))
