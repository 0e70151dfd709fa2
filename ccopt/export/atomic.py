"""Kept so ``from ccopt.export.atomic import write_text_atomic`` still works:
the atomic writes live in :mod:`ccopt.atomic` (shared by export and feed)."""
from __future__ import annotations

from ccopt.atomic import write_bytes_atomic, write_text_atomic

__all__ = ["write_bytes_atomic", "write_text_atomic"]
