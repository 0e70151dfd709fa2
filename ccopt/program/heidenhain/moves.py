"""Path functions: ``L``, ``LP``, ``C``, ``CP``, ``CR``, ``CT``, ``CC``,
``RND``, ``CHF``, ``APPR``, ``DEP``.

Each contour element is made as a plane piece (:mod:`.contour`) first, so a
pending rounding or chamfer (written between two elements) and a pending
approach (``APPR`` needs the direction of the first contour element) can be
applied before its block is written. Plane of a straight line: the working
plane; of ``C``/``CP``: the pole's plane; of ``CR``/``CT``: the working
plane, or the plane of the two axes the block writes when that is another.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ccopt.errors import ProgramError
from ccopt.program.heidenhain import contour
from ccopt.program.heidenhain.args import Args
from ccopt.program.heidenhain.machine import LEADS, PLANE_OF_PAIR, Machine
from ccopt.program.model import PLANE_AXES, Motion, Source
from ccopt.tolerances import POINT_EPS

#: Largest difference between a ``C`` arc's end radius and its start radius
#: (program units) still read as an arc about ``CC``: CAM systems round end
#: points to 3 decimals. Beyond it the block is refused, as the TNC does.
ARC_END_TOL = 0.005
#: The approach/departure words each kind takes.
_LEAD_WORDS = {"LT": {"LEN"}, "LN": {"LEN"}, "CT": {"CCA", "R"}, "LCT": {"R"}}
_COMMON = {"side", "F", "M"}


@dataclass
class Pending:
    """What waits for the next contour element: ``RND``/``CHF`` (``value``)
    or ``APPR`` (``lead``: the lead's words, ``ps``: where the tool was)."""

    kind: str
    src: Source
    value: float = 0.0
    lead: dict | None = None
    ps: tuple | None = None
    feed: float | None = None
    rapid_before: bool = False
    w_end: float = 0.0
    mcodes: tuple = ()


class Moves:
    """The path functions over one :class:`Machine`."""

    def __init__(self, m: Machine):
        self.m = m
        self.pending: Pending | None = None

    def err(self, msg: str, src: Source) -> ProgramError:
        return ProgramError(msg, src.file, src.line, src.col)

    # -- elements ----------------------------------------------------------------------
    def element(self, src: Source, piece, w1: float, plane: str, a: Args,
                rapid: bool = False) -> None:
        """Write the contour element ``piece`` (from the current position),
        after any pending rounding, chamfer or approach."""
        m = self.m
        if a.side is not None and a.side != m.side and piece[0] == "arc":
            raise self.err("radius compensation is switched on or off in a straight line "
                           "block (L, LP, APPR, DEP), not on an arc", src)
        if a.side is not None:
            m.side = a.side
        m.feed_from(a.feed, a.st.line, a.col("F"), a.fauto)
        pend, self.pending = self.pending, None
        if pend is not None and pend.kind in ("RND", "CHF"):
            piece = self._corner(pend, piece, plane)
        in_plane = contour.norm(contour.sub(piece[2], piece[1])) > POINT_EPS or piece[0] == "arc"
        if pend is not None and pend.kind == "APPR":
            if not in_plane:
                raise self.err("APPR must be followed by the first contour element, a move "
                               "in the working plane", pend.src)
            self._approach(pend, piece, plane)
        m.last_rapid = rapid
        w_axis = PLANE_AXES[plane][2]
        if not in_plane and abs(w1 - m.pos[w_axis]) <= POINT_EPS and not a.coords:
            return          # no coordinates (L FMAX M99): no block, its M functions still act
        m.emit_piece(src, piece, w1, plane, rapid=rapid, mcodes=a.mcodes)
        if in_plane:
            m.last_piece, m.last_block_index = piece, len(m.blocks) - 1

    def _corner(self, pend: Pending, piece, plane: str):
        m = self.m
        last = m.blocks[m.last_block_index] if m.last_piece is not None else None
        if last is None or m.last_block_index != len(m.blocks) - 1 or last.modal.plane != plane:
            raise self.err(f"{pend.kind} must stand between two contour elements in one plane",
                           pend.src)
        try:
            if pend.kind == "RND":
                ta, arc, tb = contour.rounding(m.last_piece, piece, pend.value)
            else:
                ta, arc, tb = contour.chamfer(m.last_piece, piece, pend.value)
        except contour.GeometryError as exc:
            raise self.err(str(exc), pend.src) from None
        m.replace_end(m.last_block_index, ta)
        w = m.pos[PLANE_AXES[plane][2]]
        m.emit_piece(pend.src, arc, w, plane, feed=pend.feed)
        new = (piece[0], tb, *piece[2:])
        if piece[0] == "arc":
            new = ("arc", tb, piece[2], piece[3],
                   contour.arc_sweep(tb, piece[2], piece[3], piece[4] > 0))
        return new

    def _approach(self, pend: Pending, piece, plane: str) -> None:
        """The APPR blocks, now that the first element's direction is known:
        PS -> PH, the infeed at PH, PH -> PA (at radius 0: the program's path)."""
        m = self.m
        lead = pend.lead
        t1 = contour.start_tangent(piece)
        m.pos = list(pend.ps)
        try:
            ph, pieces = contour.approach(lead["kind"], m.uv(pend.ps, plane), piece[1], t1,
                                          m.side, 0.0, lead["length"], lead["radius"],
                                          lead["cca"])
        except contour.GeometryError as exc:
            raise self.err(str(exc), pend.src) from None
        m.meta[LEADS][pend.src] = {"dir": "APPR", **lead}
        w_axis = PLANE_AXES[plane][2]
        w0 = m.pos[w_axis]
        m.emit(pend.src, Motion.LINE, m.xyz(ph, w0, plane), plane=plane,
               rapid=pend.rapid_before, surface="air")
        if abs(pend.w_end - w0) > POINT_EPS:
            m.emit(pend.src, Motion.LINE, m.xyz(ph, pend.w_end, plane), plane=plane,
                   feed=pend.feed, surface="air")
        for p in pieces:
            m.emit_piece(pend.src, p, pend.w_end, plane, feed=pend.feed, surface="air",
                         mcodes=pend.mcodes)

    # -- statements ------------------------------------------------------------------------
    def line(self, src: Source, a: Args, polar: bool) -> None:
        m = self.m
        a.allow(({"PR", "IPR", "PA", "IPA", "Z"} if polar else set("XYZ")) | _COMMON | {"M"},
                "LP" if polar else "L", m.file)
        end = m.target({k: v for k, v in a.coords.items()} if not polar else
                       {k: v for k, v in a.coords.items() if k == "Z"})
        plane = m.plane
        if polar:
            plane = m.pole_plane
            uv = self._polar_end(src, a, plane)
            end = list(m.xyz(uv, end[PLANE_AXES[plane][2]], plane))
        piece = ("line", m.uv(m.pos, plane), m.uv(end, plane))
        if self.pending is not None and self.pending.kind != "APPR" and not (
                contour.norm(contour.sub(piece[2], piece[1])) > POINT_EPS):
            raise self.err(f"{self.pending.kind} must be followed by a contour element",
                           self.pending.src)
        self.element(src, piece, end[PLANE_AXES[plane][2]], plane, a, rapid=a.rapid)

    def _pole(self, src: Source):
        if self.m.pole is None:
            raise self.err("polar coordinates or C without a pole: program CC first", src)
        return self.m.uv(self.m.pole, self.m.pole_plane)

    def _polar_end(self, src: Source, a: Args, plane: str) -> contour.Pt:
        cc = self._pole(src)
        if self.m.rot != 0.0 and plane != self.m.plane:
            raise self.err("polar coordinates in another plane than the working plane while "
                           "it is turned (CYCL DEF 10) are not read by ccopt", src)
        here = contour.sub(self.m.uv(self.m.pos, plane), cc)
        pr0, pa0 = contour.norm(here), math.degrees(math.atan2(here[1], here[0]))
        pr = a.pr if a.pr is not None else pr0 + (a.ipr or 0.0)
        # PA is measured in the program's axes: a rotation (CYCL DEF 10) turns it
        pa = a.pa + self.m.rot if a.pa is not None else pa0 + (a.ipa or 0.0)
        return contour.polar(cc, pr, pa)

    def pole(self, src: Source, a: Args) -> None:
        m = self.m
        a.allow(set("XYZ"), "CC", m.file)
        axes = set(a.coords)
        if len(axes) == 2:
            plane = PLANE_OF_PAIR[frozenset(axes)]
        elif len(axes) <= 1 and axes <= set(m.plane):
            plane = m.plane
        else:
            raise self.err("CC: give the two coordinates of the pole in one plane", src)
        if m.rot != 0.0 and plane != m.plane:
            raise self.err("CC in another plane than the working plane while it is turned "
                           "(CYCL DEF 10) is not read by ccopt", src)
        m.pole, m.pole_plane = tuple(m.target(a.coords)), plane

    def arc(self, src: Source, head: str, a: Args) -> None:
        """``C``, ``CP``, ``CR``, ``CT``."""
        m = self.m
        words = {"C": set("XYZ") | {"DR"}, "CP": {"PA", "IPA", "Z", "DR"},
                 "CR": set("XYZ") | {"DR", "R"}, "CT": set("XYZ")}[head]
        a.allow(words | _COMMON, head, m.file)
        if head in ("C", "CP"):
            plane = m.pole_plane
        else:
            plane = m.plane
            inplane = [ax for ax in a.coords if ax != "XYZ"[PLANE_AXES[m.plane][2]]]
            if len(a.coords) == 2 and len(inplane) < 2:
                plane = PLANE_OF_PAIR[frozenset(a.coords)]
        iw = PLANE_AXES[plane][2]
        end = m.target({k: v for k, v in a.coords.items()})
        s = m.uv(m.pos, plane)
        if head == "CP":
            end_uv = self._polar_end(src, a, plane)
        else:
            end_uv = m.uv(end, plane)
        piece = self._arc_piece(src, head, a, s, end_uv, plane)
        self.element(src, piece, end[iw], plane, a)

    def _arc_piece(self, src: Source, head: str, a: Args, s, e, plane: str):
        m = self.m
        try:
            if head == "CT":
                if m.last_piece is None or self.pending is not None:
                    raise contour.GeometryError("CT needs a contour element just before it "
                                                "(not RND, CHF or APPR)")
                c, ccw = contour.tangent_arc(s, contour.end_tangent(m.last_piece), e)
            else:
                if a.direction is None and head != "CR":
                    raise contour.GeometryError(f"{head}: give the direction DR+ or DR-")
                ccw = (a.direction or 1) > 0
                if head == "CR":
                    if a.radius is None or a.direction is None:
                        raise contour.GeometryError("CR: give the radius R and DR+ or DR-")
                    c = contour.centre_from_radius(s, e, a.radius, ccw)
                else:
                    c = self._pole(src)
                    if m.pole_plane != plane:
                        raise contour.GeometryError("the arc is not in the pole's plane")
        except contour.GeometryError as exc:
            raise self.err(str(exc), src) from None
        rs, re_ = contour.norm(contour.sub(s, c)), contour.norm(contour.sub(e, c))
        if abs(rs - re_) > ARC_END_TOL:
            raise self.err(f"the end point is {re_:.6g} from the centre, the start {rs:.6g}: "
                           "not an arc (check the end point and CC)", src)
        if rs <= POINT_EPS:
            raise self.err("the arc starts at its centre (check CC)", src)
        if head == "CP" and a.ipa is not None:
            sweep = math.radians(a.ipa)
            if (sweep > 0) != ccw and abs(sweep) > 0:
                raise self.err(f"IPA{a.ipa:+g} turns against DR{'+' if ccw else '-'}", src)
            e = contour.rotate_about(s, c, sweep)
        else:
            sweep = contour.arc_sweep(s, e, c, ccw)
        return ("arc", s, e, c, sweep)

    def corner(self, src: Source, head: str, a: Args, value: float | None) -> None:
        """``RND R..`` (``value`` None: from ``R``) or ``CHF <value>``."""
        a.allow({"R", "F", "M"} if head == "RND" else {"F", "M"}, head, self.m.file)
        if head == "RND":
            value = a.radius
        if value is None:
            raise self.err(f"{head}: give its size ({'RND R2' if head == 'RND' else 'CHF 1'})",
                           src)
        self.pending = Pending(head, src, value, feed=None if a.feed is None else
                               a.feed / 60.0 / (10.0 if self.m.units == "inch" else 1.0))

    def _lead_point(self, src: Source, head: str, kind: str, a: Args, coords: bool):
        """``(kind, end)``: the lead's kind without its polar ``P`` and the
        point its coordinates give (``APPR PLT PR.. PA..``: polar about ``CC``
        in the working plane), after checking the words it takes."""
        m = self.m
        polar = kind.startswith("P") and kind[1:] in _LEAD_WORDS
        base = kind[1:] if polar else kind
        if base not in _LEAD_WORDS:
            raise self.err(f"{head} {kind}: not read by ccopt ({head} LT, LN, CT, LCT and "
                           "their polar forms are)", src)
        w = "XYZ"[PLANE_AXES[m.plane][2]]
        where = ({"PR", "PA", "IPR", "IPA", w} if polar else set("XYZ")) if coords else {w}
        a.allow(_LEAD_WORDS[base] | where | _COMMON, f"{head} {kind}", m.file)
        end = m.target({k: v for k, v in a.coords.items() if k == w or not polar})
        if polar:
            if m.pole_plane != m.plane:
                raise self.err(f"{head} {kind}: the pole CC is not in the working plane", src)
            uv = self._polar_end(src, a, m.plane)
            end = list(m.xyz(uv, end[PLANE_AXES[m.plane][2]], m.plane))
        elif coords and len(set(a.coords) - {w}) < 2:
            raise self.err(f"{head} {kind}: give both coordinates of the "
                           f"{'first contour' if head == 'APPR' else 'end'} point", src)
        return base, end

    def appr(self, src: Source, kind: str, a: Args) -> None:
        m = self.m
        kind, end = self._lead_point(src, "APPR", kind, a, True)
        if a.side not in (1, -1):
            raise self.err(f"APPR {kind}: give the radius compensation RL or RR", src)
        ps = tuple(m.pos)
        rapid_before = m.last_rapid
        m.feed_from(a.feed, a.st.line, a.col("F"), a.fauto)
        m.side = a.side
        self.pending = Pending("APPR", src, lead={"kind": kind, "length": a.length,
                                                  "radius": a.radius, "cca": a.cca},
                               ps=ps, feed=m.feed, rapid_before=rapid_before,
                               w_end=end[PLANE_AXES[m.plane][2]], mcodes=a.mcodes)
        # the next element starts at PA: the blocks are written with it
        m.pos = [end[0], end[1], end[2]]
        m.pos[PLANE_AXES[m.plane][2]] = ps[PLANE_AXES[m.plane][2]]

    def dep(self, src: Source, kind: str, a: Args) -> None:
        m = self.m
        kind, end = self._lead_point(src, "DEP", kind, a, kind in ("LCT", "PLCT"))
        if m.side == 0 or m.last_piece is None or m.last_block_index != len(m.blocks) - 1:
            raise self.err(f"DEP {kind} must follow the last contour element, with RL or RR "
                           "in force", src)
        plane = m.blocks[-1].modal.plane
        m.feed_from(a.feed, a.st.line, a.col("F"), a.fauto)
        pn = m.uv(end, plane) if kind == "LCT" else None
        try:
            pieces = contour.departure(kind, m.uv(m.pos, plane),
                                       contour.end_tangent(m.last_piece), m.side, 0.0,
                                       a.length, a.radius, a.cca, pn)
        except contour.GeometryError as exc:
            raise self.err(str(exc), src) from None
        m.meta[LEADS][src] = {"dir": "DEP", "kind": kind, "length": a.length,
                              "radius": a.radius, "cca": a.cca}
        iw = PLANE_AXES[plane][2]
        w0 = m.pos[iw]
        for p in pieces:
            m.emit_piece(src, p, w0, plane, surface="air", mcodes=a.mcodes)
        m.side = 0
        m.last_piece = None
        if "XYZ"[iw] in a.coords and abs(end[iw] - w0) > POINT_EPS:
            m.emit(src, Motion.LINE, m.xyz(m.uv(m.pos, plane), end[iw], plane), plane=plane,
                   rapid=a.rapid)

