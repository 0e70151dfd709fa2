"""``FeedError``: feed planning could not be done, located at a block."""
from __future__ import annotations

from ccopt.errors import ProgramError


class FeedError(ProgramError):
    """Feed planning failed (bad limits for this path, or TOPPRA failed).

    A :class:`ProgramError`, so the CLI prints it as one located line and
    exits 2: ``file:line: message`` names the source block where planning
    failed when there is one.
    """
