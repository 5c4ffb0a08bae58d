"""pytest --nbmake runs every notebook here top to bottom at a tiny budget (the kernels inherit
this process's environment)."""

import os

os.environ.setdefault("DUALIGHT_BUDGET", "tiny")
os.environ.setdefault("MPLBACKEND", "Agg")
