"""SVG drawing of a tool path (and optionally the programmed contour).

Lines and arcs are exact SVG path commands (``L`` and ``A``); spirals are
drawn as polylines sampled every ``spiral_step`` of arc length — a drawing,
never a basis for a result. The y axis is flipped so the drawing reads like
the machine's XY plane. Colours by role.
"""
from __future__ import annotations

import math
import numpy as np

from ccopt.export.text import xml_text
from ccopt.geometry import Arc, Line
from ccopt.geometry.angles import TWO_PI
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import Role, ToolPath

#: An arc within this of a full turn (radians) is drawn as a polyline: SVG's
#: arc command cannot draw a circle whose start and end coincide.
FULL_CIRCLE_SLACK = 1e-9

ROLE_COLOUR = {
    Role.RAPID: "#999999",
    Role.LEAD_IN: "#2a9d8f",
    Role.COMPENSATED: "#1d3557",
    Role.CORNER: "#e76f51",
    Role.LEAD_OUT: "#8338ec",
    Role.UNCOMPENSATED: "#457b9d",
}


def _d(seg, step: float) -> str:
    g = seg.geom
    x0, y0 = g.start
    out = [f"M {x0:.6f} {-y0:.6f}"]
    if isinstance(g, Line):
        x1, y1 = g.end
        out.append(f"L {x1:.6f} {-y1:.6f}")
    elif isinstance(g, Arc) and abs(g.sweep) < TWO_PI - FULL_CIRCLE_SLACK:
        x1, y1 = g.end
        large = 1 if abs(g.sweep) > math.pi else 0
        # y is flipped, so counter-clockwise in the plane is clockwise in SVG
        sweep_flag = 0 if g.sweep > 0 else 1
        out.append(f"A {g.radius:.6f} {g.radius:.6f} 0 {large} {sweep_flag} {x1:.6f} {-y1:.6f}")
    else:
        n = max(8, int(math.ceil(g.length / step)))
        pts = g.point(np.linspace(0.0, g.length, n + 1))
        out += [f"L {x:.6f} {-y:.6f}" for x, y in pts[1:]]
    return " ".join(out)


def write_svg(path: ToolPath, contour: ToolPath | None = None, title: str = "",
              spiral_step: float | None = None) -> str:
    """SVG text of ``path`` (and ``contour`` dashed underneath)."""
    segs = list(path.segments) + (list(contour.segments) if contour else [])
    if not segs:
        return '<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"/>\n'
    boxes = np.array([s.geom.bbox() for s in segs])
    xmin, ymin = boxes[:, 0].min(), boxes[:, 1].min()
    xmax, ymax = boxes[:, 2].max(), boxes[:, 3].max()
    span = max(xmax - xmin, ymax - ymin, POINT_EPS)
    pad = 0.05 * span
    step = spiral_step or span / 400
    stroke = span / 400
    vb = f"{xmin - pad:.6f} {-(ymax + pad):.6f} {xmax - xmin + 2 * pad:.6f} {ymax - ymin + 2 * pad:.6f}"
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{vb}" width="800" '
             f'height="{800 * (ymax - ymin + 2 * pad) / (xmax - xmin + 2 * pad):.0f}">',
             f"<title>{xml_text(title or path.style)}</title>"]
    if contour is not None:
        parts.append(f'<g fill="none" stroke="#000" stroke-width="{stroke:.6g}" '
                     f'stroke-dasharray="{4 * stroke:.6g} {2 * stroke:.6g}">')
        parts += [f'<path d="{_d(s, step)}"/>' for s in contour.segments if s.length > 0]
        parts.append("</g>")
    parts.append(f'<g fill="none" stroke-width="{stroke:.6g}">')
    for s in path.segments:
        if s.length > 0:
            parts.append(f'<path stroke="{ROLE_COLOUR[s.role]}" d="{_d(s, step)}">'
                         f"<title>{s.role.value}, line {s.block.source.line if s.block else '?'}"
                         f"</title></path>")
    parts.append("</g></svg>")
    return "\n".join(parts) + "\n"
