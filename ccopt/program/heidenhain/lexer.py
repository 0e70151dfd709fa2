"""Klartext text -> statements: one per NC block, each a list of words.

A Klartext file has one NC block per line, ``<block number> <content>``
(``12 L X+10 Y+5 RL F200 M3``). A block may run over several lines when a
line ends with ``~`` (the cycle definitions CAM systems write). ``;`` starts
a comment up to the end of the physical line; a block whose content starts
with ``*`` is a comment block (``* - Contour1``). Words are separated by
white space; a word is a keyword (``L``, ``CC``, ``RL``, ``FMAX``) or an
address with its value (``X+10``, ``IX-5``, ``PA+30``, ``R+5``, ``Q1=+3``).
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from ccopt.errors import ProgramError

#: A leading block number: ``12 L X+1`` -> content ``L X+1``.
_NUMBER_RE = re.compile(r"\s*(\d+)\s+")
_WORD_RE = re.compile(r"\S+")


@dataclass(frozen=True)
class Word:
    """One word of a block: its text (upper case) and 1-based column."""

    text: str
    col: int


@dataclass(frozen=True)
class Statement:
    """One NC block: 1-based line of its first line, its words, its raw text."""

    line: int
    words: tuple[Word, ...]
    text: str

    @property
    def head(self) -> str:
        return self.words[0].text if self.words else ""

    def texts(self) -> list[str]:
        return [w.text for w in self.words]


def _strip_comment(line: str) -> str:
    """The line without its ``;`` comment (a ``;`` inside a "quoted" name stays)."""
    if '"' not in line:
        return line.split(";", 1)[0]
    quoted = False
    for i, ch in enumerate(line):
        if ch == '"':
            quoted = not quoted
        elif ch == ";" and not quoted:
            return line[:i]
    return line


def _words(text: str, offset: int) -> list[Word]:
    """The white-space separated words of ``text``; ``offset`` is the column
    of ``text[0]`` minus one. A "quoted" name is one word."""
    if '"' not in text:
        return [Word(m.group().upper(), m.start() + offset + 1) for m in _WORD_RE.finditer(text)]
    out: list[Word] = []
    i, n = 0, len(text)
    while i < n:
        if text[i].isspace():
            i += 1
            continue
        start = i
        if text[i] == '"':
            j = text.find('"', i + 1)
            i = n if j < 0 else j + 1
        else:
            while i < n and not text[i].isspace():
                if text[i] == '"':
                    j = text.find('"', i + 1)
                    i = n if j < 0 else j + 1
                    continue
                i += 1
        out.append(Word(text[start:i].upper() if '"' not in text[start:i] else text[start:i],
                        start + offset + 1))
    return out


def split_statements(text: str, file: str) -> list[Statement]:
    """Every NC block of ``text`` in order (comment blocks and blank lines left
    out). ProgramError for a ``~`` continuation that never ends."""
    out: list[Statement] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        first = i
        raw = lines[i]
        body = _strip_comment(raw)
        m = _NUMBER_RE.match(body)
        offset = m.end() if m else len(body) - len(body.lstrip())
        content = body[offset:]
        if content.lstrip().startswith("*"):
            i += 1
            continue
        words = _words(content, offset)
        while raw.rstrip().endswith("~"):
            i += 1
            if i >= len(lines):
                raise ProgramError("the block continues with '~' but the file ends",
                                   file, first + 1)
            raw = lines[i]
            words.extend(_words(_strip_comment(raw), 0))
        i += 1
        if "~" in raw or i - first > 1:
            words = [Word(w.text.rstrip("~"), w.col) for w in words if w.text.rstrip("~")]
        if words:
            out.append(Statement(first + 1, tuple(words), raw.strip()))
    return out
