"""The notebooks' budget: ``full`` by hand (the default), ``tiny`` in CI (``DUALIGHT_BUDGET=tiny``,
set by notebooks/conftest.py when pytest runs them through nbmake)."""

import os

TINY = os.environ.get("DUALIGHT_BUDGET", "full") == "tiny"


def pick(tiny, full):
    """``tiny`` in CI, ``full`` by hand."""
    return tiny if TINY else full
