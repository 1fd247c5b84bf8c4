# SPDX-License-Identifier: BSD-3-Clause
"""Lets `python3 examples/<name>/plot.py` work with whichever python3 comes first on PATH.

Debian's matplotlib (python3-matplotlib, installed by scripts/install-deps.sh) belongs to the
system interpreter, /usr/bin/python3. Another python3 first on PATH (pyenv, a virtual
environment) may not have it: the script is then run again by the system interpreter. Call
`matplotlib_for_files()` before importing pyplot."""
import os
import sys

SYSTEM_PYTHON = "/usr/bin/python3"


def matplotlib_for_files():
    """Returns matplotlib set to draw into files (no display needed)."""
    try:
        import matplotlib
    except ImportError:
        already_system = os.path.realpath(sys.executable) == os.path.realpath(SYSTEM_PYTHON)
        if not already_system and not os.environ.get("MPSFSI_PLOT_RERUN") and os.access(SYSTEM_PYTHON, os.X_OK):
            os.environ["MPSFSI_PLOT_RERUN"] = "1"
            os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON] + sys.argv)
        sys.exit(f"{sys.argv[0]}: matplotlib is missing (Debian: python3-matplotlib; "
                 "bash scripts/install-deps.sh installs it)")
    matplotlib.use("Agg")
    return matplotlib
