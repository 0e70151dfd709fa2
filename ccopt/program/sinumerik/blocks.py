"""Executing an ordinary SINUMERIK block on the G-code core.

The block's SINUMERIK words are applied here — the modes of tool radius
compensation (Programming Manual Fundamentals 6FC5398-2EP40, section 2.10:
``G40``-``G42`` with ``T``/``D``, ``OFFN``, ``NORM``/``KONT``,
``G450``/``G451``/``DISC``, ``CDON``/``CDOF``, smooth approach and retraction
``G140``-``G348`` with ``DISR``/``DISCL``/``FAD``), ``AC``/``IC`` values and
the circle forms (:mod:`.arcs`) — and what remains is ISO G-code the core
executes (:func:`~ccopt.program.gcode.execute.execute_words`): the same
moves, units, feeds, coordinate systems and machine words as a G-code
program. The modes travel on each block as :class:`~ccopt.program.model.SiemensModes`.
"""
from __future__ import annotations

from dataclasses import replace

from ccopt.program.expr import ExprError
from ccopt.program.gcode.codes import G_GROUPS, Words
from ccopt.program.gcode.coordinates import to_machine, to_work, work_offset
from ccopt.program.gcode.execute import execute_words
from ccopt.program.gcode.state import ProgramEnd
from ccopt.program.gcode.units import feed_factor, input_factor
from ccopt.program.model import PLANE_AXES, SmoothApproach
from ccopt.program.sinumerik import angle, arcs, corners, cycles, frames, polar
from ccopt.program.sinumerik.calls import passes_of
from ccopt.program.sinumerik.lexer import Line
from ccopt.program.sinumerik.state import SinumerikRun
from ccopt.program.sinumerik.values import whole
from ccopt.program.sinumerik.words import BlockWords, read_block

_PLANE_CODES = {170: "XY", 180: "ZX", 190: "YZ"}
#: ``DISC`` runs from 0 (transition circle) to 100 (intersection).
DISC_RANGE = (0.0, 100.0)


def exec_block(run: SinumerikRun, line: Line) -> tuple[str, int, int] | None:
    """Read and execute one ordinary block; a subprogram call is not
    executed here but returned: ``(name, passes, col)``."""
    state = run.state
    bw = read_block(run, line)
    for code, col in bw.ignored:
        run.ignored.setdefault(code, state.where(state.line_no)[1])
    first_new = len(state.blocks)
    angle.check_between(run, bw)
    if bw.call is not None or bw.passes is not None:
        corners.after_block(run, {}, first_new)
        return _call(bw)
    if bw.frame is not None:
        frames.frame_block(run, bw)
    elif bw.pole is not None:
        polar.pole_block(run, bw)
    elif bw.cycle is not None or bw.mcall is not None:
        _cycle_block(run, bw)
    if bw.frame is not None or bw.pole is not None or bw.cycle is not None \
            or bw.mcall is not None or bw.empty:
        corners.after_block(run, {}, first_new)
        return None
    bw = _pending_approach(run, bw)
    if bw is None:
        return None
    here = state.line_no
    for block, line_no in angle.contour_definition(run, bw):
        state.line_no = line_no
        _run_words(run, block)
    state.line_no = here
    return None


def _run_words(run: SinumerikRun, bw: BlockWords) -> None:
    """Execute the sorted words of one ordinary block on the G-code core."""
    state = run.state
    first_new = len(state.blocks)
    frames.check_block(run, bw)
    _modes(run, bw)
    _tool(run, bw)
    _compensation(run, bw)
    corners.read_modal(run, bw.values)
    letters = _core_letters(run, bw)
    g = list(bw.g)
    angle.angle_line(run, bw, letters, g)
    polar.polar_move(run, bw, letters, g)
    _circle_forms(run, bw, letters, g)
    sar = _smooth_approach(run, bw, letters, g)
    try:
        execute_words(state, Words(g=[(t / 10.0, c) for t, c in g], m=bw.m, letters=letters,
                                   first=bw.first))
    except ProgramEnd:   # M2/M30 end the program after the block's move: its corner counts
        corners.after_block(run, bw.values, first_new)
        raise
    corners.after_block(run, bw.values, first_new)
    if run.mcall is not None and any(b.motion.is_move for b in state.blocks[first_new:]):
        corners.interrupt(run, "a drilling cycle (MCALL) follows")
        cycles.run_cycle(run, run.mcall)
    if sar:
        _set_modes(run, replace(run.modes, sar=None))
    if bw.end:
        raise ProgramEnd()


def _cycle_block(run: SinumerikRun, bw: BlockWords) -> None:
    """A drilling cycle called once, or ``MCALL`` (with a cycle: modal, alone:
    off); in a block of its own (:mod:`.cycles`)."""
    if not replace(bw, cycle=None, mcall=None, ignored=[]).empty:
        what = "MCALL" if bw.mcall is not None else bw.cycle.name
        raise ExprError(f"{what} stands in a block of its own (move to the position in the "
                        "block before)", bw.first)
    if bw.mcall is not None:
        run.mcall = bw.cycle
        return
    corners.interrupt(run, "a drilling cycle follows")
    cycles.run_cycle(run, bw.cycle)


def _call(bw: BlockWords) -> tuple[str, int, int]:
    """A call block: the subprogram and its passes ``P``, nothing else."""
    if bw.call is None:
        raise ExprError("P (the number of passes) needs a subprogram call in its block",
                        bw.passes[1])
    name, col = bw.call
    others = replace(bw, call=None, passes=None, first=bw.first)
    if not others.empty:
        raise ExprError(f"a subprogram call ({name}) takes its block with P only: put the "
                        "other words on a block of their own", col)
    return name, passes_of(None if bw.passes is None else bw.passes[0], col), col


def _set_modes(run: SinumerikRun, modes) -> None:
    if modes != run.modes:
        run.modes = modes
        run.state.siemens = modes
        run.state.modal_changed()


def _modes(run: SinumerikRun, bw: BlockWords) -> None:
    """G450/G451, DISC, NORM/KONT, CDON/CDOF and the modal SAR settings."""
    modes = run.modes
    if bw.corner is not None:
        modes = replace(modes, corner=f"G{bw.corner[0]}")
    if "DISC" in bw.values:
        value, mode, col = bw.values["DISC"]
        if mode is not None or not DISC_RANGE[0] <= value <= DISC_RANGE[1]:
            raise ExprError(f"DISC={value:g}: DISC runs from 0 to 100", col)
        modes = replace(modes, disc=value)
    if bw.approach is not None:
        modes = replace(modes, approach=bw.approach[0])
    if bw.bottleneck is not None:
        modes = replace(modes, bottleneck="CDOF" if bw.bottleneck[0] == "CDOF2"
                        else bw.bottleneck[0])
    _set_modes(run, modes)
    if bw.sar_direction is not None:
        run.sar_direction = f"G{bw.sar_direction[0]}"
    if bw.sar_infeed is not None:
        run.sar_infeed = f"G{bw.sar_infeed[0]}"
    _sar_values(run, bw)


def _sar_values(run: SinumerikRun, bw: BlockWords) -> None:
    state = run.state
    factor = input_factor(state)
    if "DISR" in bw.values:
        value, mode, col = bw.values["DISR"]
        if mode is not None or value < 0:
            raise ExprError(f"DISR={value:g}: DISR is a distance >= 0", col)
        run.disr = value * factor
    if "DISCL" in bw.values:
        value, mode, col = bw.values["DISCL"]
        if mode == "AC":
            w = PLANE_AXES[state.plane][2]
            run.discl, run.discl_abs = None, value * factor + work_offset(state)[w]
        elif mode is None:
            run.discl, run.discl_abs = value * factor, None
        else:
            raise ExprError(f"DISCL={mode}(..): ccopt reads DISCL=value and DISCL=AC(value)",
                            col)
    if "FAD" in bw.values:
        value, mode, col = bw.values["FAD"]
        if mode not in (None, "PM") or value <= 0:
            raise ExprError("FAD is a feed > 0 in units per minute (FAD=value or FAD=PM(..); "
                            "ccopt does not read feed per revolution)", col)
        run.fad = value * feed_factor(state) / 60.0
    if "OFFN" in bw.values:
        value, mode, col = bw.values["OFFN"]
        if mode is not None:
            raise ExprError("OFFN takes a value", col)
        run.offn = value * factor


def _tool(run: SinumerikRun, bw: BlockWords) -> None:
    """``T`` selects the tool, ``D`` its cutting edge; the radius in force is
    recomputed (the core records ``T`` among the machine words). A tool
    named ``T="name"`` has no number: its radius comes from ``--radius``."""
    if bw.tool_name is not None:
        run.tool = None
        run.tool_named = True
    if "T" in bw.letters:
        run.tool_named = False
        value, col = bw.letters["T"]
        run.tool = whole(value, col)
    if bw.edge is not None:
        value, col = bw.edge
        run.edge = whole(value, col)
        if run.edge < 0:
            raise ExprError(f"D{run.edge}: the cutting edge number must be >= 0", col)
    if "T" in bw.letters or bw.tool_name or bw.edge is not None or "OFFN" in bw.values:
        _set_radius(run)


def _set_radius(run: SinumerikRun) -> None:
    """The compensation radius: the edge's ``$TC_DP6`` radius, else half the
    tool table's diameter of tool ``T``, plus ``OFFN``; ``D0`` is radius 0;
    ``None`` when neither gives one (then ``--radius`` must)."""
    state = run.state
    radius = None
    if run.edge == 0:
        radius = 0.0        # D0: no compensation (OFFN is not added)
    elif run.tool_named:
        radius = None       # T="name": no tool data ccopt knows
    else:
        edge = 1 if run.edge is None else run.edge
        key = (run.tool if run.tool is not None else 0, edge)
        if key in run.variables.tool_radius:
            radius = run.variables.tool_radius[key]
        elif run.tool is not None and state.tool_table is not None \
                and run.tool in state.tool_table:
            radius = abs(state.tool_table[run.tool]) / 2.0
    if radius is not None and run.edge != 0:
        radius += run.offn
        if radius < 0:
            raise ExprError(f"the compensation radius (tool radius plus OFFN) is {radius:g}: "
                            "it must not be negative", 0)
    if (radius, run.tool) != (state.radius, state.tool):
        state.radius, state.tool = radius, run.tool
        state.modal_changed()


def _compensation(run: SinumerikRun, bw: BlockWords) -> None:
    """``G40``/``G41``/``G42``, after a plane change on the same block."""
    if bw.comp is None:
        return
    state = run.state
    code, col = bw.comp
    for i, (tenths, _) in enumerate(bw.g):
        if tenths in _PLANE_CODES and _PLANE_CODES[tenths] != state.plane:
            if state.side != 0 and code != 40:
                raise ExprError("cannot change planes with tool radius compensation on: "
                                "program G40 first", bw.g[i][1])
            if code != 40:
                state.plane = _PLANE_CODES[tenths]
    side = {40: 0, 41: 1, 42: -1}[code]
    if side != 0:
        _set_radius(run)
    if side != state.side:
        state.side = side
        state.modal_changed()


def _core_letters(run: SinumerikRun, bw: BlockWords) -> dict:
    """The block's words as the core's letters: axes and centres with
    ``AC``/``IC`` resolved in the distance mode of the block, ``CR`` as
    ``R``, ``TURN`` as ``P``, a dwell's ``F`` as ``P``."""
    state = run.state
    letters = dict(bw.letters)
    letters.pop("T", None)
    if "T" in bw.letters:
        letters["T"] = bw.letters["T"]
    incremental = state.incremental
    for t, _ in bw.g:
        if t in (900, 910):
            incremental = t == 910
    modal = any(m is not None for _, m, _ in list(bw.axes.values()) + list(bw.centre.values()))
    if modal and input_factor(state) != 1.0:
        raise ExprError("AC(..)/IC(..) in other units than the program's first (G70/G71 "
                        "changed): not read by ccopt", bw.first)
    work = to_work(state, state.pos)
    for a, (value, mode, col) in bw.axes.items():
        k = "XYZ".find(a)
        if mode is not None and k < 0:
            raise ExprError(f"{a}={mode}(..): ccopt reads AC/IC on X Y Z only", col)
        if mode == "AC" and incremental:
            value -= work[k]
        elif mode == "IC" and not incremental:
            value += work[k]
        letters[a] = (value, col)
    for a, (value, mode, col) in bw.centre.items():
        if mode == "AC":      # the offset from the start along the work axes
            value -= work["IJK".index(a)]
        letters[a] = (value, col)
    for name, letter in (("CR", "R"), ("TURN", "P")):
        if name in bw.values:
            value, mode, col = bw.values[name]
            letters[letter] = (value + 1.0 if name == "TURN" else value, col)
    if bw.dwell and "F" in letters:
        letters["P"] = letters.pop("F")
    return letters


def _circle_forms(run: SinumerikRun, bw: BlockWords, letters: dict, g: list) -> None:
    """``CIP``, ``CT`` (modal, in the motion group with G0-G3) and ``AR=``."""
    state = run.state
    motion_g = [t for t, _ in g if t in (0, 10, 20, 30)]
    if motion_g:
        run.motion = None
    if bw.motion is not None:
        run.motion = bw.motion[0]
    moves = any(a in letters for a in "XYZ")
    special = run.motion is not None or "AR" in bw.values or bw.middle
    if special and input_factor(state) != 1.0:
        raise ExprError("CIP, CT and AR= in other units than the program's first (G70/G71 "
                        "changed) are not read by ccopt", bw.first)
    col = bw.motion[1] if bw.motion else bw.first
    if run.motion == "CIP" and (moves or bw.middle):
        motion = arcs.cip(state, letters, _middle(run, bw, col), col)
        g[:] = [(t, c) for t, c in g if t not in (0, 10, 20, 30)] + [(motion, col)]
    elif run.motion == "CT" and moves:
        motion = arcs.ct(state, letters, col)
        g[:] = [(t, c) for t, c in g if t not in (0, 10, 20, 30)] + [
            (10 if motion is None else motion, col)]
    elif bw.middle:
        raise ExprError("I1 J1 K1 (an intermediate point) need CIP", next(
            iter(bw.middle.values()))[2])
    if "AR" in bw.values:
        value, mode, acol = bw.values["AR"]
        motion = next((t for t in motion_g if t in (20, 30)), None)
        if motion is None and state.motion_mode in (20, 30) and not motion_g:
            motion = state.motion_mode
        if motion is None or mode is not None or "R" in letters:
            raise ExprError("AR= needs G2 or G3 and either the centre (I J K) or the end "
                            "point (not CR=)", acol)
        wu_wv = [w for w in "IJK" if w in letters]
        if wu_wv and moves:
            raise ExprError("AR= with both the centre and the end point: give one of them",
                            acol)
        arcs.opening_angle(state, letters, motion, value, bool(wu_wv), acol)


def _middle(run: SinumerikRun, bw: BlockWords, col: int):
    """The CIP intermediate point (machine coordinates): ``I1 J1 K1``
    absolute in G90, from the start in G91 (or by AC/IC)."""
    state = run.state
    if not bw.middle:
        raise ExprError("CIP needs the intermediate point I1= J1= K1=", col)
    here = to_work(state, state.pos)
    point = list(here)
    for letter, (value, mode, _) in bw.middle.items():
        k = "IJK".index(letter)
        relative = mode == "IC" or (mode is None and state.incremental)
        point[k] = here[k] + value if relative else value
    return to_machine(state, point)


def _smooth_approach(run: SinumerikRun, bw: BlockWords, letters: dict, g: list) -> bool:
    """A SAR block: the modes of this block carry its :class:`SmoothApproach`.
    ccopt reads an approach on the block that switches compensation on and a
    retraction on the block that switches it off, each moving in the plane
    with G0/G1 (the contour's start or the retraction's end written there)."""
    if bw.sar is None:
        return False
    state = run.state
    kind, col = bw.sar
    approach = kind in (147, 247, 347)
    if approach and (bw.comp is None or bw.comp[0] == 40):
        raise ExprError(f"G{kind}: ccopt reads a smooth approach on the block that switches "
                        "compensation on (G41/G42 in the same block)", col)
    if not approach and (bw.comp is None or bw.comp[0] != 40):
        raise ExprError(f"G{kind}: ccopt reads a smooth retraction on the block that switches "
                        "compensation off (G40 in the same block)", col)
    iu, iv, _ = PLANE_AXES[state.plane]
    if not any("XYZ"[k] in letters for k in (iu, iv)):
        raise ExprError(f"G{kind}: write the {'contour start' if approach else 'end point'} "
                        "in this block (ccopt does not take it from a later block)", col)
    mode = [t for t, _ in g if t in (0, 10, 20, 30)]
    if (mode[-1] if mode else state.motion_mode) in (20, 30) or run.motion is not None:
        raise ExprError(f"G{kind} moves with G0 or G1 (not a circle)", col)
    disr = run.disr if run.disr is not None else 0.0
    if kind in (247, 248, 347, 348) and disr <= 0:
        raise ExprError(f"G{kind} needs DISR > 0, the radius of the tool-centre arc", col)
    before = state.motion_mode
    _, feed = _feeds(run, bw)
    infeed = None if before in (None, 0) else (state.feed / 60.0 if state.feed else feed)
    sar = SmoothApproach(kind=f"G{kind}", direction=run.sar_direction, infeed=run.sar_infeed,
                         disr=disr, discl=run.discl, discl_abs=run.discl_abs, fad=run.fad,
                         feed=feed, infeed_feed=infeed)
    _set_modes(run, replace(run.modes, sar=sar))
    return True


def _feeds(run: SinumerikRun, bw: BlockWords) -> tuple[float | None, float | None]:
    """The feed in force before the block and the block's own (its ``F`` or
    the modal one), in program units per second (``None``: no feed set)."""
    state = run.state
    before = state.feed / 60.0 if state.feed else None
    if "F" in bw.letters and state.feed_mode == "per_minute":
        return before, bw.letters["F"][0] * feed_factor(state) / 60.0
    return before, before


def _in_plane_words(state, bw: BlockWords) -> bool:
    plane = state.plane
    for tenths, _ in bw.g:
        plane = _PLANE_CODES.get(tenths, plane)
    iu, iv, _ = PLANE_AXES[plane]
    return any("XYZ"[k] in bw.axes for k in (iu, iv))


def _pending_approach(run: SinumerikRun, bw: BlockWords) -> BlockWords | None:
    """A smooth approach whose block writes no end point in the plane takes it
    from the next block that does (PM 2.10.4.1, "Programming of end point P4
    for approach"); the blocks between may not move. The two blocks are
    executed as one, located at the second. ``None``: nothing to execute now."""
    state = run.state
    pending = run.pending_sar
    if pending is None:
        if bw.sar is not None and bw.sar[0] in (147, 247, 347) \
                and not _in_plane_words(state, bw):
            run.pending_sar, run.pending_line = bw, state.line_no
            return None
        return bw
    if not _in_plane_words(state, bw):
        if bw.axes or bw.sar is not None or bw.comp is not None:
            col = next(iter(bw.axes.values()))[2] if bw.axes else bw.first
            raise ExprError("between a smooth approach block and the block that gives its end "
                            "point nothing may move or switch compensation", col)
        return bw
    run.pending_sar = None
    groups = {G_GROUPS.get(t) for t, _ in bw.g}
    merged = replace(pending, g=[(t, c) for t, c in pending.g if G_GROUPS.get(t) not in groups]
                     + bw.g, m=pending.m + bw.m, first=bw.first,
                     letters={**pending.letters, **bw.letters},
                     axes={**pending.axes, **bw.axes}, values={**pending.values, **bw.values})
    for f in ("corner", "approach", "bottleneck", "motion", "edge", "sar_direction",
              "sar_infeed"):
        if getattr(bw, f) is not None:
            setattr(merged, f, getattr(bw, f))
    merged.end = bw.end
    return merged
