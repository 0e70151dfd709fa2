"""Plots of a case (matplotlib, Agg), returned as PNG bytes for embedding.

Drawing samples the exact segments finely; that is for the eye only — every
figure ccopt reports comes from the exact geometry. Titles pass through
:func:`ccopt.export.text.plot_text` (one line, no mathtext).
"""
from __future__ import annotations

import io

import numpy as np

from ccopt.export.text import plot_text
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import Role, ToolPath

ROLE_STYLE = {
    Role.RAPID: dict(color="#999999", lw=0.8, ls=":"),
    Role.LEAD_IN: dict(color="#2a9d8f", lw=1.6),
    Role.COMPENSATED: dict(color="#1d3557", lw=1.6),
    Role.CORNER: dict(color="#e76f51", lw=1.8),
    Role.LEAD_OUT: dict(color="#8338ec", lw=1.6),
    Role.UNCOMPENSATED: dict(color="#457b9d", lw=1.2),
}


def _figure(width=7.0, height=5.0):
    """A figure of its own, outside pyplot: drawing a report neither chooses
    nor changes the backend of a notebook or program that imports ccopt (its
    figures still show inline), and nothing is left open."""
    # deferred: matplotlib is heavy and optional (only reports with plots need it)
    from matplotlib.figure import Figure
    fig = Figure(figsize=(width, height), dpi=110)
    return fig, fig.subplots()


def _plan_figure(xmin, xmax, ymin, ymax, extra_width=0.0):
    """A figure shaped like the plan view it shows (equal axes): 7 inches wide
    (plus ``extra_width``, e.g. for a colour bar), as tall as the extent's
    aspect asks, between 2.4 and 6 inches, so a long narrow part is not a
    thin strip in a square of white."""
    # a part with no extent one way (a single line) still gets a figure
    w, h = max(xmax - xmin, POINT_EPS), max(ymax - ymin, POINT_EPS)
    return _figure(7.0 + extra_width, float(np.clip(7.0 * h / w + 0.8, 2.4, 6.0)))


def _extent(paths) -> tuple[float, float, float, float]:
    boxes = [seg.geom.bbox() for p in paths if p is not None for seg in p.segments
             if seg.length > 0]
    if not boxes:
        return 0.0, 1.0, 0.0, 1.0
    b = np.asarray(boxes, float)
    return float(b[:, 0].min()), float(b[:, 2].max()), float(b[:, 1].min()), float(b[:, 3].max())


def _png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", bbox_inches="tight")
    return buf.getvalue()


def _legend_outside(ax) -> None:
    """The legend beside the axes, top right outside: it never hides the path or a
    curve, and placing it costs nothing (``loc="best"`` searches every plotted
    point for the emptiest corner, a third of a plan view's drawing time)."""
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)


def _samples(geom, step: float) -> np.ndarray:
    n = max(2, int(np.ceil(geom.length / step)) + 1)
    return geom.point(np.linspace(0.0, geom.length, n))


def _polyline(segments, step: float) -> np.ndarray | None:
    """The samples of ``segments`` (those of zero length left out) as one
    polyline, a NaN row where one segment does not start where the last ended:
    one matplotlib line for a whole role, not one per block (a 300-block
    program otherwise spends most of its plot drawing line objects)."""
    parts = []
    end = None
    for seg in segments:
        if seg.length <= 0:
            continue
        p = _samples(seg.geom, step)
        if end is not None and np.hypot(*(p[0, :2] - end[:2])) > POINT_EPS:
            parts.append(np.full((1, p.shape[1]), np.nan))
        parts.append(p)
        end = p[-1]
    return np.concatenate(parts) if parts else None


def _step(path: ToolPath) -> float:
    total = max(path.length, POINT_EPS)
    return total / 2000


def path_plot(path: ToolPath, contour: ToolPath | None, radius: float,
              violations: list | None = None, title: str = "") -> bytes:
    """Programmed contour (black), tool-centre path by role, tool circles
    along it, violations marked with red crosses at their witness points."""
    x0, x1, y0, y1 = _extent([path, contour])
    fig, ax = _plan_figure(x0, x1, y0 - radius, y1 + radius)
    step = _step(path)
    if contour is not None:
        p = _polyline([s for s in contour.segments if s.role is not Role.RAPID], step)
        if p is not None:
            ax.plot(p[:, 0], p[:, 1], color="black", lw=1.0)
    # one line per role, in the order the roles first appear (the legend's order)
    for role in dict.fromkeys(seg.role for seg in path.segments if seg.length > 0):
        p = _polyline([s for s in path.segments if s.role is role], step)
        ax.plot(p[:, 0], p[:, 1], label=role.value, **ROLE_STYLE[role])
    if radius > 0:
        from matplotlib.patches import Circle  # deferred: matplotlib is heavy and optional
        cut = [s for s in path.segments if s.role is not Role.RAPID and s.length > 0]
        total = sum(s.length for s in cut)
        spacing = max(total / 60, radius)
        acc = 0.0
        for seg in cut:
            for s in np.arange((-acc) % spacing, seg.length, spacing):
                c = seg.geom.point(s)
                ax.add_patch(Circle(c, radius, fill=False, lw=0.4, color="#888888", alpha=0.6))
            acc = (acc + seg.length) % spacing
    for v in violations or []:
        w = v.get("witness_tool") or v.get("witness")
        if w:
            ax.plot([w[0]], [w[1]], "x", color="red", ms=10, mew=2)
    ax.set_aspect("equal")
    ax.set_title(plot_text(title))
    _legend_outside(ax)
    ax.grid(alpha=0.3)
    return _png(fig)


def feed_plot(profile, title: str = "") -> bytes:
    """Tool path coloured by the planned tangential speed."""
    from matplotlib.collections import LineCollection  # deferred: heavy and optional
    samples = profile.sample(max(profile.duration / 4000, 1e-4)) if profile.duration > 0 else None
    if samples is not None and len(samples) > 1:
        xy = samples.position[:, :2]
        fig, ax = _plan_figure(xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(),
                                    xy[:, 1].max(), extra_width=1.2)
        segs = np.stack([xy[:-1], xy[1:]], axis=1)
        # the colours span the feed moves' speeds; a faster rapid takes the top colour
        top = speed_axis_top({"": profile})
        lc = LineCollection(segs, array=samples.feed[:-1], cmap="viridis", lw=2.0)
        if top is not None:
            lc.set_clim(0.0, top)
        ax.add_collection(lc)
        fig.colorbar(lc, ax=ax, label="feed (units/s)",
                     extend="max" if top is not None and samples.feed.max() > top else "neither")
        ax.set_xlim(xy[:, 0].min() - 1, xy[:, 0].max() + 1)
        ax.set_ylim(xy[:, 1].min() - 1, xy[:, 1].max() + 1)
    else:
        fig, ax = _figure()
    ax.set_aspect("equal")
    ax.set_title(plot_text(title))
    ax.grid(alpha=0.3)
    return _png(fig)


#: Head room above the fastest feed move on the speed axes (a rapid may go
#: above, clipped): 8 % of it.
FEED_HEADROOM = 1.08


def rapid_samples(profile, samples) -> np.ndarray:
    """Which ``samples`` of ``profile`` lie on rapid moves (boolean array)."""
    rapid = np.array([seg.role is Role.RAPID for seg in profile.path.toolpath.segments]
                     + [False])       # index -1 (a dwell) is no rapid
    return rapid[np.where(samples.segment >= 0, samples.segment, -1)]


def speed_axis_top(profiles: dict) -> float | None:
    """The top of the speed axis: :data:`FEED_HEADROOM` times the fastest
    sample on a feed move over every profile, so rapids (often several times
    the feed) do not flatten the feed moves; ``None`` when there are none."""
    top = 0.0
    for prof in profiles.values():
        if prof is None or prof.duration <= 0:
            continue
        smp = prof.sample(max(prof.duration / 4000, 1e-4))
        moving = smp.feed[~rapid_samples(prof, smp)]
        if moving.size:
            top = max(top, float(moving.max()))
    return FEED_HEADROOM * top if top > 0 else None


def speed_time_plot(profiles: dict, title: str = "") -> bytes:
    """Tangential speed against time, one curve per planner: solid on feed
    moves, dotted on rapids; the axis tops at the feed moves' speed
    (:func:`speed_axis_top`), a faster rapid is clipped and the label says so."""
    fig, ax = _figure(7.0, 3.2)
    clipped = False
    top = speed_axis_top(profiles)
    for name, prof in profiles.items():
        if prof is None or prof.duration <= 0:
            continue
        smp = prof.sample(max(prof.duration / 4000, 1e-4))
        rapid = rapid_samples(prof, smp)
        line, = ax.plot(smp.t, np.where(rapid, np.nan, smp.feed),
                        label=f"{name} ({prof.duration:.3f} s)", lw=1.2)
        if rapid.any():
            ax.plot(smp.t, np.where(rapid, smp.feed, np.nan), color=line.get_color(), lw=0.8,
                    ls=":")
            clipped |= top is not None and bool((smp.feed[rapid] > top).any())
    if top is not None:
        ax.set_ylim(0.0, top)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("feed (units/s)" + ("; rapids dotted, clipped" if clipped else ""))
    ax.set_title(plot_text(title))
    _legend_outside(ax)
    ax.grid(alpha=0.3)
    return _png(fig)
