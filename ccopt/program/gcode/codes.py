"""The words of an ordinary line (LinuxCNC ``read_items`` and the G/M code
checks of ``interp_check.cc``).

:func:`read_words` reads the words and ``#`` settings of a lexed line into
:class:`Words`; :func:`classify` checks its G- and M-codes against what ccopt
knows and their modal groups (two codes of one group on a line are an
error). G-codes are kept in tenths (``G41.1`` -> 411), with their column.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from ccopt.program.expr import ExprError
from ccopt.program.gcode.parameters import (is_ini_name, is_position_name, parameter_target,
                                             read_value)
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, Lexed, fmt, gname, skip_blanks
from ccopt.program.model import MAX_PROGRAM_COORDINATE, out_of_range

#: A G number within this of a tenth is that tenth (``G41.1`` read as 41.1
#: in floating point): the codes have one decimal at most.
_G_TENTHS_TOL = 1e-3
#: G numbers this large cannot be a G-code (and would overflow rounding).
_G_NUMBER_LIMIT = 1e6

# G-codes ccopt knows, in tenths (G41.1 -> 411), with their modal group.
G_GROUPS: dict[int, str] = {
    0: "motion", 10: "motion", 20: "motion", 30: "motion", 800: "motion",
    330: "motion",  # spindle-synchronised motion (execute._synchronised_feed)
    331: "motion",  # rigid tapping (cycles.rigid_tap)
    760: "motion",  # threading (threading.py)
    # canned cycles (cycles.py)
    730: "motion", 740: "motion", 810: "motion", 820: "motion", 830: "motion", 840: "motion",
    850: "motion", 860: "motion", 870: "motion", 880: "motion", 890: "motion",
    # lathe cycles (lathe_cycles.py)
    700: "motion", 710: "motion", 711: "motion", 712: "motion", 720: "motion", 721: "motion",
    722: "motion",
    980: "retract", 990: "retract",
    40: "dwell",
    170: "plane", 180: "plane", 190: "plane",
    200: "units", 210: "units",
    400: "comp", 410: "comp", 420: "comp", 411: "comp", 421: "comp",
    430: "length", 431: "length", 490: "length",
    540: "coord", 550: "coord", 560: "coord", 570: "coord", 580: "coord", 590: "coord",
    591: "coord", 592: "coord", 593: "coord",
    # non-modal codes that take the line's axis words (LinuxCNC group 0)
    100: "axis_setting", 520: "axis_setting", 920: "axis_setting", 921: "axis_setting",
    922: "axis_setting", 923: "axis_setting",
    280: "axis_setting", 281: "axis_setting", 300: "axis_setting", 301: "axis_setting",
    530: "machine_coords",
    610: "path", 611: "path", 640: "path",
    900: "distance", 910: "distance",
    70: "lathe_diameter", 80: "lathe_diameter",
    901: "arc_distance", 911: "arc_distance",
    930: "feed_mode", 940: "feed_mode", 950: "feed_mode",
    960: "spindle_mode", 970: "spindle_mode",
    1360: "corner", 1370: "corner",
    1380: "start_end", 1390: "start_end",
}
_KNOWN_G = ("G0 G1 G2 G3 G4 G7 G8 G33 G33.1 G10 G17 G18 G19 G20 G21 G40 G41 G42 G41.1 G42.1 G43 G43.1 G49 "
            "G28 G28.1 G30 G30.1 G52 G53 G54-G59.3 G61 G61.1 G64 G80 G90 G91 G90.1 G91.1 G92 G92.1 G92.2 G92.3 "
            "G70 G71 G71.1 G71.2 G72 G72.1 G72.2 G73 G74 G76 G81-G87 G89 G93 G94 G95 G96 G97 G98 G99 G136 "
            "G137 G138 G139")
_G_UNSUPPORTED_HINT: dict[int, str] = {
    **{t: "probing ends where the probe touches the part, which the program does not say; "
          "write the moves out" for t in (382, 383, 384, 385)},
    **{t: "splines (G5 cubic, G5.1 quadratic, G5.2/G5.3 NURBS): write them out as lines "
          "or arcs" for t in (50, 51, 52, 53)},
}
# M-code modal groups that may not appear twice on a line.
_M_GROUPS: dict[int, str] = {0: "stop", 1: "stop", 2: "stop", 30: "stop", 60: "stop",
                             6: "tool change", 3: "spindle", 4: "spindle", 5: "spindle",
                             7: "coolant", 8: "coolant", 9: "coolant"}
_M_LIMIT = 1000  # M-codes run from M0 to M999

_WORD_LETTERS = set("GMXYZIJKRFPDHTSQLEABCUVW@^")
# Words holding a length or a feed: bounded by MAX_PROGRAM_COORDINATE where they are written.
_BOUNDED_LETTERS = set("XYZIJKRFEABCUVW@^")


@dataclass(slots=True)
class Words:
    """The words of one line. ``g``/``m``: ``(value, col)`` in line order;
    ``letters``: other letter -> ``(value, col)``; after :func:`classify`,
    ``gcodes``: modal group -> ``(tenths, col)`` and ``mcodes`` the M numbers."""

    g: list = field(default_factory=list)
    m: list = field(default_factory=list)
    letters: dict = field(default_factory=dict)
    gcodes: dict = field(default_factory=dict)
    mcodes: list = field(default_factory=list)
    first: int | None = None
    classified: bool = False


#: One word written as a letter and a literal number, and the blanks after it:
#: the number as :data:`~ccopt.program.gcode.words._NUMBER` reads it (sign
#: directly before the digits, no blank or second point inside).
_LITERAL_WORD = re.compile(r"([A-Za-z])[ \t]*([+-]?(?:\d+\.?\d*|\.\d+))(?![.\d]|[ \t]+[.\d])"
                           r"[ \t]*")


def _literal_words(code: str, p: int, first: int | None) -> Words | None:
    """The words of a line written only as letters and literal numbers (most
    lines of a long CAM program), read from ``p``: what the general loop of
    :func:`read_words` reads there, or None for any other line (a parameter,
    an expression, a sign apart from its digits, a number with blanks inside,
    a letter that is no word, a value out of range, a letter twice), which
    that loop then reads and reports."""
    n = len(code)
    p = skip_blanks(code, p)
    words = Words()
    letters = words.letters
    match = _LITERAL_WORD.match
    while p < n:
        m = match(code, p)
        if m is None:
            return None
        up = m.group(1).upper()
        value = float(m.group(2))
        if up not in _WORD_LETTERS or not math.isfinite(value):
            return None
        if up == "G":
            words.g.append((value, p))
        elif up == "M":
            words.m.append((value, p))
        elif up in letters or (up in _BOUNDED_LETTERS and out_of_range(value)):
            return None
        else:
            letters[up] = (value, p)
        p = m.end()
    words.first = first
    return words


def read_words(state: GCodeState, lx: Lexed) -> tuple[Words, list[tuple[str, object, float]]]:
    """The words of line ``lx`` and its parameter settings ``(kind, key,
    value)``, which take effect after the whole line has been read."""
    code = lx.code
    if "#" not in code and "[" not in code:
        words = _literal_words(code, lx.start, lx.first)
        if words is not None:
            return words, []
    n = len(code)
    p = lx.start
    words = Words()
    settings: list[tuple[str, object, float]] = []
    while True:
        p = skip_blanks(code, p)
        if p >= n:
            break
        ch = code[p]
        up = ch.upper()
        if ch == "#":
            kind, key, q = parameter_target(state, code, p)
            q = skip_blanks(code, q)
            if q >= n or code[q] != "=":
                raise ExprError("parameter setting needs '=' and a value, e.g. #1 = 2.5", p)
            if kind == "name" and (is_ini_name(key) or is_position_name(key)):
                what = ("the machine's INI file entry" if is_ini_name(key)
                        else "the current line number" if key == "_line"
                        else "the current position")
                raise ExprError(f"cannot assign to read-only parameter #<{key}>: it is {what}",
                                p)
            value, p = read_value(state, code, q + 1, "=", q)
            settings.append((kind, key, value))
        elif up in _WORD_LETTERS:
            value, q = read_value(state, code, p + 1, up, p)
            if up == "G":
                words.g.append((value, p))
            elif up == "M":
                words.m.append((value, p))
            else:
                if up in _BOUNDED_LETTERS and out_of_range(value):
                    raise ExprError(f"{up}{fmt(value)} is out of range: coordinates, I J K R "
                                    f"E and F must lie within +-{MAX_PROGRAM_COORDINATE:g}", p)
                if up in words.letters:
                    raise ExprError(f"two {up} words on one line: keep one", p)
                words.letters[up] = (value, p)
            p = q
        else:
            raise _not_a_word(ch, p)
    words.first = lx.first
    return words, settings


def _not_a_word(ch: str, p: int) -> ExprError:
    """The error for character ``ch`` at ``p`` where a word should start."""
    up = ch.upper()
    if up == "N":
        return ExprError("N (line number) must be the first word on the line", p)
    if up == "O":
        return ExprError("an O-word must be the first word on its line", p)
    if up == "/":
        return ExprError("block delete '/' is not supported: ccopt cannot know the "
                         "switch; remove the '/' or the line", p)
    if "A" <= up <= "Z":
        return ExprError(f"unknown word {up}: ccopt reads G M X Y Z A B C U V W I J K R F P D H "
                         "T S L N Q E words, @ and ^ (polar), #parameters and O-words", p)
    return ExprError(f"unexpected character {ch!r}: expected a word such as G1 or X10", p)


def classify(state: GCodeState, words: Words) -> None:
    """Check G/M codes and their modal groups; fills ``words.gcodes``/``mcodes``."""
    for value, col in words.g:
        tenths = _g_tenths(state, value, col)
        group = G_GROUPS[tenths]
        if group in words.gcodes:
            other = words.gcodes[group][0]
            raise state.error(f"{gname(other)} and {gname(tenths)} on one line belong to the "
                              f"same modal group ({group}): keep one", col)
        words.gcodes[group] = (tenths, col)
    mgroups: dict[str, int] = {}
    for value, col in words.m:
        if abs(value - round(value)) > WHOLE_NUMBER_TOL or not 0 <= value < _M_LIMIT:
            raise state.error(f"M-code M{fmt(value)} is not a whole number from 0 to 999", col)
        m = int(round(value))
        if m == 98 or (m == 99 and len(state.frames) > 1):
            # a call or return is a line of its own (fanuc.py), as LinuxCNC's read_items
            raise state.error(f"M{m} must be the first word of its line (after N): it "
                              f"{'calls a subprogram' if m == 98 else 'returns from the subprogram'}"
                              " and takes its line", col)
        g = _M_GROUPS.get(m)
        if g is not None:
            if g in mgroups:
                raise state.error(f"M{mgroups[g]} and M{m} on one line belong to the same "
                                  f"modal group ({g}): keep one", col)
            mgroups[g] = m
        words.mcodes.append(m)


def _g_tenths(state: GCodeState, value: float, col: int) -> int:
    """The known G-code ``value`` in tenths; an error naming it otherwise."""
    tenths = round(value * 10) if abs(value) < _G_NUMBER_LIMIT else -1
    if tenths < 0 or abs(value * 10 - tenths) > _G_TENTHS_TOL or tenths not in G_GROUPS:
        hint = _G_UNSUPPORTED_HINT.get(tenths) if tenths >= 0 and \
            abs(value * 10 - tenths) <= _G_TENTHS_TOL else None
        if hint:
            # a code ccopt knows and refuses is "not supported", never "unknown"
            raise state.error(f"G{fmt(value)} is not supported: {hint}", col)
        raise state.error(f"unknown G-code G{fmt(value)}: ccopt reads {_KNOWN_G}", col)
    return tenths
