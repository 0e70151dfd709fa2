"""Program flow of a SINUMERIK part program (Programming Manual Job Planning,
"Program jumps to jump markers" and "Control structures").

* ``GOTOF label`` jumps forward, ``GOTOB`` backward, ``GOTO`` forward then
  backward, ``GOTOC`` as ``GOTO`` without an alarm when the label is
  missing; the target is a jump label (``LOOP1:``) or a block number
  (``N100``). ``IF cond GOTOF label`` jumps when the condition holds.
* ``IF cond`` .. [``ELSE``] .. ``ENDIF``; ``WHILE cond`` .. ``ENDWHILE``;
  ``REPEAT`` .. ``UNTIL cond``; ``LOOP`` .. ``ENDLOOP`` (left by a jump);
  ``FOR var = a TO b`` .. ``ENDFOR`` (counting up by 1).

The structures are matched once over the whole text (:func:`match_structures`);
a structure opened and never closed, or closed and never opened, is an error
located where it is written.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from ccopt.errors import ProgramError
from ccopt.program.sinumerik.lexer import Line, next_name, skip_blanks, split_line

#: Statement keywords that open a structure, with the keyword that closes it.
OPENERS = {"IF": "ENDIF", "WHILE": "ENDWHILE", "REPEAT": "UNTIL", "LOOP": "ENDLOOP",
           "FOR": "ENDFOR"}
CLOSERS = {v: k for k, v in OPENERS.items()}
JUMPS = ("GOTOF", "GOTOB", "GOTO", "GOTOC")


@dataclass
class Structure:
    """The lines of a program and what matches what (0-based line indices)."""

    lines: list[Line]
    kinds: list[str | None]          # the statement keyword of each line, else None
    match: dict[int, int] = field(default_factory=dict)     # opener <-> closer
    else_of: dict[int, int] = field(default_factory=dict)   # IF line -> its ELSE line
    labels: dict[str, int] = field(default_factory=dict)
    numbers: dict[str, list[int]] = field(default_factory=dict)


def statement(line: Line) -> str | None:
    """The flow keyword a line starts with (``IF`` of a one-line ``IF .. GOTO``
    is ``"IFGOTO"``), else ``None``."""
    name, q = next_name(line.code, line.start)
    if name == "IF":
        return "IFGOTO" if any(j in line.code[q:] for j in ("GOTO",)) else "IF"
    if name in OPENERS or name in CLOSERS or name == "ELSE" or name in JUMPS:
        return name
    return None


def match_structures(texts: list[str], file: str) -> Structure:
    """Split every line and match its structures."""
    lines = [split_line(t) for t in texts]
    st = Structure(lines, [statement(ln) for ln in lines])
    stack: list[int] = []
    for i, (ln, kind) in enumerate(zip(lines, st.kinds)):
        if ln.label is not None:
            if ln.label in st.labels:
                raise ProgramError(f"jump label {ln.label} is defined twice (first on line "
                                   f"{st.labels[ln.label] + 1})", file, i + 1, 1)
            st.labels[ln.label] = i
        if ln.number is not None:
            st.numbers.setdefault(ln.number, []).append(i)
        if kind in OPENERS:
            if kind == "REPEAT" and skip_blanks(ln.code, ln.start + 6) < len(ln.code):
                raise ProgramError("REPEAT with a label (program section repetition) is not "
                                   "read by ccopt: write the section out or use a loop",
                                   file, i + 1, ln.start + 1)
            stack.append(i)
        elif kind == "ELSE":
            if not stack or st.kinds[stack[-1]] != "IF" or stack[-1] in st.else_of:
                raise ProgramError("ELSE without its IF", file, i + 1, ln.start + 1)
            st.else_of[stack[-1]] = i
        elif kind in CLOSERS:
            opener = CLOSERS[kind]
            if not stack or st.kinds[stack[-1]] != opener:
                raise ProgramError(f"{kind} without its {opener}", file, i + 1, ln.start + 1)
            j = stack.pop()
            st.match[i], st.match[j] = j, i
    if stack:
        j = stack[-1]
        kind = st.kinds[j]
        raise ProgramError(f"{kind} is never closed: add {OPENERS[kind]}", file, j + 1,
                           lines[j].start + 1)
    return st


def jump_target(st: Structure, keyword: str, target: str, pc: int) -> int | None:
    """The line a jump from line ``pc`` to ``target`` (a label or block
    number) goes to, or ``None`` when there is none in that direction."""
    if target in st.labels:
        candidates = [st.labels[target]]
    else:
        candidates = st.numbers.get(target, [])
    forward = [i for i in candidates if i > pc]
    backward = [i for i in candidates if i <= pc]
    if keyword == "GOTOF":
        return min(forward, default=None)
    if keyword == "GOTOB":
        return max(backward, default=None)
    return min(forward, default=None) if forward else max(backward, default=None)
