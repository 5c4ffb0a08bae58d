"""``make test`` runs the notebooks through tests/test_notebooks.py (each in a kernel, at the
tiny budget, every figure checked). For ``pytest --nbmake notebooks`` by hand the same budget
applies (the kernels inherit this process's environment)."""

import os

os.environ.setdefault("DUALIGHT_BUDGET", "tiny")
os.environ.setdefault("MPLBACKEND", "Agg")
