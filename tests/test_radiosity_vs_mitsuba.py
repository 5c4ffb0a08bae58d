"""Radiosity against the stored full-global-illumination Mitsuba 3 reference.

``cornell_64_full`` (dualight/data/references, made by make_references.py) is Mitsuba's path
tracer on ``cornell_box((64, 64))`` with ``max_depth=-1``: every bounce, as radiosity counts
them all.

Radiosity is deterministic apart from the (seeded) form-factor visibility rays, and its error
is a discretisation error, not Monte Carlo noise, so a Welch test is the wrong tool. The
criteria are:

* the issue's requirement: mean CIEDE2000 < 2 "with a fine enough mesh"
  (:func:`dualight.metrics.delta_e2000`, exposure set by the reference);
* because a 10 % error in the light's power changes the mean Delta E by only about 1.2 (its
  light_scale=0.9 control stays below 2 at this mesh: Delta E 2 is loose for a uniform
  brightness error), also the per-channel ratio of mean *reflected* radiance within 1 %: the
  image mean over the pixels that do not see the light. The light's own pixels are left out:
  they hold about half of the image mean, their radiance is the emission, exact in both
  renderers, and their partially covered edge pixels depend mostly on the pixel sampling.

Both are checked at ``MAX_EDGE``: the correct solution must pass both, and each negative
control (light x 0.9, reflectance x 0.9) must fail the combined verdict. Discretisation biases
the reflected radiance low (patches that straddle the contact lines of the blocks with the
floor and of the light with the ceiling average lit with unlit area), by about 0.017 % per mm
of ``max_edge`` (0.98 at 110 mm, 0.9925 at 45 mm, 0.996 at 25 mm): see
dualight/data/references/README.md for the convergence table.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np
import pytest

import dualight
from dualight import metrics, scenes
from dualight.bench import REFERENCE_DIR as REFERENCES
from dualight.radiosity import PatchMesh, Solution, solve

REFERENCE = "cornell_64_full"
#: Longest patch edge (mm): 4352 patches. The coarsest mesh whose reflected-radiance ratio is
#: within 1 % with some margin (Delta E < 2 already holds from 150 mm, 488 patches, on).
MAX_EDGE = 45.0
SAMPLES_PER_AXIS = 8  # 64 stratified samples per pixel: the light's edge pixels are well covered
MAX_DELTA_E = 2.0
MAX_RATIO_ERROR = 0.01
RESOLUTION = (64, 64)


@dataclass(frozen=True)
class Outcome:
    """One radiosity image against the reference."""

    label: str
    patches: int
    seconds: float
    delta_e: dict[str, float]
    relmse: float
    ratio: np.ndarray  # per channel, image mean / reference mean, all pixels
    reflected_ratio: np.ndarray  # the same over the pixels that do not see the light

    @property
    def delta_e_passes(self) -> bool:
        return self.delta_e["mean"] < MAX_DELTA_E

    @property
    def ratio_passes(self) -> bool:
        return bool(np.all(np.abs(self.reflected_ratio - 1.0) <= MAX_RATIO_ERROR))

    @property
    def passed(self) -> bool:
        return self.delta_e_passes and self.ratio_passes

    def __str__(self) -> str:
        de = self.delta_e
        return (
            f"{self.label}: {'PASS' if self.passed else 'FAIL'} ({self.patches} patches, "
            f"{self.seconds:.1f} s): dE2000 mean {de['mean']:.3f} / p95 {de['p95']:.3f} / "
            f"max {de['max']:.2f}, relMSE {self.relmse:.4f}, mean ratio RGB "
            f"{np.round(self.ratio, 4).tolist()}, "
            f"reflected {np.round(self.reflected_ratio, 4).tolist()}"
        )


def _reference() -> tuple[np.ndarray, dict]:
    mean = dualight.Image.load(REFERENCES / f"{REFERENCE}_mean.exr")
    return np.asarray(mean), mean.stats


def _light_pixels(solution: Solution) -> np.ndarray:
    """Pixels that see the light: where the emission alone renders non-zero, grown by one
    pixel so edge pixels that no sample happened to hit are left out as well."""
    emission = dataclasses.replace(solution, B=solution.E)
    seen = np.asarray(emission.render(mode="radiosity", smooth=False, samples_per_axis=16))
    m = seen.sum(axis=2) > 0
    grown = m.copy()
    grown[1:] |= m[:-1]
    grown[:-1] |= m[1:]
    grown[:, 1:] |= m[:, :-1]
    grown[:, :-1] |= m[:, 1:]
    return grown


def _outcome(label: str, solution: Solution, seconds: float, light: np.ndarray) -> Outcome:
    ref, _ = _reference()
    start = time.perf_counter()
    image = np.asarray(
        solution.render(mode="radiosity", smooth=True, samples_per_axis=SAMPLES_PER_AXIS)
    )
    seconds += time.perf_counter() - start
    return Outcome(
        label=label,
        patches=len(solution.patches),
        seconds=seconds,
        delta_e=metrics.delta_e2000(image, ref),
        relmse=metrics.relmse(image, ref),
        ratio=image.mean(axis=(0, 1), dtype=np.float64) / ref.mean(axis=(0, 1), dtype=np.float64),
        reflected_ratio=(
            image[~light].mean(axis=0, dtype=np.float64)
            / ref[~light].mean(axis=0, dtype=np.float64)
        ),
    )


@pytest.fixture(scope="module")
def correct() -> tuple[Solution, np.ndarray, Outcome]:
    scene = scenes.cornell_box(resolution=RESOLUTION)
    start = time.perf_counter()
    solution = solve(scene, method="gauss_seidel", max_edge=MAX_EDGE, importance=False)
    seconds = time.perf_counter() - start
    light = _light_pixels(solution)
    return solution, light, _outcome("correct", solution, seconds, light)


def test_reference_is_full_global_illumination() -> None:
    ref, info = _reference()
    assert info["max_depth"] == -1  # radiosity counts every bounce
    assert info["scene"] == "cornell_box(resolution=(64, 64))"
    assert ref.shape == (*RESOLUTION[::-1], 3)


def test_radiosity_matches_mitsuba(correct: tuple[Solution, np.ndarray, Outcome]) -> None:
    solution, light, outcome = correct
    print(f"\nradiosity vs Mitsuba (max_edge {MAX_EDGE} mm): {outcome}")
    ff_seconds = solution.stats["form_factors"]["seconds"]
    print(f"  form factors {ff_seconds:.1f} s, light pixels {light.sum()}")
    assert solution.stats["converged"]
    assert 0 < light.sum() < 200  # the light is small in the image
    assert outcome.delta_e["mean"] < MAX_DELTA_E
    assert np.all(np.abs(outcome.reflected_ratio - 1.0) <= MAX_RATIO_ERROR)
    assert outcome.passed


@pytest.mark.parametrize(
    "wrong", [{"light_scale": 0.9}, {"reflectance_scale": 0.9}], ids=["light0.9", "rho0.9"]
)
def test_negative_controls_fail(
    correct: tuple[Solution, np.ndarray, Outcome], wrong: dict[str, float]
) -> None:
    solution, light, _ = correct
    scene = scenes.cornell_box(resolution=RESOLUTION, **wrong)
    start = time.perf_counter()
    patches = PatchMesh(scene, max_edge=MAX_EDGE)
    # Same geometry, so the same form factors (they depend on geometry and the seed only).
    np.testing.assert_array_equal(patches.vertices, solution.patches.vertices)
    wrong_solution = solve(
        scene,
        method="gauss_seidel",
        importance=False,
        patches=patches,
        precomputed=(solution.form_factors, solution.stats["form_factors"]),
    )
    outcome = _outcome(f"cornell {wrong}", wrong_solution, time.perf_counter() - start, light)
    print(f"\nradiosity {wrong} vs Mitsuba: {outcome}")
    assert not outcome.passed
    assert not outcome.ratio_passes  # off by about 10 % either way
    if "reflectance_scale" in wrong:
        assert not outcome.delta_e_passes  # Delta E catches a colour change (about 3.2)
