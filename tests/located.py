"""A located refusal, checked the same way everywhere: reading ``text``
raises a :class:`~ccopt.errors.ProgramError` at ``(file, line, col)``
(1-based) whose message holds ``words``."""
from __future__ import annotations

import pytest

from ccopt.errors import ProgramError


def assert_refused_at(read, text: str, where: tuple, words: str, **kw) -> None:
    """``read(text, **kw)`` refuses ``text`` at ``where = (file, line, col)``."""
    with pytest.raises(ProgramError) as info:
        read(text, **kw)
    exc = info.value
    assert (exc.file, exc.line, exc.col) == where, str(exc)
    assert words in str(exc)
