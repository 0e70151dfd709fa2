"""Random edits of a valid part program, for the readers' and the CLI's robustness tests.

:func:`mutate` applies a few edits, each one of: delete a short run of
characters, insert a token, replace a character by a token, duplicate a line,
drop a line. The programs it makes are mostly invalid; the tests check that
every one is read or refused with a located error.
"""
from __future__ import annotations

from hypothesis import strategies as st

KINDS = ("delete", "insert", "replace", "dupline", "dropline")


def mutate(draw, text: str, *, inserts, replaces, edits: tuple[int, int],
           delete_max: int) -> str:
    """``text`` after ``edits[0]..edits[1]`` random edits drawn with ``draw``
    (a Hypothesis ``@composite`` draw): insertions from ``inserts``, replacements
    from ``replaces``, deletions of at most ``delete_max`` characters."""
    for _ in range(draw(st.integers(*edits))):
        kind = draw(st.sampled_from(KINDS))
        i = draw(st.integers(0, len(text)))
        if kind == "delete":
            text = text[:i] + text[draw(st.integers(i, min(len(text), i + delete_max))):]
        elif kind == "insert":
            text = text[:i] + draw(st.sampled_from(inserts)) + text[i:]
        elif kind == "replace":
            if i < len(text):
                text = text[:i] + draw(st.sampled_from(replaces)) + text[i + 1:]
        else:
            lines = text.split("\n")
            k = draw(st.integers(0, len(lines) - 1))
            if kind == "dupline":
                lines.insert(k, lines[k])
            else:
                del lines[k]
            text = "\n".join(lines)
    return text
