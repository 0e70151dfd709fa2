"""SINUMERIK 840D tool radius compensation (G40/G41/G42, G450/G451, DISC,
NORM/KONT, smooth approach and retraction G147-G348).

Rules: docs/compensation.md, section "SINUMERIK 840D style", from the
Programming Manual Fundamentals 6FC5398-2EP40-0BA0 (12/2019), section 2.10
"Tool radius compensation" (2.10.2 approach and retraction NORM/KONT,
2.10.3 outside corners G450/G451/DISC, 2.10.4 smooth approach and
retraction) and the Function Manual Basic Functions W1 "Tool offset",
section 18.5 "Tool radius compensation 2D (TRC)". The control looks ahead
like the Fagor 8070 (:mod:`.fagor`), whose joint machinery this style runs
on: at each boundary between two in-plane moves a joint decides where the
incoming tool path ends, which transition segments follow and where the
outgoing one starts.

* **Outside corners**: ``G450`` (default) an arc of radius ``r`` about the
  programmed corner ``P`` from ``P + r*o(t_in)`` to ``P + r*o(t_out)``, part
  of the next block; ``DISC=100`` the offsets' intersection; ``0 < DISC <
  100`` is refused (the manual gives no curve). ``G451``: the offsets'
  intersection, falling back to G450 when the path turns by the corner
  limit or more (MD20210 ``CUTCOM_CORNER_LIMIT``, 100 degrees) or when the
  offsets do not meet. The outgoing block's mode decides.
* **Inside corners**: the offsets' intersection (none: the change over the
  next move, as PMAC).
* **Approach and retraction** (``NORM``/``KONT`` of the activation and the
  G40 block): ``NORM`` straight to / from the point perpendicular to the
  contour's start / end; ``KONT`` with the start (end) point behind the
  contour goes round the contour's start (end) point as at an outside
  corner under G450/G451, else as ``NORM``. ``KONTT``/``KONTC`` are refused.
* **Smooth approach and retraction** (:mod:`.siemens_sar`): on the
  activation block (``G147``/``G247``/``G347``) or the G40 block
  (``G148``/``G248``/``G348``), the block's move becomes the SAR sub-moves
  P0..P4 ending (starting) tangentially at the contour's offset start (end).
"""
from __future__ import annotations

import math

from ccopt.compensate import decisions
from ccopt.compensate.corners import (
    Corner, Element, carrier_intersections, classify, corner_arc, reversal_sweep, turn,
)
from ccopt.compensate.fagor import UNCOMP, LEAD_IN, COMP, LEAD_OUT, FagorStyle, _FagorSegments
from ccopt.compensate.pmac import Joint
from ccopt.compensate.siemens_sar import (APPROACH_KINDS, retraction_kind, sar_pieces)
from ccopt.errors import CompensationError
from ccopt.program.model import Block, SiemensModes, SmoothApproach
from ccopt.tolerances import POINT_EPS

_DEFAULT_MODES = SiemensModes()
#: DISC values the style reproduces: 0 (the transition circle) and 100 (the intersection).
DISC_CIRCLE, DISC_INTERSECTION = 0.0, 100.0

__all__ = ["SiemensStyle", "UNCOMP", "LEAD_IN", "COMP", "LEAD_OUT"]


def _err(block: Block, message: str) -> CompensationError:
    s = block.source
    return CompensationError(message, s.file, s.line, s.col)


def modes_of(block: Block) -> SiemensModes:
    """The block's SINUMERIK modes (the defaults for programs of other dialects)."""
    return block.modal.siemens or _DEFAULT_MODES


class SiemensStyle(FagorStyle):
    """The SINUMERIK 840D rules. The modes come from the program
    (``Modal.siemens``); the options override them everywhere:

    ``corner``: ``"G450"`` or ``"G451"``; ``approach``: ``"NORM"`` or
    ``"KONT"`` (the program's smooth approaches and retractions are then
    not made); ``corner_limit``: the G451 fallback angle in degrees
    (default :data:`decisions.SIEMENS_CORNER_LIMIT_DEG`); ``sar``:
    ``"G147"``, ``"G247"`` or ``"G347"`` makes that smooth approach (and its
    retraction) on every activation and G40 move, the program's own
    replaced, with ``disr`` (program units) and ``discl`` (``None``: none).
    """

    name = "siemens"

    def __init__(self, corner: str | None = None, approach: str | None = None,
                 corner_limit: float | None = None, sar: str | None = None,
                 disr: float | None = None, discl: float | None = None):
        if corner not in (None, "G450", "G451"):
            raise ValueError("corner must be 'G450' (transition circle) or 'G451' "
                             "(intersection)")
        if approach not in (None, "NORM", "KONT"):
            raise ValueError("approach must be 'NORM' or 'KONT'")
        if sar not in (None, *APPROACH_KINDS):
            raise ValueError(f"sar must be one of {', '.join(APPROACH_KINDS)}")
        if sar is not None and (disr is None or not math.isfinite(disr) or disr < 0
                                or (sar != "G147" and disr <= 0)):
            raise ValueError("sar needs disr, a distance >= 0 (> 0 for G247/G347)")
        if corner_limit is not None and not 0.0 < corner_limit <= 180.0:
            raise ValueError("corner_limit is an angle in degrees in (0, 180]")
        super().__init__()
        self.corner = corner
        self.approach = approach
        self.corner_limit = (decisions.SIEMENS_CORNER_LIMIT_DEG if corner_limit is None
                             else float(corner_limit))
        self.sar = sar
        self.disr = disr
        self.discl = discl

    # -- modes ----------------------------------------------------------------
    def _corner_modes(self, a: Element, b: Element) -> tuple[str, float, Block]:
        """G450/G451 and DISC at the corner between ``a`` and ``b``: the
        outgoing block's (decisions.SIEMENS_MODAL_OF_CORNER), and that block."""
        blk = b.block if decisions.SIEMENS_MODAL_OF_CORNER == "outgoing-block" else a.block
        m = modes_of(blk)
        return self.corner or m.corner, m.disc, blk

    def _approach_mode(self, blk: Block) -> str:
        mode = self.approach or modes_of(blk).approach
        if mode in ("KONTT", "KONTC"):
            raise _err(blk, f"{mode}: the polynomial approach and retraction is not "
                            "reproduced by ccopt (the manuals do not give the polynomial): "
                            "use NORM or KONT, or a smooth approach G147/G247/G347")
        return mode

    def smooth(self, blk: Block, approach: bool) -> SmoothApproach | None:
        """The SAR of an activation (``approach``) or G40 block: the one the
        ``sar`` option forces, none when the ``approach`` option forces NORM or
        KONT, else the block's own."""
        if self.sar is not None:
            kind = self.sar if approach else retraction_kind(self.sar)
            return SmoothApproach(kind=kind, disr=float(self.disr), discl=self.discl)
        own = modes_of(blk).sar
        if own is None or self.approach is not None:
            return None
        return own if own.approach == approach else None

    # -- joints ----------------------------------------------------------------
    def outside(self, a: Element, b: Element, P, A, B, t_in, t_out, k: int, r: float,
                reversal: bool) -> Joint:
        """The outside-corner joint from ``A`` to ``B`` about ``P``: G450 arc, or
        G451 / DISC=100 at the intersection of ``a``'s and ``b``'s offsets (an
        activation move's offset is the line through ``A`` along it)."""
        if r <= POINT_EPS:
            return Joint(A, B)
        mode, disc, blk = self._corner_modes(a, b)
        turned = 180.0 if reversal else math.degrees(abs(turn(t_in, t_out).theta))
        intersect = (mode == "G451" and turned < self.corner_limit) or (
            mode == "G450" and disc >= DISC_INTERSECTION)
        if mode == "G450" and DISC_CIRCLE < disc < DISC_INTERSECTION:
            raise _err(blk, f"DISC={disc:g}: ccopt reproduces DISC=0 (the transition circle) "
                            "and DISC=100 (the intersection) only: the manuals give no curve "
                            "between them")
        if intersect and not reversal:
            hits = carrier_intersections(a.carrier(True, k, r), b.carrier(False, k, r))
            x = decisions.nearest_root(hits, A, B)
            if x is not None:
                return Joint(x, x)
            if decisions.SIEMENS_INTERSECTION_MISSING == "next-move":
                return Joint(A, A)
        if mode == "G451" and DISC_CIRCLE < disc < DISC_INTERSECTION:
            raise _err(blk, f"DISC={disc:g} with G451's fallback to G450: ccopt reproduces "
                            "DISC=0 and DISC=100 only")
        sweep = reversal_sweep(k) if reversal else None
        return Joint(A, B, [corner_arc(P, r, t_in, t_out, k, sweep)])

    def full_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        P = a.end
        ti, tj = a.t_end, b.t_start
        A = a.offset_point(True, k, r)
        B = b.offset_point(False, k, r)
        kind = classify(k, turn(ti, tj))
        if kind is Corner.REVERSAL and not decisions.SIEMENS_REVERSAL_IS_OUTSIDE:
            kind = Corner.INSIDE
        if kind is Corner.TANGENT:
            return Joint(A, A)
        if kind is Corner.INSIDE:
            hits = carrier_intersections(a.carrier(True, k, r), b.carrier(False, k, r))
            x = decisions.nearest_root(hits, A, B)
            return Joint(A, A) if x is None else Joint(x, x)
        return self.outside(a, b, P, A, B, ti, tj, k, r, kind is Corner.REVERSAL)

    def lead_in_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the activation move, ``b`` the first compensated move."""
        B = b.offset_point(False, k, r)
        if self.smooth(a.block, True) is not None:
            return Joint(B, B)          # the SAR sub-moves end at B (_emit_move)
        P = a.end
        ti, tj = a.t_end, b.t_start
        kind = classify(k, turn(ti, tj))
        if self._approach_mode(a.block) == "NORM" or kind in (Corner.INSIDE, Corner.TANGENT):
            return Joint(B, B)
        A = a.offset_point(True, k, r)
        return self.outside(a, b, P, A, B, ti, tj, k, r, kind is Corner.REVERSAL)

    def lead_out_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the last compensated move, ``b`` the G40 move."""
        A = a.offset_point(True, k, r)
        if self.smooth(b.block, False) is not None:
            return Joint(A, A)          # the SAR sub-moves start at A (_emit_move)
        P = a.end
        ti, tj = a.t_end, b.t_start
        kind = classify(k, turn(ti, tj))
        if self._approach_mode(b.block) == "NORM" or kind in (Corner.INSIDE, Corner.TANGENT):
            return Joint(A, A)
        B = b.offset_point(False, k, r)
        joint = self.outside(a, b, P, A, B, ti, tj, k, r, kind is Corner.REVERSAL)
        if not joint.corner:
            # G451: the intersection with the G40 move's offset line; the move
            # then runs from there to its programmed end
            x = joint.end_prev
            return Joint(x, x)
        return joint

    # -- moves -------------------------------------------------------------------
    @staticmethod
    def _corner_block(els: list[Element], i: int) -> Block:
        """"The transition circle belongs to the next travel command" (PM
        2.10.3; the 808D manual: as far as the feedrate is concerned): the
        outgoing move's block, the G40 move's at a retraction."""
        return els[i + 1].block if i + 1 < len(els) else els[i].block

    def _emit_move(self, out: _FagorSegments, el: Element, cl: str, start, end) -> None:
        """The activation or G40 move of a SAR block as its sub-moves; every
        other move as the Fagor engine makes it."""
        if cl in (LEAD_IN, LEAD_OUT):
            sar = self.smooth(el.block, cl == LEAD_IN)
            if sar is not None:
                for seg in sar_pieces(el, cl == LEAD_IN, sar, self._sar_contour, start, end):
                    out.segs.append(seg)
                return
        super()._emit_move(out, el, cl, start, end)

    def _joints(self, els: list[Element], classes: list[str]):
        # the contour's tangent and side at each SAR block, for sar_pieces
        self._sar_contour = {}
        for i, cl in enumerate(classes):
            if cl == LEAD_IN and i + 1 < len(els):
                nxt = els[i + 1]
                self._sar_contour[id(els[i])] = (nxt.t_start, nxt.k, nxt.r)
            elif cl == LEAD_OUT and i > 0:
                prev = els[i - 1]
                self._sar_contour[id(els[i])] = (prev.t_end, prev.k, prev.r)
        return super()._joints(els, classes)
