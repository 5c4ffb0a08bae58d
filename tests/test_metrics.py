"""Tests for dualight.metrics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dualight import metrics

SHAPE = (64, 64, 3)


def _estimate(
    rng: np.random.Generator, truth: np.ndarray, sigma: float, n: int
) -> tuple[np.ndarray, np.ndarray]:
    """Simulate a per-pixel mean of ``n`` samples with std ``sigma`` and its variance of mean."""
    mean = truth + rng.normal(0.0, sigma / math.sqrt(n), truth.shape)
    sample_var = sigma**2 * rng.chisquare(n - 1, truth.shape) / (n - 1)
    return mean, sample_var / n


def _truth(rng: np.random.Generator) -> np.ndarray:
    return rng.uniform(0.2, 0.8, SHAPE)


# --------------------------------------------------------------------------- rmse / relmse


def test_rmse_hand_computed() -> None:
    x = np.zeros((1, 2, 3))
    y = np.zeros((1, 2, 3))
    x[0, 0] = [1.0, 2.0, 0.0]  # squared errors 1, 4, 0, 0, 0, 0 -> mean 5/6
    assert metrics.rmse(x, y) == pytest.approx(math.sqrt(5 / 6))
    assert metrics.rmse(y, y) == 0.0


def test_relmse_hand_computed() -> None:
    y = np.full((1, 1, 3), [1.0, 0.0, 3.0])
    x = np.full((1, 1, 3), [2.0, 0.5, 3.0])
    expected = (1.0 / 1.01**2 + 0.25 / 0.01**2 + 0.0) / 3
    assert metrics.relmse(x, y) == pytest.approx(expected)
    expected_eps = (1.0 / 1.5**2 + 0.25 / 0.5**2) / 3
    assert metrics.relmse(x, y, eps=0.5) == pytest.approx(expected_eps)
    # Not tev's definition (x - y)^2 / (y^2 + eps).
    tev = (1.0 / 1.01 + 0.25 / 0.01) / 3
    assert metrics.relmse(x, y) != pytest.approx(tev)


def test_rmse_shape_mismatch() -> None:
    with pytest.raises(ValueError, match="reference"):
        metrics.rmse(np.zeros((2, 2, 3)), np.zeros((2, 3, 3)))
    with pytest.raises(ValueError, match="H x W x 3"):
        metrics.relmse(np.zeros((2, 2)), np.zeros((2, 2)))


# --------------------------------------------------------------------------- Welch test


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_welch_same_distribution_passes(seed: int) -> None:
    rng = np.random.default_rng(seed)
    truth = _truth(rng)
    a, va = _estimate(rng, truth, 0.5, 64)
    b, vb = _estimate(rng, truth, 0.3, 256)
    for block in (1, 8):
        r = metrics.welch_test(a, va, b, vb, block=block)
        assert r.pass_fraction >= 0.9975, str(r)
        assert r.z.shape == (64 // block, 64 // block, 3)
        assert r.passed.shape == (64 // block, 64 // block)
        assert r.n_units == (64 // block) ** 2


def test_welch_large_bias_fails_pixel_and_block() -> None:
    rng = np.random.default_rng(10)
    truth = _truth(rng)
    a, va = _estimate(rng, truth * 1.03, 0.01, 64)
    b, vb = _estimate(rng, truth, 0.01, 64)
    pixel = metrics.welch_test(a, va, b, vb)
    blocks = metrics.welch_test(a, va, b, vb, block=8)
    assert pixel.pass_fraction < 0.5
    assert blocks.pass_fraction < 0.5


@pytest.mark.parametrize("seed", [20, 21, 22])
def test_welch_small_bias_only_visible_per_block(seed: int) -> None:
    # Per-pixel std of the difference ~0.014, so a bias of 0.01 gives z ~ 0.7 per pixel (far
    # below z* ~ 4.9) but z ~ 5.7 per 8x8 block (above z* ~ 4.1).
    rng = np.random.default_rng(seed)
    truth = np.full(SHAPE, 0.5)
    a, va = _estimate(rng, truth + 0.01, 0.08, 64)
    b, vb = _estimate(rng, truth, 0.08, 64)
    pixel = metrics.welch_test(a, va, b, vb)
    blocks = metrics.welch_test(a, va, b, vb, block=8)
    assert pixel.pass_fraction >= 0.9975, str(pixel)
    assert blocks.pass_fraction < 0.5, str(blocks)


def test_welch_block_aggregation_and_remainder() -> None:
    # 5x5 image with block 2: the last row and column are dropped.
    m = np.zeros((5, 5, 3))
    v = np.full((5, 5, 3), 0.01)
    m[4, :] = 100.0  # would fail if not dropped
    m[:, 4] = 100.0
    m2 = m.copy()
    m2[:2, :2] = 0.1  # block mean diff 0.1, block var (4 * 0.02) / 16 = 0.005
    r = metrics.welch_test(m2, v, m, v, block=2, var_floor=0.0)
    assert r.z.shape == (2, 2, 3)
    assert r.z[0, 0] == pytest.approx(np.full(3, 0.1 / math.sqrt(0.005)))
    assert np.all(r.z[1:, :] == 0) and np.all(r.z[:, 1:] == 0)


def test_welch_sidak_alpha() -> None:
    z = np.zeros(SHAPE)
    r = metrics.welch_test(z, z, z, z, alpha=0.01)
    n = 64 * 64 * 3
    assert r.alpha == 0.01
    assert r.alpha_per_test == pytest.approx(1 - 0.99 ** (1 / n), rel=1e-9)
    assert r.alpha_per_test == pytest.approx(8.1790e-7, rel=1e-4)
    assert 1 - (1 - r.alpha_per_test) ** n == pytest.approx(0.01, rel=1e-9)
    assert r.pass_fraction == 1.0 and r.max_z == 0.0
    assert "4096/4096" in str(r)


def test_welch_threshold_matches_normal_tail() -> None:
    # alpha_per_test for a single unit of 3 channels; z just below/above the critical value.
    alpha = 0.05
    per_test = 1 - (1 - alpha) ** (1 / 3)
    zstar = metrics._z_critical(per_test)
    assert math.erfc(zstar / math.sqrt(2)) == pytest.approx(per_test, rel=1e-9)
    ones, zeros = np.ones((1, 1, 3)), np.zeros((1, 1, 3))
    lo = metrics.welch_test(ones * (zstar - 1e-6), ones, zeros, zeros, alpha=alpha, var_floor=0)
    hi = metrics.welch_test(ones * (zstar + 1e-6), ones, zeros, zeros, alpha=alpha, var_floor=0)
    assert lo.pass_fraction == 1.0 and hi.pass_fraction == 0.0


def test_welch_errors() -> None:
    z = np.zeros((8, 8, 3))
    with pytest.raises(ValueError, match="var_b"):
        metrics.welch_test(z, z, z, np.zeros((8, 7, 3)))
    with pytest.raises(ValueError, match=r"var_a.*negative"):
        metrics.welch_test(z, -np.ones_like(z), z, z)
    bad = z.copy()
    bad[3, 3, 1] = np.nan
    with pytest.raises(ValueError, match=r"mean_b.*NaN"):
        metrics.welch_test(z, z, bad, z)
    with pytest.raises(ValueError, match="block"):
        metrics.welch_test(z, z, z, z, block=9)
    with pytest.raises(ValueError, match="block"):
        metrics.welch_test(z, z, z, z, block=0)
    with pytest.raises(ValueError, match="alpha"):
        metrics.welch_test(z, z, z, z, alpha=0.0)


# --------------------------------------------------------------------------- Delta E 2000


def _lab_of_grey(g: float) -> np.ndarray:
    """CIE L*a*b* of linear sRGB grey (g, g, g) under its own white point: a* = b* = 0."""
    f = g ** (1 / 3) if g > (6 / 29) ** 3 else g / (3 * (6 / 29) ** 2) + 4 / 29
    return np.array([116 * f - 16, 0.0, 0.0])


def _ciede2000_lightness_only(lab1: np.ndarray, lab2: np.ndarray) -> float:
    """CIEDE2000 for neutral colours (a* = b* = 0): |dL| / S_L."""
    lbar = (lab1[0] + lab2[0]) / 2
    s_l = 1 + 0.015 * (lbar - 50) ** 2 / math.sqrt(20 + (lbar - 50) ** 2)
    return abs(lab1[0] - lab2[0]) / s_l


def test_delta_e_identical_is_zero() -> None:
    ref = np.random.default_rng(30).uniform(0.0, 2.0, (16, 16, 3))
    de = metrics.delta_e2000(ref, ref)
    assert de == {"mean": 0.0, "p95": 0.0, "max": 0.0}


def test_delta_e_brighter_image_penalised() -> None:
    ref = np.random.default_rng(31).uniform(0.05, 1.0, (32, 32, 3))
    de = metrics.delta_e2000(ref * 1.1, ref)
    assert de["mean"] > 0.5
    assert de["mean"] <= de["p95"] <= de["max"]


def test_delta_e_grey_known_value() -> None:
    g1, g2 = 0.2, 0.21
    a, b = np.full((4, 4, 3), g1), np.full((4, 4, 3), g2)
    expected = _ciede2000_lightness_only(_lab_of_grey(g1), _lab_of_grey(g2))
    de = metrics.delta_e2000(a, b, exposure=1.0)
    assert de["mean"] == pytest.approx(expected, rel=1e-6)
    assert de["max"] == pytest.approx(expected, rel=1e-6)
    # Default exposure maps the reference's 99th-percentile luminance (g2) to 1.
    de_auto = metrics.delta_e2000(a, b)
    expected_auto = _ciede2000_lightness_only(_lab_of_grey(g1 / g2), _lab_of_grey(1.0))
    assert de_auto["mean"] == pytest.approx(expected_auto, rel=1e-6)


def test_delta_e_symmetric_and_monotonic() -> None:
    ref = np.random.default_rng(32).uniform(0.05, 0.5, (16, 16, 3))
    means = [metrics.delta_e2000(ref * s, ref, exposure=1.0)["mean"] for s in (1.0, 1.02, 1.1)]
    assert means[0] == 0.0 and means[0] < means[1] < means[2]
    ab = metrics.delta_e2000(ref * 1.1, ref, exposure=1.0)
    ba = metrics.delta_e2000(ref, ref * 1.1, exposure=1.0)
    assert ab["mean"] == pytest.approx(ba["mean"], rel=1e-12)


def test_delta_e_black_reference_needs_exposure() -> None:
    z = np.zeros((4, 4, 3))
    with pytest.raises(ValueError, match="exposure"):
        metrics.delta_e2000(z, z)
    assert metrics.delta_e2000(z, z, exposure=1.0)["mean"] == 0.0


# --------------------------------------------------------------------------- compare


def test_compare_same_distribution_passes() -> None:
    rng = np.random.default_rng(40)
    truth = _truth(rng)
    # Noise low enough for the perceptual criterion (mean dE2000 < 1) to hold as well.
    a, va = _estimate(rng, truth, 0.04, 64)
    b, vb = _estimate(rng, truth, 0.02, 1024)
    c = metrics.compare(a, va, b, vb)
    assert c.passed, str(c)
    assert c.blocks.block == 8 and c.pixel.block == 1
    assert c.relmse == pytest.approx(metrics.relmse(a, b))
    assert str(c).startswith("PASS")


def test_compare_biased_fails() -> None:
    rng = np.random.default_rng(41)
    truth = _truth(rng)
    a, va = _estimate(rng, truth * 1.03, 0.05, 64)
    b, vb = _estimate(rng, truth, 0.05, 64)
    c = metrics.compare(a, va, b, vb)
    assert not c.passed
    assert c.blocks.pass_fraction < 0.9975
    assert str(c).startswith("FAIL")


def test_mask_leaves_out_pixels_and_blocks() -> None:
    rng = np.random.default_rng(3)
    ref = rng.uniform(0.2, 0.8, (32, 32, 3))
    var = np.full_like(ref, 1e-5)
    image = ref + rng.normal(0.0, 3e-3, ref.shape)
    image[:8, :8] += 0.5  # a region the estimator is not meant to render
    full = metrics.compare(image, var, ref, var)
    assert not full.passed and full.blocks.pass_fraction < 1.0
    mask = np.ones((32, 32), dtype=bool)
    mask[:8, :8] = False
    masked = metrics.compare(image, var, ref, var, mask=mask)
    assert masked.passed, masked
    assert masked.pixel.n_units == 32 * 32 - 64 and masked.blocks.n_units == 15
    # A mask that cuts into a block removes that whole block from the block test.
    mask[8, 8] = False
    assert metrics.welch_test(image, var, ref, var, block=8, mask=mask).n_units == 14
    with pytest.raises(ValueError, match="mask"):
        metrics.compare(image, var, ref, var, mask=np.ones((4, 4), dtype=bool))
    with pytest.raises(ValueError, match="no pixel"):
        metrics.welch_test(image, var, ref, var, mask=np.zeros((32, 32), dtype=bool))


def test_block_mean_averages_blocks() -> None:
    image = np.arange(4 * 6 * 3, dtype=np.float64).reshape(4, 6, 3)
    out = metrics.block_mean(image, 2)
    assert out.shape == (2, 3, 3)
    np.testing.assert_allclose(out[0, 0], image[:2, :2].reshape(-1, 3).mean(axis=0))
    assert metrics.block_mean(image, 4).shape == (1, 1, 3)  # trailing columns dropped
    with pytest.raises(ValueError, match="block"):
        metrics.block_mean(image, 5)


def test_student_t_matches_tabulated_values() -> None:
    # Two-sided 5 % and 1 % points from standard tables; Welch's non-integer dof works too.
    assert metrics.student_t_critical(10, 0.05) == pytest.approx(2.228139, abs=1e-6)
    assert metrics.student_t_critical(1, 0.05) == pytest.approx(12.706205, abs=1e-6)
    assert metrics.student_t_critical(23, 0.01) == pytest.approx(2.807336, abs=1e-6)
    assert metrics.student_t_critical(1e7, 0.05) == pytest.approx(1.959964, abs=1e-5)
    assert metrics.student_t_p_value(2.228139, 10) == pytest.approx(0.05, abs=1e-7)
    assert metrics.student_t_p_value(-2.228139, 10) == pytest.approx(0.05, abs=1e-7)
    assert metrics.student_t_p_value(0.0, 3.5) == 1.0
    # Negative control: the normal's value is not the t's at few degrees of freedom.
    assert abs(metrics.student_t_critical(5, 0.05) - 1.959964) > 0.5
    with pytest.raises(ValueError, match="dof"):
        metrics.student_t_p_value(1.0, 0.0)


def test_delta_e_without_colour_science_says_how_to_install_it(monkeypatch) -> None:
    import sys

    monkeypatch.setitem(sys.modules, "colour", None)  # `import colour` raises ImportError
    img = np.full((4, 4, 3), 0.5)
    with pytest.raises(ImportError, match="needs colour-science.*pip install colour-science"):
        metrics.delta_e2000(img, img)
