"""HEIDENHAIN TNC cutter radius compensation (RL/RR/R0, M97, M98, APPR/DEP).

Rules: docs/compensation.md, section 10 "HEIDENHAIN TNC style", from the TNC
User's Manuals (HEIDENHAIN conversational programming: "Tool compensation",
"Approaching and departing a contour", "Miscellaneous functions for
contouring behavior"). The engine is PMAC's joint-by-joint walk
(:mod:`.pmac`) with the TNC's choices:

* **Outside corners** (every one, there is no break angle): a transition
  arc of radius ``r`` about the programmed corner; **inside corners**: the
  offsets' intersection (HEIDENHAIN rule 2).
* **Switching on and off** (HEIDENHAIN rule 1): the first block with
  ``RL``/``RR`` ends perpendicular to the first contour element's start,
  ``P + r*o(t_next)``; the block with ``R0`` leaves from perpendicular to the
  last element's end, ``P + r*o(t_last)``. ``RL`` <-> ``RR`` without an
  ``R0`` block between is an error.
* **M97** on a block: the outside corner at its end is cut at the offsets'
  intersection, as an inside corner (rule 3). **M98**: the inside corner at
  its end is left open: the tool path is extended to the end of the block's
  offset, and the next block runs from there (rule 4).
* **APPR / DEP** (rule 5): the approach and departure paths are built on
  the tool centre (:func:`ccopt.program.heidenhain.contour.approach` and
  ``departure`` at the radius in force); the reader marks their blocks
  (``Program.meta["heidenhain_leads"]``) and wrote them at radius 0.
"""
from __future__ import annotations

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.batch import ElementArrays
from ccopt.compensate.corners import (
    Corner, Element, carrier_intersections, classify, corner_arc, tool_geometry, turn,
)
from ccopt.compensate.pmac import (
    COMP, LEAD_IN, LEAD_OUT, ROLE_OF, UNCOMP, Joint, Joints, MoveClasses, PmacStyle, SegmentList,
    classes_of, decide_joints, emit_tail,
)
from ccopt.compensate.planes import by_plane
from ccopt.compensate.scan import ScanResult, scan_program
from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line
from ccopt.geometry.columns import paused_gc
from ccopt.program.heidenhain import LEADS
from ccopt.program.heidenhain import contour
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import PathSegment, Role, ToolPath

#: Every outside corner gets the transition arc: PMAC's Isx99 at its limit.
NO_BREAK_ANGLE = 1.0


def _err(block: Block, message: str) -> CompensationError:
    s = block.source
    return CompensationError(message, s.file, s.line, s.col)


def _geometry(piece):
    """A :mod:`contour` piece as an exact :class:`Line` or :class:`Arc`."""
    if piece[0] == "line":
        return Line(piece[1], piece[2])
    _, s, _, c, sweep = piece
    radius = contour.norm(contour.sub(s, c))
    return Arc(c, radius, float(np.arctan2(s[1] - c[1], s[0] - c[0])), sweep)


class HeidenhainStyle(PmacStyle):
    """The TNC rules (no options: the TNC has no switch for them)."""

    name = "heidenhain"

    def __init__(self):
        super().__init__(break_cos=NO_BREAK_ANGLE)
        self._leads: dict = {}
        self._special = np.zeros(0, bool)

    # -- joints ---------------------------------------------------------------------
    def _is_lead(self, el: Element) -> bool:
        return el.block.source in self._leads

    def batch_corners(self, arr: ElementArrays, ia: np.ndarray):
        done, end_prev, start_next, arcs = super().batch_corners(arr, ia)
        # M97/M98 blocks and the approach/departure elements go one at a time
        done = done & ~self._special[ia] & ~self._special[ia + 1]
        return done, end_prev, start_next, arcs

    def joint(self, a: Element, ca: str, b: Element, cb: str, gap: int) -> Joint:
        if self._is_lead(a) or self._is_lead(b):
            return Joint(a.end, a.end)      # decided by _leads_joints
        if a.k != 0 and b.k != 0 and a.k != b.k:
            raise _err(b.block, "radius compensation changes between RL and RR: the TNC needs "
                                "a block with R0 between them (HEIDENHAIN rule 1)")
        if cb == LEAD_OUT and a.r > 0.0:
            return Joint(a.offset_point(True, a.k, a.r), a.offset_point(True, a.k, a.r))
        if ca == LEAD_IN and cb == COMP and a.r > 0.0:
            B = b.offset_point(False, b.k, a.r)
            return Joint(B, B)
        if ca in (LEAD_IN, COMP) and cb == COMP and a.r > 0.0:
            mcodes = a.block.mcodes
            if 97 in mcodes or 98 in mcodes:
                return self._m97_m98(a, b, 97 in mcodes)
        return super().joint(a, ca, b, cb, gap)

    def _m97_m98(self, a: Element, b: Element, m97: bool) -> Joint:
        """HEIDENHAIN rules 3 and 4 at the corner after ``a``."""
        k, r = a.k, a.r
        A, B = a.offset_point(True, k, r), b.offset_point(False, k, r)
        tr = turn(a.t_end, b.t_start)
        kind = classify(k, tr)
        if m97 and kind is Corner.OUTSIDE:
            hits = carrier_intersections(a.carrier(True, k, r), b.carrier(False, k, r))
            x = decisions.nearest_root(hits, A, B)
            if x is not None:
                return Joint(x, x)
            if decisions.HEIDENHAIN_M97_WITHOUT_INTERSECTION == "arc":
                return Joint(A, B, [corner_arc(a.end, r, a.t_end, b.t_start, k)])
            return Joint(A, A)
        if not m97 and kind is Corner.INSIDE:
            if decisions.HEIDENHAIN_M98_OPEN_CORNER == "extend-then-next-block":
                return Joint(A, A)
            return Joint(A, B, [Line((float(A[0]), float(A[1])), (float(B[0]), float(B[1])))])
        return super().joint(a, COMP, b, COMP, 0)

    # -- approach and departure ----------------------------------------------------------
    def _groups(self, scan: ScanResult):
        """``(first, last, spec)`` of every run of APPR or DEP elements."""
        out, i, n = [], 0, len(scan)
        while i < n:
            src = scan.blocks[i].source
            spec = self._leads.get(src)
            if spec is None:
                i += 1
                continue
            j = i
            while j + 1 < n and scan.blocks[j + 1].source == src:
                j += 1
            out.append((i, j, spec))
            i = j + 1
        return out

    def _lead_pieces(self, scan: ScanResult, first: int, last: int, spec: dict):
        """The tool pieces of one APPR/DEP run, and where the neighbours end/start."""
        el = scan.element(last if spec["dir"] == "APPR" else first)
        k, r = el.k, el.r
        if spec["dir"] == "APPR":
            if last + 1 >= len(scan) or scan.k[last + 1] != k:
                raise _err(el.block, "APPR must be followed by the first contour element")
            nxt = scan.element(last + 1)
            ps = scan.element(first).start
            _, pieces = contour.approach(spec["kind"], (ps[0], ps[1]), tuple(el.end),
                                         tuple(nxt.t_start), k, r, spec["length"],
                                         spec["radius"], spec["cca"])
            return pieces
        if first == 0 or scan.k[first - 1] != k:
            raise _err(el.block, "DEP must follow the last contour element")
        prev = scan.element(first - 1)
        pn = scan.element(last).end
        return contour.departure(spec["kind"], tuple(el.start), tuple(prev.t_end), k, r,
                                 spec["length"], spec["radius"], spec["cca"], (pn[0], pn[1]))

    def _leads_joints(self, scan: ScanResult, classes: MoveClasses, joints: Joints) -> dict:
        """Put the APPR/DEP tool paths into ``joints``; returns the pieces that
        replace each lead element's own tool segment."""
        override: dict[int, list] = {}
        for first, last, spec in self._groups(scan):
            try:
                pieces = self._lead_pieces(scan, first, last, spec)
            except contour.GeometryError as exc:
                raise _err(scan.blocks[first], f"{spec['dir']} {spec['kind']}: {exc}") from None
            geoms = [_geometry(p) for p in pieces]
            start, end = np.asarray(pieces[0][1], float), np.asarray(pieces[-1][2], float)
            for i in range(first, last + 1):
                override[i] = []
                joints.corners.pop(i, None)
            if spec["dir"] == "APPR":
                if first < last:      # PS -> PH, then the approach element
                    override[first] = [(Line(tuple(joints.starts[first]), tuple(start)),
                                        ROLE_OF[classes[first]])]
                else:                 # the tool stood at PH: the lead-in is the approach
                    override[first] = [(Line(tuple(joints.starts[first]), tuple(start)),
                                        Role.LEAD_IN)]
                override[last] = override.get(last, []) + [(g, Role.COMPENSATED) for g in geoms]
                joints.ends[first] = joints.starts[last] = start
            else:
                joints.corners.pop(first - 1, None)
                joints.ends[first - 1] = start
                override[first] = [(g, Role.COMPENSATED) for g in geoms]
            joints.ends[last] = end
            if last + 1 < len(scan):
                joints.starts[last + 1] = end
            elif spec["dir"] == "DEP":
                joints.tail_return = None    # DEP ends compensation where it leaves the tool
        return override

    # -- the whole program -----------------------------------------------------------------
    @by_plane
    def compensate(self, program: Program, radius: float | None = None,
                   side: int | None = None) -> ToolPath:
        with paused_gc():
            scan = scan_program(program, radius=radius, side=side, style=self.name)
            return self._assemble(scan, program)

    def _assemble(self, scan: ScanResult, program: Program) -> ToolPath:
        n, k, r = len(scan), scan.k, scan.r
        out = SegmentList()
        radius = float(r[k != 0].max()) if n and (k != 0).any() else 0.0
        if n == 0:
            out.gap(scan.gaps[0], np.asarray(scan.start_uv, float), False)
            return ToolPath(tuple(out.segs), plane=scan.plane, style=self.name, radius=radius,
                            dwells=tuple(out.dwells), units=program.units)
        self._leads = program.meta.get(LEADS, {})
        self._special = np.array([b.source in self._leads or 97 in b.mcodes or 98 in b.mcodes
                                  for b in scan.blocks] + [False], bool)
        classes = classes_of(k)
        for i, cl in enumerate(classes):
            if cl == COMP and scan.blocks[i].source not in self._leads:
                scan.element(i).check_offset(int(k[i]), float(r[i]))
        arr = ElementArrays.from_blocks(scan.blocks, scan.plane, k, r, scan.columns)
        joints = decide_joints(self, scan, arr, classes, True)
        if k[-1] != 0 and decisions.HEIDENHAIN_PROGRAM_END_WHILE_ON == "stay-at-offset":
            joints.tail_return = None
        override = self._leads_joints(scan, classes, joints)
        arc_at, arc_rows = joints.arc_rows
        for i, (cu, cv, rad, th0, sw) in zip(arc_at.tolist(), arc_rows.tolist()):
            if i not in override and i + 1 not in override:
                joints.corners[i] = [Arc((cu, cv), rad, th0, sw)]
        _emit(out, scan, classes, joints, override)
        emit_tail(out, scan, joints)
        return ToolPath(tuple(out.segs), plane=scan.plane, style=self.name, radius=radius,
                        dwells=tuple(out.dwells), units=program.units)


def _emit(out: SegmentList, scan: ScanResult, classes: MoveClasses, joints: Joints,
          override: dict) -> None:
    """Each move's tool segments (its own, or the APPR/DEP pieces in its
    place), its corner segments and the gaps between moves (after the corner
    arc, decisions.GAP_MOVES_AFTER_CORNER_ARC, as PMAC)."""
    n, k = len(scan), scan.k
    plane_w = PLANE_AXES[scan.plane][2]
    gaps_after = decisions.GAP_MOVES_AFTER_CORNER_ARC
    for i, (blk, cls) in enumerate(zip(scan.blocks, classes)):
        on = k[i] != 0 and cls != LEAD_IN
        if scan.gaps[i] and (gaps_after or i == 0):
            out.gap(scan.gaps[i], joints.starts[i], on)
        w0, w1 = blk.start[plane_w], blk.end[plane_w]
        if i in override:
            pieces = override[i]
        else:
            role = Role.RAPID if cls == UNCOMP and blk.motion is Motion.RAPID else ROLE_OF[cls]
            pieces = [(tool_geometry(scan.element(i), joints.starts[i], joints.ends[i]), role)]
        for geom, role in pieces:
            if geom.length > POINT_EPS or w0 != w1:
                out.segs.append(PathSegment(geom, role, blk, w0, w1, blk.feed))
                w0 = w1
        if not gaps_after and i + 1 < n and scan.gaps[i + 1]:
            out.gap(scan.gaps[i + 1], joints.ends[i], k[i + 1] != 0 and classes[i + 1] != LEAD_IN)
        for cg in joints.corners.get(i, ()):
            out.segs.append(PathSegment(cg, Role.CORNER, blk, w1, w1, blk.feed))


__all__ = ["HeidenhainStyle"]
