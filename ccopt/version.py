"""The installed distribution's version, in one place (the package root, the
CLI's ``--version`` and export headers read it without importing each other)."""
from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("ccopt")
except PackageNotFoundError:  # running from a source tree without install
    __version__ = "0.0.0+unknown"
