"""The words after a block's keyword, read into one :class:`Args`.

``L X+10 IY-5 RL F200 M3`` -> coordinates ``{"X": (10, False), "Y": (-5,
True)}``, side +1, feed 200, M codes (3,). Which words a keyword allows is
checked by the caller (:func:`Args.allow`).
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

from ccopt.errors import ProgramError
from ccopt.program.heidenhain.lexer import Statement, Word
from ccopt.program.heidenhain.values import Parameters

AXES = "XYZ"
_ROTARY = set("ABCUVW")
_SIDES = {"RL": 1, "RR": -1, "R0": 0}
#: address -> attribute for the valued words other than coordinates
_VALUED = (("IPA", "ipa"), ("IPR", "ipr"), ("CCA", "cca"), ("LEN", "length"), ("PA", "pa"),
           ("PR", "pr"), ("DL", "dl"), ("DR", "dr_value"), ("R", "radius"), ("F", "feed"),
           ("S", "speed"))
_M_RE = re.compile(r"M(\d+)$")
_ADDRESSES = {addr for addr, _ in _VALUED}
_VALUE_RE = re.compile(r"[+-]?(\d+\.?\d*|\.\d+|Q[LR]?\d+)$")


@dataclass
class Args:
    """What a block's words say (``None``: not written)."""

    st: Statement
    coords: dict = field(default_factory=dict)      # "X" -> (value, incremental)
    cols: dict = field(default_factory=dict)        # attribute / axis -> column
    side: int | None = None
    direction: int | None = None                    # DR+ 1, DR- -1
    feed: float | None = None
    rapid: bool = False
    fauto: bool = False
    mcodes: tuple = ()
    radius: float | None = None
    length: float | None = None
    cca: float | None = None
    pa: float | None = None
    ipa: float | None = None
    pr: float | None = None
    ipr: float | None = None
    dl: float | None = None
    dr_value: float | None = None
    speed: float | None = None
    extra: list = field(default_factory=list)       # words read by the caller (M140 MB ...)

    def allow(self, names: set[str], what: str, file: str) -> None:
        """ProgramError at the first word written that ``what`` does not take."""
        for key, col in self.cols.items():
            if key not in names:
                raise ProgramError(f"{what} does not take {key}", file, self.st.line, col)

    def col(self, key: str) -> int:
        return self.cols.get(key, self.st.words[0].col)


def read_args(st: Statement, words: list[Word], q: Parameters, file: str) -> Args:
    """Read ``words`` (the block's words after its keyword)."""
    a = Args(st)
    i = 0
    while i < len(words):
        w = words[i]
        t = w.text
        i += 1
        if t in _SIDES:
            a.side, a.cols["side"] = _SIDES[t], w.col
        elif t in ("DR+", "DR-"):
            a.direction, a.cols["DR"] = (1 if t == "DR+" else -1), w.col
        elif t == "FMAX":
            a.rapid, a.cols["F"] = True, w.col
        elif t == "FAUTO":
            a.fauto, a.cols["F"] = True, w.col
        elif t == "M120":
            raise ProgramError("M120 (radius-compensated path calculated in advance, LOOK "
                               "AHEAD) is not read by ccopt: the heidenhain style has no "
                               "look-ahead; remove it to compensate block by block", file,
                               st.line, w.col)
        elif _M_RE.match(t):
            a.mcodes += (int(t[1:]),)
            a.cols["M"] = w.col
            if t == "M140":
                while i < len(words) and (words[i].text.startswith("MB")
                                          or words[i].text in ("MAX", "F")):
                    a.extra.append(words[i])
                    i += 1
        else:
            if t in _ADDRESSES and i < len(words) and _VALUE_RE.match(words[i].text):
                # an address and its value written apart: CCA 180, LEN 5
                w = Word(t + words[i].text, w.col)
                i += 1
            _valued(a, w, q, file)
    return a


def _valued(a: Args, w: Word, q: Parameters, file: str) -> None:
    t = w.text
    inc = t.startswith("I") and len(t) > 1 and t[1] in AXES
    axis = t[1] if inc else t[0]
    if axis in AXES and (len(t) == (2 if inc else 1) or t[2 if inc else 1] in "+-.0123456789Q"):
        if axis in a.coords:
            raise ProgramError(f"{axis} written twice", file, a.st.line, w.col)
        a.coords[axis] = (q.number(t[2 if inc else 1:], a.st.line, w.col, t[:2 if inc else 1]),
                          inc)
        a.cols[axis] = w.col
        return
    if t[0] in _ROTARY and len(t) > 1 and t[1] in "+-.0123456789Q":
        raise ProgramError(f"{t}: rotary and secondary axes (A B C U V W) are not read by "
                           "ccopt", file, a.st.line, w.col)
    for addr, attr in _VALUED:
        if t.startswith(addr) and len(t) > len(addr) and t[len(addr)] in "+-.0123456789Q":
            if t.startswith("FZ") or t.startswith("FU"):
                break
            setattr(a, attr, q.number(t[len(addr):], a.st.line, w.col, addr))
            a.cols[addr] = w.col
            return
    raise ProgramError(f"{t}: word not read by ccopt here", file, a.st.line, w.col)
