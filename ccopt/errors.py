"""Errors that reach users.

Every problem with user input (a program, a case file, a command-line value)
is a :class:`ProgramError` carrying the source location, printed by the CLI as
``file:line:col: message`` (or ``file:line: message`` when the column is not
known) with exit code 2 and never a traceback.
"""
from __future__ import annotations


class CcoptError(Exception):
    """Base class of every error ccopt raises on purpose."""


class ProgramError(CcoptError):
    """Bad input, located in its source.

    Parameters
    ----------
    message:
        What is wrong and, where possible, what to change.
    file:
        Source file name as given by the user (``"<string>"`` for text).
    line:
        1-based line number, or ``None`` when the problem has no line.
    col:
        1-based column, or ``None``.

    Attributes
    ----------
    read_before:
        For an error met while running a G-code program, the program as read
        up to the error (a :class:`~ccopt.program.model.Program`: the moves a
        LinuxCNC machine makes before it stops there), else ``None``.
    """

    read_before = None

    def __init__(self, message: str, file: str = "<string>", line: int | None = None,
                 col: int | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.col = col

    def located(self) -> str:
        parts = [self.file]
        if self.line is not None:
            parts.append(str(self.line))
            if self.col is not None:
                parts.append(str(self.col))
        return ":".join(parts)

    def __str__(self) -> str:
        # One line, always: messages never carry newlines to the terminal.
        msg = " ".join(self.message.split())
        return f"{self.located()}: {msg}"


class CompensationError(ProgramError):
    """A program that the chosen controller style cannot compensate."""
