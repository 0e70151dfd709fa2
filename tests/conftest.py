"""Test-suite root: its folder is on sys.path, so shared test helpers such as
``linuxcnc_data`` import from any test folder.

Hypothesis profiles: ``HYPOTHESIS_PROFILE=ci`` (set by .ci/run) draws the
same examples on every run, so a CI verdict is reproducible; the default
profile draws new ones each run, which is how new failures are found.
"""
import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))
