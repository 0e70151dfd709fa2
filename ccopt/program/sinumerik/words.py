"""The words of an ordinary SINUMERIK block, read and sorted
(Programming Manual Fundamentals: the G groups, ``T``/``D``, ``AC``/``IC``,
``CR=``, ``AR=``, ``CIP``/``CT``, ``TURN=``; the tool radius compensation
words of section 2.10; arithmetic parameters and ``DEF``).

:func:`read_block` reads a block's words left to right: settings of
parameters and variables (``R1=..``, ``$TC_DP6[1,1]=..``, ``DEF REAL A``)
take effect at once, in order; every other word is sorted into a
:class:`BlockWords` for :mod:`.blocks` to execute. A word ccopt does not
read is refused where it stands.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from ccopt.program.expr import ExprError
from ccopt.program.sinumerik import cycles
from ccopt.program.sinumerik.calls import find_sub
from ccopt.program.sinumerik.lexer import Line, Word, next_name, read_word, skip_blanks, \
    string_argument
from ccopt.program.sinumerik.state import SinumerikRun
from ccopt.program.sinumerik.values import (RADIUS_PARAMETER, TOOL_PARAMETERS, check_r,
                                            whole)

#: G-codes the ISO core executes with the same meaning (G-number -> the
#: core's code in tenths).
CORE_G = {0: 0, 1: 10, 2: 20, 3: 30, 4: 40, 17: 170, 18: 180, 19: 190, 53: 530,
          54: 540, 55: 550, 56: 560, 57: 570, 90: 900, 91: 910, 93: 930, 94: 940,
          95: 950, 70: 200, 700: 200, 71: 210, 710: 210}
#: Continuous-path and exact-stop modes: no effect on the programmed path's
#: geometry in ccopt (its feed planner plans the path itself); read and noted.
PATH_MODES = {9, 60, 64, 641, 642, 643, 644, 645, 601, 602, 603}
#: G460: the approach and retraction blocks with collision monitoring "as
#: before" (PM 8.11.2, W1 2.4), the control's reset state; ccopt applies no
#: collision (bottleneck) detection, as with CDON, so it is read and noted.
#: G461/G462 change the path only where that monitoring finds no
#: intersection with a preceding block, which ccopt does not model: refused.
RETRACT_STRATEGY_G = {460}
UNMODELLED_RETRACT_G = {461, 462}
COMP_G = {40, 41, 42}
CORNER_G = {450, 451}
SAR_KIND_G = {147, 148, 247, 248, 347, 348}
SAR_DIRECTION_G = {140, 141, 142, 143}
SAR_INFEED_G = {340, 341}
APPROACH_WORDS = {"NORM", "KONT", "KONTT", "KONTC"}
BOTTLENECK_WORDS = {"CDON", "CDOF", "CDOF2"}
VALUE_WORDS = {"CR", "AR", "TURN", "DISR", "DISCL", "FAD", "DISC", "OFFN", "RPL", "AP", "RP",
               "ANG"}
POLE_G = {110, 111, 112}
#: Chamfer and rounding words (:mod:`.corners`): values as written.
CORNER_VALUES = {"CHF", "CHR", "RND", "RNDM", "FRC", "FRCM"}
AXES = "XYZABC"
#: Keywords that set the control's dynamics, look-ahead or feed reference and
#: leave the programmed path as it is in ccopt (read and noted, like G64):
#: acceleration profiles, compressors, feed forward, path feed modes.
NOTED_WORDS = {"SOFT", "BRISK", "FFWON", "FFWOF", "COMPCAD", "COMPCURV", "COMPOF", "UPATH",
               "SPATH", "FNORM", "DYNNORM", "DYNPOS", "DYNROUGH", "DYNSEMIFIN", "DYNFINISH",
               "CFC", "CFTCP", "CFIN", "STOPRE"}
#: Valued settings of the same kind (smoothing distances and tolerances).
NOTED_VALUES = {"ADIS", "ADISPOS", "CTOL", "OTOL", "ATOL"}
#: Calls with arguments that do not move: the high-speed settings cycle and
#: the simulation blank (read and noted).
NOTED_CALLS = {"CYCLE832", "WORKPIECE"}
DEF_TYPES = {"REAL", "INT", "BOOL"}


@dataclass
class BlockWords:
    """A block's words, sorted. Values are as written (program units);
    ``axes``/``centre``/``middle``: letter -> ``(value, "AC"|"IC"|None, col)``."""

    first: int
    g: list = field(default_factory=list)        # (core tenths, col)
    m: list = field(default_factory=list)        # (value, col)
    letters: dict = field(default_factory=dict)  # F S T -> (value, col)
    axes: dict = field(default_factory=dict)
    centre: dict = field(default_factory=dict)
    middle: dict = field(default_factory=dict)
    values: dict = field(default_factory=dict)   # CR AR TURN DISR ... -> (value, mode, col)
    comp: tuple | None = None                    # (40|41|42, col)
    corner: tuple | None = None
    sar: tuple | None = None
    sar_direction: tuple | None = None
    sar_infeed: tuple | None = None
    approach: tuple | None = None
    bottleneck: tuple | None = None
    motion: tuple | None = None                  # ("CIP"|"CT", col)
    edge: tuple | None = None                    # D: (value, col)
    dwell: bool = False
    end: bool = False                            # M17 or RET: end of the program
    call: tuple | None = None                    # (subprogram name, col)
    frame: tuple | None = None                   # (TRANS ATRANS ROT or AROT, col)
    pole: tuple | None = None                    # (110|111|112, col)
    cycle: object = None                         # a drilling cycle called (cycles.py)
    mcall: int | None = None                     # MCALL: its column
    tool_name: tuple | None = None               # T="name": (name, col)
    passes: tuple | None = None                  # P: (value, col)
    ignored: list = field(default_factory=list)  # (code, col) read and ignored

    @property
    def empty(self) -> bool:
        return not (self.g or self.m or self.letters or self.axes or self.centre or self.middle
                    or self.values or self.comp or self.corner or self.sar
                    or self.sar_direction or self.sar_infeed or self.approach
                    or self.bottleneck or self.motion or self.edge or self.end
                    or self.call or self.passes or self.frame or self.tool_name or self.pole
                    or self.cycle is not None or self.mcall is not None)


def read_block(run: SinumerikRun, line: Line) -> BlockWords:
    """Read the words of ``line`` (settings executed as they are read)."""
    code = line.code
    bw = BlockWords(first=line.start)
    p = line.start
    while True:
        p = skip_blanks(code, p)
        if p >= len(code):
            return bw
        word, p = read_word(code, p)
        p = _word(run, bw, word, code, p)


def _word(run: SinumerikRun, bw: BlockWords, w: Word, code: str, p: int) -> int:
    """Sort or execute one word; the position after it."""
    name = w.name
    if name == "G":
        _g(bw, _literal(w), w.col)
    elif name == "M":
        m = _literal(w)
        if m in (17.0,):
            bw.end = True
        else:
            bw.m.append((m, w.col))
    elif name in AXES and len(name) == 1 or name in "IJK" and len(name) == 1:
        value, mode, p = _value(run, w, code, p, ("AC", "IC"))
        target = bw.axes if name in AXES else bw.centre
        _once(target, name, w.col)
        target[name] = (value, mode, w.col)
    elif name in ("I1", "J1", "K1"):
        value, mode, p = _value(run, w, code, p, ("AC", "IC"))
        bw.middle[name[0]] = (value, mode, w.col)
    elif name == "T" and w.expr is not None and code.startswith('"', skip_blanks(code, w.expr)):
        q = skip_blanks(code, w.expr)
        end = code.find('"', q + 1)
        if end < 0:
            raise ExprError('T="name": the name has no closing quote', q)
        bw.tool_name = (code[q + 1:end], w.col)
        p = end + 1
    elif name in ("F", "S", "T"):
        value, _, p = _value(run, w, code, p, ())
        _once(bw.letters, name, w.col)
        bw.letters[name] = (value, w.col)
    elif name == "P":
        value, _, p = _value(run, w, code, p, ())
        bw.passes = (value, w.col)
    elif name == "D":
        value, _, p = _value(run, w, code, p, ())
        bw.edge = (value, w.col)
    elif name in VALUE_WORDS:
        value, mode, p = _value(run, w, code, p, ("AC", "IC", "PM", "PR"))
        bw.values[name] = (value, mode, w.col)
    elif name in CORNER_VALUES:
        value, mode, p = _value(run, w, code, p, ())
        _once(bw.values, name, w.col)
        bw.values[name] = (value, mode, w.col)
    else:
        return _other(run, bw, w, code, p)
    return p


def _other(run: SinumerikRun, bw: BlockWords, w: Word, code: str, p: int) -> int:
    name = w.name
    if name in APPROACH_WORDS:
        bw.approach = (name, w.col)
    elif name in BOTTLENECK_WORDS:
        bw.bottleneck = (name, w.col)
    elif name in ("CIP", "CT"):
        bw.motion = (name, w.col)
    elif name[0] == "R" and name[1:].isdigit() and w.expr is not None:
        n = int(name[1:])
        check_r(n, w.col)
        value, p = run.variables.evaluate(code, w.expr)
        run.variables.r[n] = value
    elif name == "R" and w.index is not None:
        n, _ = run.variables.evaluate(code, w.index + 1)
        n = whole(n, w.index)
        check_r(n, w.col)
        run.variables.r[n], p = run.variables.evaluate(code, w.expr)
    elif name.startswith("$TC_DP") and w.index is not None:
        p = _tool_data(run, w, code)
    elif name in run.variables.user and w.expr is not None:
        run.variables.user[name], p = run.variables.evaluate(code, w.expr)
    elif name == "DEF":
        return _define(run, code, p)
    elif name == "MSG":
        return string_argument(code, p)
    elif name == "RET":
        bw.end = True
    elif name in NOTED_WORDS and w.expr is None:
        bw.ignored.append((name, w.col))
    elif name in NOTED_VALUES and w.expr is not None:
        _, p = run.variables.evaluate(code, w.expr)
        bw.ignored.append((name, w.col))
    elif name in NOTED_CALLS and w.expr is None:
        bw.ignored.append((name, w.col))
        return string_argument(code, p)
    elif name in ("TRANS", "ATRANS", "ROT", "AROT") and w.expr is None:
        if bw.frame is not None:
            raise ExprError("one frame instruction (TRANS, ATRANS, ROT, AROT) a block", w.col)
        bw.frame = (name, w.col)
    elif name == "PROC":
        return _proc(code, p)
    elif name == "MCALL" and w.expr is None:
        bw.mcall = w.col
    elif cycles.is_cycle(name) and w.expr is None and w.index is None:
        if bw.cycle is not None:
            raise ExprError("one cycle call a block", w.col)
        bw.cycle, p = cycles.read_call(run, name, code, p, w.col)
    elif name == "L" and w.literal is not None:
        _call(bw, f"L{int(w.literal)}" if w.literal == int(w.literal) else "L?", w.col)
    elif w.expr is None and w.index is None and find_sub(run.state, name) is not None:
        _call(bw, name, w.col)
    else:
        raise ExprError(_unknown(name), w.col)
    return p


def _call(bw: BlockWords, name: str, col: int) -> None:
    if name == "L?" or bw.call is not None:
        raise ExprError("one subprogram call a block, L<whole number> or its name", col)
    bw.call = (name, col)


def _proc(code: str, p: int) -> int:
    """``PROC NAME``: a subprogram's head (read, nothing to do); parameters
    are refused."""
    name, q = next_name(code, skip_blanks(code, p))
    q = skip_blanks(code, q)
    if q < len(code) and code[q] == "(":
        raise ExprError(f"PROC {name}(...): subprograms with parameters are not read by "
                        "ccopt", q)
    return len(code)


def _unknown(name: str) -> str:
    if name in ("SCALE", "ASCALE", "MIRROR", "AMIRROR", "ROTS", "AROTS", "CROTS", "TRAORI",
                "CYCLE800"):
        return (f"{name}: scaling and mirroring frames, rotations in space and "
                "transformations are not read by ccopt (TRANS, ATRANS, ROT and AROT in G17 "
                "are): program the contour in the coordinates they give")
    return (f"{name} is not read by ccopt's SINUMERIK reader (G0-G3, CIP, CT, AR=, CR=, "
            "TURN=, G17-G19, G40-G42, G450/G451, NORM/KONT, SAR G140-G348, CHF/CHR/RND/"
            "RNDM, ANG, AP/RP with G110-G112, TRANS/ATRANS/ROT/AROT, R parameters and DEF "
            "variables, IF/WHILE/REPEAT/LOOP/FOR, GOTOF/GOTOB and subprogram calls "
            f"are): a command it does not know, or a call of a subprogram with no file "
            f"{name}.SPF beside the program")


def _once(target: dict, name: str, col: int) -> None:
    if name in target:
        raise ExprError(f"two {name} words in one block: keep one", col)


def _literal(w: Word) -> float:
    if w.literal is None:
        raise ExprError(f"{w.name} needs its number written directly, e.g. {w.name}1", w.col)
    return w.literal


def _g(bw: BlockWords, value: float, col: int) -> None:
    n = round(value)
    if abs(value - n) > 0 or n < 0:
        raise ExprError(f"G{value:g} is not a SINUMERIK G-code (they are whole numbers)", col)
    slots = {**{g: "comp" for g in COMP_G}, **{g: "corner" for g in CORNER_G},
             **{g: "sar" for g in SAR_KIND_G}, **{g: "sar_direction" for g in SAR_DIRECTION_G},
             **{g: "sar_infeed" for g in SAR_INFEED_G}, **{g: "pole" for g in POLE_G}}
    if n in slots:
        if getattr(bw, slots[n]) is not None:
            raise ExprError(f"G{n} and G{getattr(bw, slots[n])[0]} on one block belong to "
                            "the same group: keep one", col)
        setattr(bw, slots[n], (n, col))
    elif n in CORE_G:
        if n == 4:
            bw.dwell = True
        bw.g.append((CORE_G[n], col))
    elif n in PATH_MODES or n in RETRACT_STRATEGY_G:
        bw.ignored.append((f"G{n}", col))
    elif n in UNMODELLED_RETRACT_G:
        raise ExprError(f"G{n} is not read by ccopt's SINUMERIK reader: it changes the approach "
                        "or retraction only where the control's collision monitoring finds no "
                        "intersection with a preceding block, which ccopt does not model (G460, "
                        "the default, is read)", col)
    elif n == 500:
        bw.g.append((540, col))       # G500: no settable frame; see docs/sinumerik.md
    else:
        raise ExprError(f"G{n} is not read by ccopt's SINUMERIK reader", col)


def _value(run: SinumerikRun, w: Word, code: str, p: int,
           modes: tuple[str, ...]) -> tuple[float, str | None, int]:
    """A word's value: written directly, or after ``=`` an expression, or
    one of ``modes`` (``AC(..)``, ``IC(..)``, ``PM(..)``, ``PR(..)``)."""
    if w.literal is not None:
        return w.literal, None, p
    if w.expr is None:
        raise ExprError(f"{w.name} needs a value, e.g. {w.name}=10", w.col)
    q = skip_blanks(code, w.expr)
    name, r = next_name(code, q)
    if name in ("AC", "IC", "PM", "PR") and skip_blanks(code, r) < len(code) \
            and code[skip_blanks(code, r)] == "(":
        if name not in modes:
            raise ExprError(f"{name}(..) does not apply to {w.name}", q)
        value, end = run.variables.evaluate(code, skip_blanks(code, r))
        return value, name, end
    if code.startswith('"', q):
        raise ExprError(f"{w.name} with a name in quotes is not read by ccopt: give the "
                        "number", q)
    value, end = run.variables.evaluate(code, q)
    return value, None, end


def _tool_data(run: SinumerikRun, w: Word, code: str) -> int:
    """``$TC_DPn[t, d] = value``: ``n = 6`` is the radius, the others are kept out."""
    digits = w.name[len("$TC_DP"):]
    if not digits.isdigit() or not 1 <= int(digits) <= TOOL_PARAMETERS:
        raise ExprError(f"{w.name}: ccopt reads the tool data $TC_DP1 .. "
                        f"$TC_DP{TOOL_PARAMETERS}", w.col)
    key, _ = run.variables.tool_index(code, w.index)
    value, p = run.variables.evaluate(code, w.expr)
    if int(digits) == RADIUS_PARAMETER:
        run.variables.tool_radius[key] = value
    return p


def _define(run: SinumerikRun, code: str, p: int) -> int:
    """``DEF REAL|INT|BOOL NAME[=value][, NAME2 ...]``."""
    kind, p = next_name(code, skip_blanks(code, p))
    if kind not in DEF_TYPES:
        raise ExprError(f"DEF {kind or '?'}: ccopt reads DEF REAL, DEF INT and DEF BOOL", p)
    while True:
        q = skip_blanks(code, p)
        name, p = next_name(code, q)
        if not name:
            raise ExprError("DEF needs a variable name", q)
        if len(name) == 1 or name in VALUE_WORDS or name in CORNER_VALUES:
            raise ExprError(f"{name} is an address, not a variable name", q)
        value = 0.0
        p = skip_blanks(code, p)
        if p < len(code) and code[p] == "=":
            value, p = run.variables.evaluate(code, p + 1)
        run.variables.user[name] = float(int(value)) if kind == "INT" else value
        p = skip_blanks(code, p)
        if p >= len(code):
            return p
        if code[p] != ",":
            raise ExprError("expected ',' between the variables of DEF", p)
        p += 1
