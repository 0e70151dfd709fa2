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


#: White space kept round the drawn extent of a saved figure, inches (matplotlib's
#: ``savefig.pad_inches`` default, which ``bbox_inches="tight"`` adds).
PNG_PAD = 0.1


def _png(fig) -> bytes:
    """``fig`` as PNG bytes cropped to what is drawn, plus :data:`PNG_PAD`.

    The same image as ``savefig(bbox_inches="tight")`` (the tests compare the
    bytes), drawn once instead of twice: "tight" first draws the whole figure
    without output to place it, but the extent needs only the layout
    (``get_tightbbox`` lays out ticks, titles and equal aspects itself)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # deferred: heavy and optional
    renderer = FigureCanvasAgg(fig).get_renderer()
    box = fig.get_tightbbox(renderer).padded(PNG_PAD)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", bbox_inches=box)
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


def _draw_path(ax, path: ToolPath, contour: ToolPath | None, radius: float,
               violations: list | None, step: float, legend: bool = True,
               box: tuple | None = None) -> None:
    """The contour, the tool path by role, tool circles and violations, on ``ax``;
    with ``box`` (x0, x1, y0, y1), a zoomed view, only what reaches into it."""
    def shown(segments):
        return [s for s in segments if box is None or _meets(s.geom.bbox(), box, radius)]

    if contour is not None:
        p = _polyline(shown([s for s in contour.segments if s.role is not Role.RAPID]), step)
        if p is not None:
            ax.plot(p[:, 0], p[:, 1], color="black", lw=1.0)
    # one line per role, in the order the roles first appear (the legend's order)
    for role in dict.fromkeys(seg.role for seg in path.segments if seg.length > 0):
        p = _polyline(shown([s for s in path.segments if s.role is role]), step)
        if p is not None:
            ax.plot(p[:, 0], p[:, 1], label=role.value, **ROLE_STYLE[role])
    if radius > 0:
        _draw_tool_circles(ax, path, radius, box)
    for v in violations or []:
        w = v.get("witness_tool") or v.get("witness")
        if w:
            ax.plot([w[0]], [w[1]], "x", color="red", ms=10, mew=2)
    ax.set_aspect("equal")
    if legend:
        _legend_outside(ax)
    ax.grid(alpha=0.3)


def _meets(bbox, box, margin: float) -> bool:
    """Whether a segment's ``bbox`` (x0, y0, x1, y1) comes within ``margin`` of
    the view ``box`` (x0, x1, y0, y1)."""
    return (bbox[0] <= box[1] + margin and bbox[2] >= box[0] - margin
            and bbox[1] <= box[3] + margin and bbox[3] >= box[2] - margin)


def _draw_tool_circles(ax, path: ToolPath, radius: float, box: tuple | None = None) -> None:
    """The cutter outline every ``max(length / 60, radius)`` along the cutting
    moves, as one collection (one artist, not one patch per circle: a patch
    each was a tenth of a report's drawing time); with ``box``, those that
    reach into it."""
    from matplotlib.collections import PatchCollection  # deferred: heavy and optional
    from matplotlib.patches import Circle  # deferred: heavy and optional
    cut = [s for s in path.segments if s.role is not Role.RAPID and s.length > 0]
    total = sum(s.length for s in cut)
    spacing = max(total / 60, radius)
    acc = 0.0
    circles = []
    for seg in cut:
        for s in np.arange((-acc) % spacing, seg.length, spacing):
            c = seg.geom.point(s)
            if box is None or _meets((c[0], c[1], c[0], c[1]), box, radius):
                circles.append(Circle(c[:2], radius))
        acc = (acc + seg.length) % spacing
    if circles:
        ax.add_collection(PatchCollection(circles, facecolor="none", edgecolor="#888888",
                                          lw=0.4, alpha=0.6), autolim=True)


def path_plot(path: ToolPath, contour: ToolPath | None, radius: float,
              violations: list | None = None, title: str = "") -> bytes:
    """Programmed contour (black), tool-centre path by role, tool circles
    along it, violations marked with red crosses at their witness points; a
    long thin part also gets zoomed views of its lead-in and first corner
    (:func:`zoom_windows`), at the same scale both ways."""
    x0, x1, y0, y1 = _extent([path, contour])
    step = _step(path)
    windows = zoom_windows(path, radius, (x0, x1, y0, y1))
    if not windows:
        fig, ax = _plan_figure(x0, x1, y0 - radius, y1 + radius)
        _draw_path(ax, path, contour, radius, violations, step)
        ax.set_title(plot_text(title))
        return _png(fig)
    fig, ax, zooms = _thin_figure(x0, x1, y0 - radius, y1 + radius, windows)
    _draw_path(ax, path, contour, radius, violations, step)
    ax.set_title(plot_text(title))
    for (name, box), zax in zip(windows, zooms):
        # finer samples: the window is a small part of the path
        _draw_path(zax, path, contour, radius, violations, step / 10, legend=False, box=box)
        _zoom_to(zax, name, box)
    return _png(fig)


#: A plan view thinner than this (height / width) is drawn with zoomed views:
#: at equal scale a 500 x 20 mm part is a strip in which no lead or corner shows.
THIN_ASPECT = 0.2


def zoom_windows(path: ToolPath, radius: float, extent) -> list[tuple[str, tuple]]:
    """For a long thin plan view (:data:`THIN_ASPECT`): squares (name, (x0,
    x1, y0, y1)) around where the first lead-in meets the part and around the
    first corner (else the last lead-out), each a few cutter radii wide and
    taking in the lead; none for any other part."""
    x0, x1, y0, y1 = extent
    w, h = x1 - x0, y1 - y0
    if w <= 0 or (h / w >= THIN_ASPECT and w / max(h, POINT_EPS) >= THIN_ASPECT):
        return []
    segs = [s for s in path.segments if s.length > 0 and s.role is not Role.RAPID]
    if not segs:
        return []
    spots = []
    lead_in = [s for s in segs if s.role is Role.LEAD_IN]
    if lead_in:
        spots.append(("lead-in", lead_in[0], lead_in[0].geom.point(lead_in[0].length)))
    corner = next((s for s in segs if s.role is Role.CORNER), None)
    lead_out = [s for s in segs if s.role is Role.LEAD_OUT]
    if corner is not None:
        spots.append(("first corner", corner, corner.geom.point(corner.length / 2)))
    elif lead_out:
        spots.append(("lead-out", lead_out[-1], lead_out[-1].geom.point(0.0)))
    out = []
    for name, seg, centre in spots:
        bx0, by0, bx1, by1 = seg.geom.bbox()
        half = max(4 * radius, 0.6 * max(bx1 - bx0, by1 - by0), POINT_EPS)
        half = min(half, max(w, h) / 4)
        cx, cy = float(centre[0]), float(centre[1])
        out.append((name, (cx - half, cx + half, cy - half, cy + half)))
    return out


def _thin_figure(x0, x1, y0, y1, windows):
    """A figure with the whole plan view on top (equal axes, as tall as it
    needs) and one square zoom panel per window below it."""
    from matplotlib.figure import Figure  # deferred: matplotlib is heavy and optional
    top = float(np.clip(7.0 * (y1 - y0) / max(x1 - x0, POINT_EPS) + 0.6, 1.2, 6.0))
    fig = Figure(figsize=(7.0, top + 3.4), dpi=110)
    grid = fig.add_gridspec(2, max(len(windows), 1), height_ratios=[top, 3.4])
    ax = fig.add_subplot(grid[0, :])
    zooms = [fig.add_subplot(grid[1, k]) for k in range(len(windows))]
    return fig, ax, zooms


def _zoom_to(ax, name: str, box) -> None:
    ax.set_xlim(box[0], box[1])
    ax.set_ylim(box[2], box[3])
    ax.set_aspect("equal")
    ax.set_title(f"zoom: {name}", fontsize=9)


def feed_plot(profile, title: str = "") -> bytes:
    """Tool path coloured by the planned tangential speed; a long thin part
    with zoomed views as :func:`path_plot` draws it."""
    samples = profile.sample(max(profile.duration / 4000, 1e-4)) if profile.duration > 0 else None
    if samples is None or len(samples) < 2:
        fig, ax = _figure()
        ax.set_aspect("equal")
        ax.set_title(plot_text(title))
        ax.grid(alpha=0.3)
        return _png(fig)
    xy = samples.position[:, :2]
    box = (xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max())
    toolpath = profile.path.toolpath
    windows = zoom_windows(toolpath, toolpath.radius or 0.0, box)
    if windows:
        fig, ax, zooms = _thin_figure(*box, windows)
    else:
        fig, ax = _plan_figure(*box, extra_width=1.2)
        zooms = []
    # the colours span the feed moves' speeds; a faster rapid takes the top colour
    top = speed_axis_top({"": profile})
    lc = _speed_lines(ax, xy, samples.feed, top)
    pad = 1.0
    ax.set_xlim(box[0] - pad, box[1] + pad)
    ax.set_ylim(box[2] - pad, box[3] + pad)
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    for (name, zbox), zax in zip(windows, zooms):
        # only the pieces that reach into the window (a tenth of the samples, or fewer)
        margin = 0.5 * (zbox[1] - zbox[0])
        near = ((xy[:, 0] >= zbox[0] - margin) & (xy[:, 0] <= zbox[1] + margin)
                & (xy[:, 1] >= zbox[2] - margin) & (xy[:, 1] <= zbox[3] + margin))
        piece = near[:-1] | near[1:]
        _speed_lines(zax, xy, samples.feed, top, piece)
        _zoom_to(zax, name, zbox)
        zax.grid(alpha=0.3)
    fig.colorbar(lc, ax=[ax, *zooms], label="feed (units/s)",
                 extend="max" if top is not None and samples.feed.max() > top else "neither")
    ax.set_title(plot_text(title))
    return _png(fig)


def _speed_lines(ax, xy: np.ndarray, feed: np.ndarray, top: float | None,
                 piece: np.ndarray | None = None):
    """The path ``xy`` on ``ax`` as line pieces coloured by ``feed`` (0 .. ``top``);
    ``piece``: which of the pieces (``len(xy) - 1`` booleans) to draw, default all."""
    from matplotlib.collections import LineCollection  # deferred: heavy and optional
    lines, colour = np.stack([xy[:-1], xy[1:]], axis=1), feed[:-1]
    if piece is not None:
        lines, colour = lines[piece], colour[piece]
    lc = LineCollection(lines, array=colour, cmap="viridis", lw=2.0)
    if top is not None:
        lc.set_clim(0.0, top)
    ax.add_collection(lc)
    return lc


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
