"""Test-suite root: its folder is on sys.path, so shared test helpers such as
``linuxcnc_data`` import from any test folder."""
