"""Chamfers and roundings inserted at contour corners: ``CHF``, ``CHR``,
``RND``, ``RNDM``, ``FRC``, ``FRCM`` (Programming Manual Fundamentals
6FC5398-2EP40, "Chamfer, rounding (CHF, CHR, RND, RNDM, FRC, FRCM)").

The word stands in the block leading to the corner; the element is inserted
after that block, in the plane of ``G17``-``G19``, before the next block that
moves in the plane:

- ``RND=r``: the arc of radius ``r`` tangent to both elements (lines and
  arcs in any combination); ``RNDM=r`` the same at every following corner
  until ``RNDM=0``.
- ``CHR=w``: the straight chamfer whose sides along both elements are ``w``
  ("width in the direction of motion"); ``CHF=h``: the chamfer of length
  ``h``, i.e. ``w = h / (2 cos(phi/2))`` with ``phi`` the corner's turning
  angle (the manual's ``CHF = 2 cos(alpha) CHR``, ``alpha = phi/2`` the angle
  between chamfer and element). Between two lines only in ccopt.
- The element runs at ``FRC`` (this corner) or ``FRCM`` (modal, ``0``: off),
  units per minute as ``F``; otherwise at the feed of the block leading away
  from the corner (the manual's default). A chamfer into a ``G0`` block is a
  rapid.

As the manual says, nothing is inserted where the plane changes or the next
move leaves the plane (moves along the plane's normal), nor after more than
three blocks without motion, nor at the program's end; a tangent transition
has no corner to round. Where the manual leaves the result open, ccopt refuses
with the place rather than guess: a value too large for an element (the
control reduces it by a rule the manual does not give), a rounding touching a
rapid, a dwell, a helix, a multi-turn arc, a smooth approach or retraction
block, or a block that switches compensation. Lengths are program units
(converted as ``X``..); feeds are stored in program units per second.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ccopt.program.expr import ExprError
from ccopt.program.gcode.units import feed_factor, input_factor
from ccopt.program.heidenhain.contour import (GeometryError, arc_sweep, chamfer, cross, dot,
                                              end_tangent, norm, rounding, start_tangent, sub)
from ccopt.program.model import PLANE_AXES, Block, Motion, Source
from ccopt.tolerances import POINT_EPS, TURN_EPS

#: The words of this module; one of ``CHF``/``CHR``/``RND`` a block.
CORNER_WORDS = ("CHF", "CHR", "RND")
MODAL_WORDS = ("RNDM", "FRCM")
FEED_WORDS = ("FRC",)
#: Blocks without motion in the plane allowed between the two elements.
MAX_EMPTY_BLOCKS = 3
#: ``Program.meta`` key: corner elements programmed and not inserted, with
#: the reason -> the first ``file:line`` where it happened.
NOT_INSERTED = "sinumerik_corners_not_inserted"


@dataclass
class PendingCorner:
    """A corner element waiting for the block leading away from the corner.

    ``kind``: ``"RND"``, ``"CHR"`` or ``"CHF"``; ``size`` program units;
    ``feed`` units per second or ``None`` (the next block's); ``index`` the
    leading block in ``state.blocks``; ``line``, ``col`` where the word (for
    ``RNDM``: the block) stands, 0-based; ``empty`` the blocks without motion
    seen since."""

    kind: str
    size: float
    feed: float | None
    index: int
    line: int
    col: int
    empty: int = 0


def read_modal(run, values: dict) -> None:
    """``RNDM``/``FRCM`` of a block: set the modal rounding and feed."""
    if "RNDM" in values:
        run.rndm = _size(run, "RNDM", values["RNDM"], zero_ok=True)
    if "FRCM" in values:
        value, mode, col = values["FRCM"]
        run.frcm = None if value == 0 and mode is None else _feed(run, "FRCM", values["FRCM"])


def after_block(run, values: dict, first_new: int) -> None:
    """After a block has run: insert a waiting element before the block's
    first move, and note the element this block asks for. ``first_new`` is
    the length of ``state.blocks`` before the block ran."""
    state = run.state
    new = state.blocks[first_new:]
    pending = run.corner
    if pending is not None:
        if not new:
            pending.empty += 1
            if pending.empty > MAX_EMPTY_BLOCKS:
                _drop(run, pending, "more than three blocks without motion in the plane")
                run.corner = None
        else:
            run.corner = None
            _insert(run, pending, first_new)
    wanted = sorted((w for w in CORNER_WORDS if w in values), key=lambda w: values[w][2])
    if len(wanted) > 1:
        raise ExprError(f"{wanted[0]} and {wanted[1]} on one block: one corner element a "
                        "block", values[wanted[1]][2])
    if not new:
        if wanted:
            raise ExprError(f"{wanted[0]} stands in the block that moves to the corner: this "
                            "block does not move", values[wanted[0]][2])
        return
    last = len(state.blocks) - 1
    if wanted:
        kind = wanted[0]
        size, col = _size(run, kind, values[kind]), values[kind][2]
    elif run.rndm > 0:
        kind, size, col = "RND", run.rndm, state.blocks[last].source.col - 1
    else:
        return
    feed = _feed(run, "FRC", values["FRC"]) if "FRC" in values else run.frcm
    if state.blocks[last].motion is Motion.DWELL:
        raise ExprError(f"{kind} on a dwell block (G4): the element goes after a move", col)
    run.corner = PendingCorner(kind, size, feed, last, state.line_no, col)


def interrupt(run, why: str) -> None:
    """Moves not of the program's blocks follow (a drilling cycle): a
    waiting element is not inserted."""
    if run.corner is not None:
        _drop(run, run.corner, why)
        run.corner = None


def at_end(run) -> None:
    """The program ended with an element waiting: none is inserted."""
    if run.corner is not None:
        _drop(run, run.corner, "no block follows the corner")
        run.corner = None


def _size(run, name: str, value_mode_col: tuple, zero_ok: bool = False) -> float:
    value, mode, col = value_mode_col
    if mode is not None:
        raise ExprError(f"{name} takes a value ({name}=2), not {mode}(..)", col)
    if not (value > 0 or zero_ok and value == 0) or not math.isfinite(value):
        raise ExprError(f"{name}={value:g}: the size must be > 0"
                        + (" (0 ends the modal rounding)" if zero_ok else ""), col)
    return value * input_factor(run.state)


def _feed(run, name: str, value_mode_col: tuple) -> float:
    value, mode, col = value_mode_col
    if mode is not None or not value > 0 or not math.isfinite(value):
        raise ExprError(f"{name}={value:g}: a feed > 0 in units per minute", col)
    if run.state.feed_mode != "per_minute":
        raise ExprError(f"{name} under G93/G95: ccopt reads chamfer and rounding feeds in "
                        "units per minute (G94) only", col)
    return value * feed_factor(run.state) / 60.0


def _drop(run, pending: PendingCorner, why: str) -> None:
    src = run.state.blocks[pending.index].source
    run.not_inserted.setdefault(f"{pending.kind}: {why}", f"{src.file}:{src.line}")


def _insert(run, pending: PendingCorner, at: int) -> None:
    """Put the element between ``blocks[pending.index]`` and ``blocks[at]``."""
    blocks = run.state.blocks
    a, b = blocks[pending.index], blocks[at]
    if pending.index != at - 1 or b.motion is Motion.DWELL:
        raise _error(run, pending, "a dwell between the corner's two moves is not read by "
                     "ccopt")
    if a.modal.plane != b.modal.plane:
        _drop(run, pending, "the plane changes at the corner")
        return
    if b.cycle is not None or not b.in_plane or _leaves_plane(b):
        _drop(run, pending, "the next move leaves the plane")
        return
    _check_pair(run, pending, a, b)
    pa, pb = _piece(a), _piece(b)
    t_in, t_out = end_tangent(pa), start_tangent(pb)
    if abs(cross(t_in, t_out)) <= TURN_EPS and dot(t_in, t_out) > 0:
        _drop(run, pending, "the transition is tangent (no corner)")
        return
    try:
        ta, element, tb = _element(pending, pa, pb, t_in, t_out)
    except GeometryError as exc:
        raise _error(run, pending, str(exc)) from None
    blocks[pending.index] = _trimmed(a, end=ta)
    blocks[at] = replace(_trimmed(b, start=tb), words=())
    blocks.insert(at, _element_block(pending, a, b, element))


def _check_pair(run, pending: PendingCorner, a: Block, b: Block) -> None:
    for blk in (a, b):
        siemens = blk.modal.siemens
        if siemens is not None and siemens.sar is not None:
            raise _error(run, pending, "at a smooth approach or retraction block (G147-G348) "
                         "is not read by ccopt")
        if blk.turns or _leaves_plane(blk):
            raise _error(run, pending, "at a helix or a multi-turn arc is not read by ccopt")
        if blk.motion.is_arc and blk.is_spiral():
            raise _error(run, pending, "at an arc whose end is off its circle")
    if a.modal.side != b.modal.side or a.modal.radius != b.modal.radius:
        raise _error(run, pending, "at a block that switches tool radius compensation is not "
                     "read by ccopt: put the element between two compensated moves")
    rapid = a.motion is Motion.RAPID or b.motion is Motion.RAPID
    if rapid and (pending.kind == "RND" or a.motion is not b.motion):
        raise _error(run, pending, "at a rapid (G0) move is not read by ccopt: round the "
                     "contour between feed moves (end a modal rounding with RNDM=0)")


def _error(run, pending: PendingCorner, why: str):
    """A located error at the word (or block) that asked for the element."""
    return run.state.error(f"{pending.kind}={pending.size:g}: {why}", pending.col,
                           pending.line)


def _leaves_plane(blk: Block) -> bool:
    w = PLANE_AXES[blk.modal.plane][2]
    return abs(blk.end[w] - blk.start[w]) > POINT_EPS


def _piece(blk: Block):
    s, e = blk.start_uv, blk.end_uv
    if not blk.motion.is_arc:
        return ("line", s, e)
    c = blk.center_uv
    return ("arc", s, e, c, arc_sweep(s, e, c, blk.motion is Motion.ARC_CCW))


def _element(pending: PendingCorner, pa, pb, t_in, t_out):
    """``(end of a, element piece, start of b)``, checked to lie on both."""
    if pending.kind == "RND":
        ta, element, tb = rounding(pa, pb, pending.size)
    else:
        if pa[0] != "line" or pb[0] != "line":
            raise GeometryError("a chamfer between a line and an arc is not read by ccopt "
                                "(between two lines it is): program it as its own line")
        width = pending.size
        if pending.kind == "CHF":
            half_turn = 0.5 * math.atan2(abs(cross(t_in, t_out)), dot(t_in, t_out))
            width = pending.size / (2.0 * math.cos(half_turn))
        ta, element, tb = chamfer(pa, pb, width)
    if not (_on_piece(pa, ta) and _on_piece(pb, tb)):
        raise GeometryError("too large for the elements at the corner (the control reduces "
                            "it by its own rule; ccopt does not guess it): give a smaller "
                            "value")
    return ta, element, tb


def _on_piece(piece, p) -> bool:
    """``p`` (on the carrier of ``piece``) lies within it, ends included."""
    s, e = piece[1], piece[2]
    if piece[0] == "line":
        d = sub(e, s)
        along = dot(sub(p, s), d) / max(norm(d), POINT_EPS)
        return -POINT_EPS <= along <= norm(d) + POINT_EPS
    c, sweep = piece[3], piece[4]
    part = arc_sweep(s, p, c, sweep > 0, False)
    rho = norm(sub(s, c))
    return abs(part) <= abs(sweep) + POINT_EPS / max(rho, 1.0) or norm(sub(p, s)) <= POINT_EPS


def _xyz(blk: Block, uv, w_from) -> tuple[float, float, float]:
    i, j, k = PLANE_AXES[blk.modal.plane]
    out = [0.0, 0.0, 0.0]
    out[i], out[j], out[k] = uv[0], uv[1], w_from[k]
    return (out[0], out[1], out[2])


def _trimmed(blk: Block, start=None, end=None) -> Block:
    if start is not None:
        blk = replace(blk, start=_xyz(blk, start, blk.start))
    if end is not None:
        blk = replace(blk, end=_xyz(blk, end, blk.end))
    return blk


def _element_block(pending: PendingCorner, a: Block, b: Block, piece) -> Block:
    """The inserted element: written where ``a`` stands (the word's column),
    with ``b``'s modes, machine words and (unless ``FRC``/``FRCM``) feed."""
    if piece[0] == "line":
        motion = Motion.RAPID if b.motion is Motion.RAPID else Motion.LINE
        center = None
    else:
        motion = Motion.ARC_CCW if piece[4] > 0 else Motion.ARC_CW
        center = _xyz(a, piece[3], a.end)
    feed = None if motion is Motion.RAPID else (pending.feed if pending.feed is not None
                                                else b.feed)
    source = Source(a.source.file, a.source.line, pending.col + 1)
    return Block(source=source, motion=motion, start=_xyz(a, piece[1], a.end),
                 end=_xyz(a, piece[2], a.end), modal=b.modal, center=center, feed=feed,
                 words=b.words, frame=b.frame, axes=a.axes)
