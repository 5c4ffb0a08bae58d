"""The image estimators by name: the one table that :func:`dualight.render` and the tasks of
:mod:`dualight.executor` read.

Each method names the core function that renders it and its options class
(``dualight._core.*Options``). The options' fields, defaults and checks are the core's
(``src/bindings/options.h``): an options class names its fields in ``_fields``, so which of
``render``'s keywords apply to a method is read from it, not listed here.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

from dualight import _core

# The choice sets of the public functions, as types, so a type checker catches a misspelled
# name. Each is defined once, here, and kept equal to its runtime table by the tests
# (test_public_api.py): Method to METHODS, Sampler, Heuristic and Strategies to the core's enums,
# RadiosityMethod to dualight.radiosity.SOLVERS plus "hierarchical".
Method = Literal["path", "light", "bdpt", "pssmlt", "mmlt", "mlt"]
"""A method of :func:`dualight.render` (the names of :data:`METHODS`)."""
Sampler = Literal["independent", "sobol"]
"""``render(sampler=...)``: the core's ``SamplerType`` names."""
Heuristic = Literal["power", "balance"]
"""``render(heuristic=...)``: BDPT's MIS heuristic, the core's ``MisHeuristic`` names."""
Strategies = Literal["mis", "bsdf", "light"]
"""``render(strategies=...)``: the path tracer's and BDPT's sampling strategies, all combined
by MIS or one alone, the core's ``Strategies`` names."""
Lanes = Literal["auto", "off", "sse2", "avx2", "avx512"]
"""``render(lanes=...)``: whether the path tracer runs a tile row's paths together in SIMD lanes
(``"auto"``: with AVX-512 or AVX2, where the CPU and the scene allow), one at a time
(``"off"``), or on a given instruction set; the core's ``LaneIsa`` names."""
RadiosityMethod = Literal["direct", "jacobi", "gauss_seidel", "southwell", "hierarchical"]
"""A method of :func:`dualight.radiosity.solve`."""


@dataclass(frozen=True)
class Estimator:
    """One method of :func:`dualight.render`: the core function that renders it, its options
    class, whether it is a Metropolis method (its budget counts mutations, its chains split a
    render into tasks, ``render``'s ``mlt=`` reaches its options) and the options its name sets
    (``"mmlt"`` is PSSMLT multiplexed)."""

    render: Callable[..., dict[str, Any]]
    options: type
    metropolis: bool = False
    fixed: Mapping[str, Any] = field(default_factory=dict)

    @property
    def budget(self) -> str:
        """The options' field that counts samples (mutations for the Metropolis methods)."""
        return "mutations_per_pixel" if self.metropolis else "spp"

    def takes(self, option: str) -> bool:
        """Whether the options have the field ``option``."""
        return option in self.options._fields

    def default(self, option: str) -> Any:
        """The core's default of field ``option`` for this method (``rr_depth``: 2 for BDPT,
        5 elsewhere)."""
        return getattr(self.options(), option)

    def keywords(
        self, fields: Mapping[str, Any], mlt: Mapping[str, Any] | None = None
    ) -> dict[str, Any]:
        """The keywords of the options: ``fields`` (from ``render``'s own keywords), what the
        name sets, and ``mlt``, which may set neither. The options' constructor checks every
        value and names a bad or unknown key."""
        own = {**fields, **self.fixed}
        for key in mlt or {}:
            if key in own:
                raise TypeError(
                    f"mlt option {key!r} is set by render's own keywords or the method's name; "
                    "pass it to render instead"
                )
        return {**own, **(mlt or {})}


ESTIMATORS: dict[str, Estimator] = {
    "path": Estimator(_core.render_path, _core.PathTracerOptions),
    "light": Estimator(_core.render_light, _core.LightTracerOptions),
    "bdpt": Estimator(_core.render_bdpt, _core.BdptOptions),
    "pssmlt": Estimator(
        _core.render_pssmlt, _core.PssmltOptions, metropolis=True, fixed={"multiplexed": False}
    ),
    "mmlt": Estimator(
        _core.render_pssmlt, _core.PssmltOptions, metropolis=True, fixed={"multiplexed": True}
    ),
    "mlt": Estimator(_core.render_mlt, _core.MltOptions, metropolis=True),
}

# Every method's name, in the table's order, and the Metropolis methods' (split by chains).
METHODS = tuple(ESTIMATORS)
METROPOLIS = tuple(name for name, e in ESTIMATORS.items() if e.metropolis)
