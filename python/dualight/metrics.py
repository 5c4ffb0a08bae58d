"""Image comparison metrics for validating renderers against references.

Every function accepts anything :func:`numpy.asarray` turns into an ``H x W x 3`` float array
(including :class:`dualight.Image`, which exposes its buffer without a copy); all arithmetic is
done in float64.

* :func:`rmse`, :func:`relmse` -- plain error norms.
* :func:`welch_test` -- per-pixel or per-block z test of "both estimates have the same
  expectation", given the variance of each mean estimate.
* :func:`delta_e2000` -- perceptual CIEDE2000 difference after a common exposure normalisation.
* :func:`compare` -- all of the above combined into a single pass/fail verdict.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

if TYPE_CHECKING:
    from dualight.scene import Scene

__all__ = [
    "Comparison",
    "WelchResult",
    "block_mean",
    "compare",
    "delta_e2000",
    "relmse",
    "rmse",
    "welch_test",
]

_REC709_Y = np.array([0.2126, 0.7152, 0.0722])


def _image(x: ArrayLike, name: str) -> np.ndarray:
    """Return ``x`` as a float64 ``H x W x 3`` array or raise ``ValueError``."""
    a = np.asarray(x, dtype=np.float64)
    if a.ndim != 3 or a.shape[2] != 3:
        raise ValueError(f"{name} must have shape H x W x 3, got {a.shape}")
    return a


def _pair(image: ArrayLike, reference: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Validate an image / reference pair of equal ``H x W x 3`` shape."""
    x, y = _image(image, "image"), _image(reference, "reference")
    _same_shape(image=x, reference=y)
    return x, y


def _same_shape(**arrays: np.ndarray) -> None:
    """Raise ``ValueError`` naming the first array whose shape differs from the first one."""
    (first, ref), *rest = arrays.items()
    for name, a in rest:
        if a.shape != ref.shape:
            raise ValueError(f"shape mismatch: {first} is {ref.shape} but {name} is {a.shape}")


def block_mean(image: ArrayLike, block: int) -> np.ndarray:
    """Average over ``block x block`` pixel blocks (trailing rows and columns that do not fill a
    block are dropped): ``H x W x C`` to ``H // block x W // block x C``.

    Colour differences of a noisy estimate measure mostly its noise; on block means they
    measure its colour (e.g. :func:`delta_e2000` of the block means of a heavy-tailed render).
    """
    x = _image(image, "image")
    h, w, c = x.shape
    if int(block) != block or not 1 <= block <= min(h, w):
        raise ValueError(f"block must be an integer in [1, {min(h, w)}], got {block}")
    hb, wb = h // block, w // block
    return x[: hb * block, : wb * block].reshape(hb, block, wb, block, c).mean(axis=(1, 3))


def rmse(image: ArrayLike, reference: ArrayLike) -> float:
    """Root mean squared error over all pixels and channels.

    Parameters
    ----------
    image, reference : array_like
        ``H x W x 3`` images.

    Returns
    -------
    float
        ``sqrt(mean((image - reference) ** 2))``.
    """
    x, y = _pair(image, reference)
    return float(np.sqrt(np.mean((x - y) ** 2)))


def relmse(image: ArrayLike, reference: ArrayLike, eps: float = 1e-2) -> float:
    """Relative mean squared error, as defined by pbrt-v4's ``imgtool``.

    ``relmse = mean over pixels and channels of (x - y)^2 / (y + eps)^2``

    where ``x`` is ``image`` and ``y`` is ``reference``. Note that tev uses a different
    definition, ``(x - y)^2 / (y^2 + eps)``; that is NOT what this function computes, so numbers
    from the two tools are not comparable.

    Parameters
    ----------
    image, reference : array_like
        ``H x W x 3`` images.
    eps : float, optional
        Offset that keeps dark reference pixels from dominating.

    Returns
    -------
    float
        The relative MSE.
    """
    x, y = _pair(image, reference)
    return float(np.mean((x - y) ** 2 / (y + eps) ** 2))


@lru_cache(maxsize=256)
def _z_critical(alpha_per_test: float) -> float:
    """Two-sided normal critical value: the ``z`` with ``erfc(z / sqrt(2)) == alpha_per_test``.

    Found by bisection on :func:`math.erfc` (monotonically decreasing), so no SciPy is needed.
    """
    lo, hi = 0.0, 40.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if math.erfc(mid / math.sqrt(2.0)) > alpha_per_test:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-13:
            break
    return 0.5 * (lo + hi)


def _incomplete_beta_fraction(a: float, b: float, x: float) -> float:
    """Continued fraction of the regularised incomplete beta function (modified Lentz)."""
    tiny = 1e-300
    qab, qap, qam = a + b, a + 1.0, a - 1.0
    c, d = 1.0, 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 500):
        for aa in (
            m * (b - m) * x / ((qam + 2 * m) * (a + 2 * m)),
            -(a + m) * (qab + m) * x / ((a + 2 * m) * (qap + 2 * m)),
        ):
            d = 1.0 + aa * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + aa / c
            c = c if abs(c) > tiny else tiny
            h *= d * c
        if abs(d * c - 1.0) < 1e-14:
            break
    return h


def student_t_p_value(t: float, dof: float) -> float:
    """Two-sided p-value ``P(|T| >= |t|)`` of Student's t with ``dof`` degrees of freedom (any
    positive real, as Welch's test gives): the regularised incomplete beta function
    ``I_x(dof / 2, 1 / 2)`` at ``x = dof / (dof + t^2)``, by its continued fraction (no SciPy)."""
    if not (dof > 0 and math.isfinite(t)):
        raise ValueError(f"need dof > 0 and a finite t, got t={t!r}, dof={dof!r}")
    x = dof / (dof + t * t)
    if x >= 1.0:
        return 1.0
    a, b = 0.5 * dof, 0.5
    log_front = (
        math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x)
    )
    front = math.exp(log_front)
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _incomplete_beta_fraction(a, b, x) / a
    return 1.0 - front * _incomplete_beta_fraction(b, a, 1.0 - x) / b


@lru_cache(maxsize=256)
def student_t_critical(dof: float, alpha: float) -> float:
    """Two-sided Student-t critical value: the ``t`` with ``student_t_p_value(t, dof) == alpha``
    (bisection)."""
    if not 0.0 < alpha < 1.0:
        raise ValueError(f"alpha must be in (0, 1), got {alpha}")
    lo, hi = 0.0, 1.0
    while student_t_p_value(hi, dof) > alpha:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if student_t_p_value(mid, dof) > alpha:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-12 * hi:
            break
    return 0.5 * (lo + hi)


@dataclass(frozen=True, eq=False)
class WelchResult:
    """Outcome of :func:`welch_test`.

    Attributes
    ----------
    pass_fraction : float
        Fraction of tested units (pixels, or blocks when ``block > 1``) that pass; a unit passes
        when all three of its channels pass.
    alpha : float
        Family-wise significance level requested.
    alpha_per_test : float
        Šidák-corrected level of each individual test, ``1 - (1 - alpha) ** (1 / n_tests)``
        with ``n_tests = n_units * 3``.
    n_units : int
        Number of tested pixels or blocks (``Hb * Wb``).
    block : int
        Block edge length in pixels (1 means per-pixel).
    z : numpy.ndarray
        ``|z|`` per unit and channel, shape ``Hb x Wb x 3``.
    passed : numpy.ndarray
        Boolean ``Hb x Wb`` map of passing units.
    max_z : float
        Largest ``|z|`` over all units and channels.
    """

    pass_fraction: float
    alpha: float
    alpha_per_test: float
    n_units: int
    block: int
    z: np.ndarray
    passed: np.ndarray
    max_z: float

    def __str__(self) -> str:
        n_pass = int(np.count_nonzero(self.passed))
        unit = "pixel" if self.block == 1 else f"{self.block}x{self.block} block"
        return (
            f"Welch ({unit}): {n_pass}/{self.n_units} pass ({100 * self.pass_fraction:.2f}%), "
            f"max |z| = {self.max_z:.3g} vs z* = {_z_critical(self.alpha_per_test):.3g} "
            f"(alpha = {self.alpha:g}, per test {self.alpha_per_test:.3g})"
        )


def welch_test(
    mean_a: ArrayLike,
    var_a: ArrayLike,
    mean_b: ArrayLike,
    var_b: ArrayLike,
    *,
    alpha: float = 0.01,
    block: int = 1,
    var_floor: float = 1e-12,
    mask: ArrayLike | None = None,
) -> WelchResult:
    """Test per pixel (or per block) whether two Monte Carlo estimates share their expectation.

    For each unit and channel the statistic is ``z = |a - b| / sqrt(var_a + var_b + var_floor)``
    with two-sided p-value ``erfc(z / sqrt(2))`` under the normal approximation. To control the
    family-wise error rate at ``alpha`` over all ``n_tests = n_units * 3`` tests, each test uses
    the Šidák level ``alpha_per_test = 1 - (1 - alpha) ** (1 / n_tests)``; a test passes when
    ``p > alpha_per_test`` (implemented as ``z < z*`` with ``z*`` the matching critical value).

    Parameters
    ----------
    mean_a, mean_b : array_like
        ``H x W x 3`` mean estimates.
    var_a, var_b : array_like
        ``H x W x 3`` variances *of the mean estimates* (sample variance divided by the sample
        count), not of individual samples.
    alpha : float, optional
        Family-wise significance level, in ``(0, 1)``.
    block : int, optional
        If greater than 1, the image is split into ``block x block`` blocks and blocks are
        tested instead of pixels. Trailing rows and columns that do not fill a whole block are
        dropped. A block mean is the average of its pixel means and its variance is the sum of
        its pixel variances divided by ``block ** 4``; this assumes pixel estimates are
        independent, as in a path tracer. For correlated estimators (e.g. MLT) this
        underestimates the variance: test per pixel with ``block=1`` on block means whose
        variances were measured from independent runs instead.
    var_floor : float, optional
        Added to the summed variance so that noise-free pixels do not divide by zero.
    mask : array_like of bool, optional
        ``H x W``: the pixels to test (e.g. those an estimator can render at all). A block is
        tested only if all its pixels are; untested units count as passed in ``passed``, have
        ``z = 0``, and are left out of ``n_units``, ``pass_fraction`` and the Šidák correction.

    Returns
    -------
    WelchResult

    Raises
    ------
    ValueError
        On shape mismatches, NaN or infinite input, negative variances, or invalid
        ``alpha`` / ``block``.
    """
    arrays = {
        "mean_a": _image(mean_a, "mean_a"),
        "var_a": _image(var_a, "var_a"),
        "mean_b": _image(mean_b, "mean_b"),
        "var_b": _image(var_b, "var_b"),
    }
    _same_shape(**arrays)
    for name, a in arrays.items():
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} contains NaN or infinite values")
    for name in ("var_a", "var_b"):
        if np.any(arrays[name] < 0):
            raise ValueError(f"{name} contains negative variances")
    if not 0.0 < alpha < 1.0:
        raise ValueError(f"alpha must be in (0, 1), got {alpha}")
    h, w, c = arrays["mean_a"].shape
    if int(block) != block or not 1 <= block <= min(h, w):
        raise ValueError(f"block must be an integer in [1, {min(h, w)}], got {block}")
    block = int(block)

    hb, wb = h // block, w // block
    cropped = {k: v[: hb * block, : wb * block] for k, v in arrays.items()}
    if block > 1:
        sums = {k: v.reshape(hb, block, wb, block, c).sum(axis=(1, 3)) for k, v in cropped.items()}
        a, b = sums["mean_a"] / block**2, sums["mean_b"] / block**2
        va, vb = sums["var_a"] / block**4, sums["var_b"] / block**4
    else:
        a, b, va, vb = (cropped[k] for k in ("mean_a", "mean_b", "var_a", "var_b"))

    z = np.abs(a - b) / np.sqrt(va + vb + var_floor)
    tested = _tested_units(mask, (h, w), block)
    z = np.where(tested[:, :, None], z, 0.0)
    n_units = int(np.count_nonzero(tested))
    if n_units == 0:
        raise ValueError("mask leaves no pixel or block to test")
    # -expm1(log1p(-alpha) / n) == 1 - (1 - alpha) ** (1 / n), without cancellation.
    alpha_per_test = float(-np.expm1(np.log1p(-alpha) / (n_units * c)))
    passed = np.all(z < _z_critical(alpha_per_test), axis=2)
    return WelchResult(
        pass_fraction=float(np.count_nonzero(passed & tested)) / n_units,
        alpha=float(alpha),
        alpha_per_test=alpha_per_test,
        n_units=n_units,
        block=block,
        z=z,
        passed=passed,
        max_z=float(z.max()),
    )


def _pixel_mask(mask: ArrayLike | None, shape: tuple[int, int]) -> np.ndarray:
    if mask is None:
        return np.ones(shape, dtype=bool)
    m = np.asarray(mask)
    if m.shape != shape or m.dtype != bool:
        raise ValueError(f"mask must be a boolean array of shape {shape}, got {m.dtype} {m.shape}")
    return m


def _tested_units(mask: ArrayLike | None, shape: tuple[int, int], block: int) -> np.ndarray:
    m = _pixel_mask(mask, shape)
    hb, wb = shape[0] // block, shape[1] // block
    return m[: hb * block, : wb * block].reshape(hb, block, wb, block).all(axis=(1, 3))


def _colour_science(needed_by: str) -> tuple[Any, type[Warning]]:
    """The ``colour`` package and its ``ColourWarning``, or an ImportError saying how to get
    it (colour-science is an optional dependency)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # import-time notices, e.g. about SciPy being absent
            import colour
            from colour.utilities import ColourWarning
    except ImportError as exc:
        raise ImportError(
            f"dualight.metrics.{needed_by} needs colour-science, which is not installed: "
            "pip install colour-science (or the extras: pip install \"dualight[notebooks]\")"
        ) from exc
    return colour, ColourWarning


def delta_e2000(
    image: ArrayLike,
    reference: ArrayLike,
    *,
    exposure: float | None = None,
    mask: ArrayLike | None = None,
) -> dict[str, float]:
    """CIEDE2000 colour difference between two linear sRGB images.

    Steps:

    1. Both images are multiplied by the *same* factor ``k`` so that an image that is too bright
       is still penalised: ``k = exposure`` if given, else ``1 / p99(Y_ref)`` with ``Y_ref`` the
       reference's Rec.709 luminance ``0.2126 R + 0.7152 G + 0.0722 B``.
    2. The scaled values are clipped to ``[0, 1]``.
    3. Linear sRGB is converted to CIE XYZ with colour-science, without applying the sRGB
       transfer function (the data is already linear and must not be decoded again).
    4. XYZ is converted to CIE L*a*b* relative to the D65 white point of sRGB.
    5. ``colour.delta_E(..., method="CIE 2000")`` is evaluated per pixel.

    Parameters
    ----------
    image, reference : array_like
        ``H x W x 3`` linear sRGB (Rec.709 primaries) images.
    exposure : float, optional
        Explicit scale factor ``k``; required if the reference is black.
    mask : array_like of bool, optional
        ``H x W``: the pixels whose differences are summarised (all by default). The exposure
        still comes from the whole reference.

    Returns
    -------
    dict
        ``{"mean": ..., "p95": ..., "max": ...}`` of the per-pixel Delta E 2000.

    Raises
    ------
    ImportError
        Without colour-science (an optional dependency), saying how to install it.
    """
    x, y = _pair(image, reference)
    keep = _pixel_mask(mask, x.shape[:2])
    if exposure is None:
        p99 = float(np.percentile(y @ _REC709_Y, 99))
        if not p99 > 0.0:
            raise ValueError("reference luminance 99th percentile is not positive; pass exposure")
        k = 1.0 / p99
    else:
        k = float(exposure)

    colour, ColourWarning = _colour_science("delta_e2000")  # noqa: N806 - a class
    space = colour.RGB_COLOURSPACES["sRGB"]
    with warnings.catch_warnings(), colour.domain_range_scale("reference"):
        warnings.simplefilter("ignore", ColourWarning)

        lab = [
            colour.XYZ_to_Lab(
                colour.RGB_to_XYZ(np.clip(rgb * k, 0.0, 1.0), space, apply_cctf_decoding=False),
                space.whitepoint,
            )
            for rgb in (x, y)
        ]
        de = np.asarray(colour.delta_E(lab[0], lab[1], method="CIE 2000"), dtype=np.float64)
    de = de[keep]
    return {
        "mean": float(de.mean()),
        "p95": float(np.percentile(de, 95)),
        "max": float(de.max()),
    }


@dataclass(frozen=True, eq=False)
class Comparison:
    """Outcome of :func:`compare`.

    ``pixel`` and ``blocks`` are the per-pixel and per-block :class:`WelchResult`, ``delta_e``
    the :func:`delta_e2000` dict, ``relmse`` the :func:`relmse` value, and ``passed`` whether all
    criteria of :func:`compare` hold.
    """

    pixel: WelchResult
    blocks: WelchResult
    delta_e: dict[str, float]
    relmse: float
    passed: bool

    def __str__(self) -> str:
        de = self.delta_e
        return (
            f"{'PASS' if self.passed else 'FAIL'}: "
            f"pixels {100 * self.pixel.pass_fraction:.2f}% pass "
            f"(max |z| {self.pixel.max_z:.3g}), "
            f"{self.blocks.block}x{self.blocks.block} blocks "
            f"{100 * self.blocks.pass_fraction:.2f}% pass (max |z| {self.blocks.max_z:.3g}), "
            f"dE2000 mean {de['mean']:.3g} / p95 {de['p95']:.3g} / max {de['max']:.3g}, "
            f"relMSE {self.relmse:.3g}"
        )


def compare(
    image: ArrayLike,
    variance: ArrayLike,
    reference: ArrayLike,
    reference_variance: ArrayLike,
    *,
    alpha: float = 0.01,
    block: int = 8,
    pixel_pass: float = 0.9975,
    block_pass: float = 0.9975,
    max_delta_e: float = 1.0,
    mask: ArrayLike | None = None,
) -> Comparison:
    """Compare a rendering against a reference, both with per-pixel variances of the mean.

    The comparison passes when all of the following hold:

    * ``pixel.pass_fraction >= pixel_pass`` for the per-pixel :func:`welch_test`;
    * ``blocks.pass_fraction >= block_pass`` for the ``block x block`` :func:`welch_test`, which
      detects small biases hidden by per-pixel noise;
    * ``delta_e2000(image, reference)["mean"] < max_delta_e``.

    ``block_pass`` defaults to the same value as ``pixel_pass`` so both tests are judged alike.
    Both tests already control the family-wise error at ``alpha``, so under the null hypothesis
    nearly every unit passes; the pass fractions leave slack for heavy-tailed estimates. With few
    blocks (e.g. 64 for a 64x64 image and ``block=8``) a 0.9975 threshold means every block must
    pass.

    Parameters
    ----------
    image, variance, reference, reference_variance : array_like
        ``H x W x 3`` means and variances of the means (see :func:`welch_test`).
    alpha, block : optional
        Forwarded to :func:`welch_test` (``block`` only for the block test).
    pixel_pass, block_pass : float, optional
        Minimum pass fractions of the per-pixel and per-block tests.
    max_delta_e : float, optional
        Exclusive upper bound on the mean CIEDE2000 difference (default exposure).
    mask : array_like of bool, optional
        ``H x W``: compare only these pixels (Welch tests, Delta E and relMSE alike), e.g. the
        pixels a light tracer can render (not those that see a mirror or glass directly).

    Returns
    -------
    Comparison
    """
    pixel = welch_test(
        image, variance, reference, reference_variance, alpha=alpha, block=1, mask=mask
    )
    blocks = welch_test(
        image, variance, reference, reference_variance, alpha=alpha, block=block, mask=mask
    )
    de = delta_e2000(image, reference, mask=mask)
    keep = _pixel_mask(mask, np.shape(reference)[:2])
    passed = (
        pixel.pass_fraction >= pixel_pass
        and blocks.pass_fraction >= block_pass
        and de["mean"] < max_delta_e
    )
    return Comparison(
        pixel=pixel,
        blocks=blocks,
        delta_e=de,
        relmse=relmse(np.asarray(image)[keep][None], np.asarray(reference)[keep][None]),
        passed=bool(passed),
    )


def renderable_by_light_tracing(scene: Scene, subsamples: int = 4) -> np.ndarray:
    """``H x W`` bool: the pixels whose every camera ray (a ``subsamples x subsamples`` grid of
    cell centres) first hits a surface without a Dirac lobe (diffuse or glossy), or nothing.
    Only these can a light tracer render completely: it cannot reach the pinhole through a
    mirror, smooth glass or a smooth coat seen directly, so compare it with another estimator
    on this mask (``welch_test(..., mask=...)``)."""
    cam = scene.camera
    if cam is None:
        raise ValueError("scene has no camera")
    ray_cam = cam._compile()
    offsets = (np.arange(subsamples) + 0.5) / subsamples
    origins, directions, pixel = [], [], []
    for y in range(cam.height):
        for x in range(cam.width):
            for oy in offsets:
                for ox in offsets:
                    o, d = ray_cam.generate_ray(x + ox, y + oy)
                    origins.append(o)
                    directions.append(d)
                    pixel.append(y * cam.width + x)
    _, prim = scene._compile().intersect(np.array(origins), np.array(directions))
    _, _, mesh_of = scene.triangle_arrays()
    not_diffuse = np.array(["specular" in m.material.flags for m in scene.meshes])
    hits_not_diffuse = np.zeros(len(prim), dtype=bool)
    hit = prim >= 0
    hits_not_diffuse[hit] = not_diffuse[mesh_of[prim[hit]]]
    bad = np.zeros(cam.width * cam.height, dtype=bool)
    np.logical_or.at(bad, np.array(pixel), hits_not_diffuse)
    return ~bad.reshape(cam.height, cam.width)
