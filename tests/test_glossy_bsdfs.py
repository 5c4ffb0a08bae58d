"""The BSDFs beyond Lambertian, mirror and smooth glass (issue 19), in their local frame:

* sampling against the density by Pearson's chi-square, Mitsuba-style, on a grid centred on
  each lobe and stretched by its roughness (so alpha down to 0.01 spreads over many cells), with
  the mass the density does not cover (failed samples, Dirac lobes) as one more cell; every
  roughness, both distributions, anisotropy, both sides of a dielectric, both transport modes;
  a density with alpha x 1.2 or another IOR is the negative control that must fail;
* sample weights and densities against eval_f / pdf_w;
* reciprocity where physics demands it, and for rough refraction the adjoint: the Importance
  form is the Radiance form with the directions swapped [Veach 1997, sec. 5.2];
* energy: albedo <= 1, the known loss of single-scattering microfacets at high roughness;
* Fresnel of conductors against complex arithmetic, the named metals against Mitsuba's.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import dualight
from chi2 import chi2_sf, pearson, sidak
from dualight import _core

ALPHA = 0.01
RADIANCE, IMPORTANCE = _core.TransportMode.radiance, _core.TransportMode.importance
AU = dualight.materials.named_metals()["Au"]


def _dirs(cos_theta: Any, phi: Any) -> np.ndarray:
    cos_theta, phi = np.asarray(cos_theta, np.float64), np.asarray(phi, np.float64)
    s = np.sqrt(np.maximum(0.0, 1.0 - cos_theta**2))
    return np.stack([s * np.cos(phi), s * np.sin(phi), cos_theta], axis=-1)


def rough_conductor(alpha_u: float, alpha_v: float, dist: str = "beckmann") -> Any:
    eta, k = AU
    return _core.Bsdf.rough_conductor(
        distribution=dist, alpha_u=alpha_u, alpha_v=alpha_v, eta=eta, k=k
    )


def rough_dielectric(alpha: float, dist: str = "beckmann", ior: float = 1.5) -> Any:
    return _core.Bsdf.rough_dielectric(distribution=dist, alpha_u=alpha, alpha_v=alpha, ior=ior)


def rough_plastic(alpha: float, dist: str = "beckmann", ior: float = 1.5) -> Any:
    return _core.Bsdf.rough_plastic(
        distribution=dist, alpha=alpha, diffuse_reflectance=(0.2, 0.5, 0.8), ior=ior
    )


def plastic(ior: float = 1.5) -> Any:
    return _core.Bsdf.plastic(diffuse_reflectance=(0.2, 0.5, 0.8), ior=ior)


# ---------------------------------------------------------------------------------------------
# Chi-square on a lobe-centred grid

N_T, N_PHI, GL, SUB = 24, 32, 5, 4


def _frame(z: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    z = z / np.linalg.norm(z)
    a = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(a, z)
    x /= np.linalg.norm(x)
    return x, np.cross(z, x), z


def _lobe_chi2(
    bsdf: Any,
    wo: np.ndarray,
    mode: Any,
    centre: np.ndarray,
    spread: float,
    side: int,
    pdf: Callable[[np.ndarray, np.ndarray], np.ndarray],
    n: int = 200_000,
    seed: int = 1,
) -> tuple[float, int, float]:
    """Pearson's test of the samples on ``side`` (+1: wo's hemisphere, -1: the other) binned by
    (t, phi) about ``centre``, theta = spread t / (1 - t); everything else is one cell."""
    rng = np.random.default_rng(seed)
    s = bsdf.sample(np.broadcast_to(wo, (n, 3)), rng.random((n, 2)), mode)
    wi = s["wi"].astype(np.float64)
    ours = s["valid"] & ~s["delta"] & (np.sign(wi[:, 2]) == side * np.sign(wo[2]))
    x, y, z = _frame(centre)
    t_max = math.pi / (math.pi + spread)
    local = np.stack([wi @ x, wi @ y, wi @ z], axis=1)[ours]
    theta = np.arccos(np.clip(local[:, 2], -1.0, 1.0))
    t = theta / (theta + spread)
    phi = np.arctan2(local[:, 1], local[:, 0])
    ti = np.clip((t / t_max * N_T).astype(np.int64), 0, N_T - 1)
    pi = np.clip(((phi + np.pi) / (2 * np.pi) * N_PHI).astype(np.int64), 0, N_PHI - 1)
    observed = np.bincount(ti * N_PHI + pi, minlength=N_T * N_PHI).astype(np.float64)
    # Expected: n times the integral of the density over each cell, Gauss-Legendre in (t, phi).
    dt, dp = t_max / N_T, 2 * np.pi / N_PHI

    def cell_integrals(g: np.ndarray, w: np.ndarray) -> np.ndarray:
        """Per cell, the sum over (t, phi) nodes g with weights w of density times Jacobian."""
        k = len(g)
        tt = ((np.arange(N_T)[:, None] + 0.5 * (1 + g[None, :])) * dt).ravel()
        pp = ((np.arange(N_PHI)[:, None] + 0.5 * (1 + g[None, :])) * dp - np.pi).ravel()
        T, P = np.meshgrid(tt, pp, indexing="ij")
        th = spread * T / (1 - T)
        jac = np.sin(th) * spread / (1 - T) ** 2  # d omega = sin(theta) dtheta dphi
        d = _dirs(np.cos(th), P).reshape(-1, 3)
        d = d[:, :1] * x + d[:, 1:2] * y + d[:, 2:3] * z
        on_side = np.sign(d[:, 2]) == side * np.sign(wo[2])
        dens = pdf(np.broadcast_to(wo, d.shape), d) * on_side
        cells = (dens.reshape(T.shape) * jac).reshape(N_T, k, N_PHI, k)
        integral = np.einsum("aibj,i,j->ab", cells, w, w).ravel() * (0.25 * dt * dp)
        side_z = (d[:, 2] * side * np.sign(wo[2])).reshape(N_T, k, N_PHI, k)
        straddles = ((side_z.min(axis=(1, 3)) < 0) & (side_z.max(axis=(1, 3)) >= -0.05)).ravel()
        return integral, straddles

    # Expected counts by Gauss-Legendre; a cell that its nodes see as empty but that straddles
    # the horizon (a sliver of it may hold density) expects a little, so Pearson pools it.
    # Composite Gauss-Legendre (GL nodes on each of SUB sub-intervals): the horizon cuts some
    # cells, and there the integrand jumps.
    g, w = np.polynomial.legendre.leggauss(GL)
    g = ((np.arange(SUB)[:, None] + 0.5 * (1 + g[None, :])) * (2.0 / SUB) - 1).ravel()
    w = np.tile(w / SUB, SUB)
    integral, _ = cell_integrals(g, w)
    fine = np.linspace(-1, 1, 14)[1:-1]
    _, straddles = cell_integrals(fine, np.ones_like(fine))
    expected = np.where((integral <= 0) & straddles, 1e-3, n * integral)
    rest_obs, rest_exp = n - observed.sum(), n - expected.sum()
    statistic, k = pearson(np.append(observed, rest_obs), np.append(expected, max(rest_exp, 0.0)))
    dof = k - 1
    return statistic, dof, chi2_sf(statistic, dof) if math.isfinite(statistic) else 0.0


def _reflect(wo: np.ndarray) -> np.ndarray:
    return np.array([-wo[0], -wo[1], wo[2]])


def _refract(wo: np.ndarray, ior: float) -> np.ndarray:
    eta = ior if wo[2] > 0 else 1.0 / ior
    sin2 = (1 - wo[2] ** 2) / eta**2
    cos_t = math.sqrt(max(0.0, 1 - sin2))
    return np.array([-wo[0] / eta, -wo[1] / eta, -math.copysign(cos_t, wo[2])])


WO_UP = (_dirs(0.8, 0.4), _dirs(0.3, 2.0))
WO_INSIDE = _dirs(-0.85, 1.0)  # inside the glass, within the critical angle

# (id, bsdf factory of alpha scale, lobe centres, wo list): centre "r" reflection about the
# normal, "t" refraction, "n" the normal (diffuse lobes); spread from the roughness.
CHI2_CASES: list[tuple[str, Callable[[float], Any], float, str, tuple[np.ndarray, ...]]] = [
    ("beckmann 0.01", lambda s: rough_conductor(0.01 * s, 0.01 * s), 0.01, "r", WO_UP),
    ("beckmann 0.1", lambda s: rough_conductor(0.1 * s, 0.1 * s), 0.1, "r", WO_UP),
    ("beckmann 0.6", lambda s: rough_conductor(0.6 * s, 0.6 * s), 0.6, "r", WO_UP),
    ("ggx 0.01", lambda s: rough_conductor(0.01 * s, 0.01 * s, "ggx"), 0.01, "r", WO_UP),
    ("ggx 0.3", lambda s: rough_conductor(0.3 * s, 0.3 * s, "ggx"), 0.3, "r", WO_UP),
    ("ggx aniso", lambda s: rough_conductor(0.05 * s, 0.4 * s, "ggx"), 0.2, "r", WO_UP),
    ("beckmann aniso", lambda s: rough_conductor(0.4 * s, 0.05 * s), 0.2, "r", WO_UP),
    ("glass beckmann 0.02 r", lambda s: rough_dielectric(0.02 * s), 0.02, "r", (*WO_UP, WO_INSIDE)),
    ("glass beckmann 0.02 t", lambda s: rough_dielectric(0.02 * s), 0.02, "t", (*WO_UP, WO_INSIDE)),
    ("glass ggx 0.4 r", lambda s: rough_dielectric(0.4 * s, "ggx"), 0.4, "r", (*WO_UP, WO_INSIDE)),
    ("glass ggx 0.4 t", lambda s: rough_dielectric(0.4 * s, "ggx"), 0.4, "t", (*WO_UP, WO_INSIDE)),
    ("roughplastic 0.05", lambda s: rough_plastic(0.05 * s), 0.05, "r", WO_UP),
    ("roughplastic ggx 0.3", lambda s: rough_plastic(0.3 * s, "ggx"), 0.3, "r", WO_UP),
]


def _run_case(
    make: Callable[[float], Any], spread: float, lobe: str, wos: tuple, pdf_scale: float
) -> list[tuple[float, int, float]]:
    bsdf = make(1.0)
    other = make(pdf_scale)
    out = []
    # The transport mode changes weights, never directions (test_modes_sample_the_same_
    # directions): each wo is tested in one mode, alternating.
    for i, wo in enumerate(wos):
        mode = (RADIANCE, IMPORTANCE)[i % 2]
        centre = _reflect(wo) if lobe == "r" else _refract(wo, 1.5)
        side = -1 if lobe == "t" else 1

        def pdf(a: np.ndarray, b: np.ndarray, m: Any = mode) -> np.ndarray:
            return other.pdf_w(a, b, m).astype(np.float64)

        out.append(_lobe_chi2(bsdf, wo, mode, centre, max(3 * spread, 0.02), side, pdf))
    return out


N_CHI2_TESTS = sum(len(c[4]) for c in CHI2_CASES)


@pytest.mark.parametrize(
    ("name", "make", "spread", "lobe", "wos"), CHI2_CASES, ids=[c[0] for c in CHI2_CASES]
)
def test_sampling_matches_the_density_chi2(
    name: str, make: Any, spread: float, lobe: str, wos: tuple
) -> None:
    results = _run_case(make, spread, lobe, wos, 1.0)
    print(
        f"\n{name} chi2 (statistic, dof, p): "
        f"{[(round(x, 1), d, f'{p:.3g}') for x, d, p in results]}"
    )
    level = sidak(ALPHA, N_CHI2_TESTS)
    assert all(p > level for _, _, p in results), results
    # Negative control: the density of the same BSDF with every roughness x 1.2.
    wrong = _run_case(make, spread, lobe, wos, 1.2)
    print(f"{name} vs alpha x 1.2: {[(round(s, 1), d, f'{p:.3g}') for s, d, p in wrong]}")
    assert all(p < level for _, _, p in wrong), wrong


def test_rough_glass_chi2_fails_with_another_ior() -> None:
    bsdf, wrong = rough_dielectric(0.2), rough_dielectric(0.2, ior=1.6)
    level = sidak(ALPHA, N_CHI2_TESTS)
    for i, wo in enumerate((*WO_UP, WO_INSIDE)):
        for mode in ((RADIANCE, IMPORTANCE)[i % 2],):
            _, _, p = _lobe_chi2(
                bsdf,
                wo,
                mode,
                _refract(wo, 1.5),
                0.6,
                -1,
                lambda a, b, m=mode: wrong.pdf_w(a, b, m),
            )
            assert p < level, (wo, mode, p)


def test_smooth_plastic_chi2_with_its_dirac_mass() -> None:
    """The diffuse lobe against its density, the coat's Dirac lobe (and nothing else) in the
    remaining cell; another coat IOR moves that mass and must fail."""
    level = sidak(ALPHA, N_CHI2_TESTS)
    for mode, wo in zip((RADIANCE, IMPORTANCE), WO_UP, strict=True):
        bsdf = plastic()
        s = bsdf.sample(
            np.broadcast_to(wo, (1000, 3)), np.random.default_rng(0).random((1000, 2)), mode
        )
        assert s["valid"].all()
        np.testing.assert_allclose(
            s["wi"][s["delta"]],
            np.broadcast_to(_reflect(wo), s["wi"][s["delta"]].shape),
            atol=1e-6,
        )
        right = _lobe_chi2(
            bsdf,
            wo,
            mode,
            np.array([0, 0, 1.0]),
            1.0,
            1,
            lambda a, b, m=mode, f=bsdf: f.pdf_w(a, b, m),
        )
        other = plastic(1.7)
        wrong = _lobe_chi2(
            bsdf,
            wo,
            mode,
            np.array([0, 0, 1.0]),
            1.0,
            1,
            lambda a, b, m=mode, f=other: f.pdf_w(a, b, m),
        )
        print(f"\nplastic {wo} {mode}: {right[2]:.3g}, ior 1.7: {wrong[2]:.3g}")
        assert right[2] > level and wrong[2] < level


# ---------------------------------------------------------------------------------------------
# Weights, densities, reciprocity, the adjoint

ALL = {
    "conductor Au": _core.Bsdf.conductor(eta=AU[0], k=AU[1]),
    "rough conductor": rough_conductor(0.3, 0.3),
    "rough conductor aniso ggx": rough_conductor(0.1, 0.5, "ggx"),
    "rough conductor two-sided": _core.Bsdf.rough_conductor(
        alpha_u=0.2, alpha_v=0.2, two_sided=True
    ),
    "thin dielectric": _core.Bsdf.thin_dielectric(ior=1.5),
    "rough dielectric": rough_dielectric(0.3),
    "rough dielectric ggx": rough_dielectric(0.05, "ggx", 1.33),
    "plastic": plastic(),
    "plastic nonlinear two-sided": _core.Bsdf.plastic(
        diffuse_reflectance=(0.9, 0.5, 0.1), nonlinear=True, two_sided=True
    ),
    "rough plastic": rough_plastic(0.2),
}


@pytest.mark.parametrize("name", sorted(ALL))
@pytest.mark.parametrize("mode", ["radiance", "importance"])
def test_sample_weight_and_pdf_agree_with_eval(name: str, mode: str) -> None:
    bsdf, m = ALL[name], getattr(_core.TransportMode, mode)
    rng = np.random.default_rng(5)
    n = 20_000
    wo = _dirs(rng.uniform(-1, 1, n), rng.uniform(0, 2 * np.pi, n))
    s = bsdf.sample(wo, rng.random((n, 2)), m)
    ok = s["valid"] & ~s["delta"]
    wi = s["wi"].astype(np.float64)
    assert np.all(np.isfinite(s["weight"])) and np.all(s["weight"] >= 0)
    np.testing.assert_allclose(np.linalg.norm(wi[s["valid"]], axis=1), 1.0, atol=1e-5)
    if ok.any():
        f = bsdf.eval_f(wo[ok], wi[ok], m).astype(np.float64)
        pdf = bsdf.pdf_w(wo[ok], wi[ok], m).astype(np.float64)
        assert np.all(pdf > 0)
        np.testing.assert_allclose(s["pdf_w"][ok], pdf, rtol=2e-3)
        np.testing.assert_allclose(
            s["weight"][ok], f * np.abs(wi[ok, 2:3]) / pdf[:, None], rtol=2e-3, atol=1e-7
        )
    if "two-sided" not in name and "dielectric" not in name:  # one-sided: black behind
        back = wo[:, 2] < 0
        assert not s["valid"][back].any()
        assert not bsdf.eval_f(wo[back], -wo[back], m).any()


@pytest.mark.parametrize("name", sorted(ALL))
def test_modes_sample_the_same_directions(name: str) -> None:
    """Radiance and Importance differ in weights only: the same random numbers give the same
    directions and densities (so the chi-square tests run each wo in one mode)."""
    rng = np.random.default_rng(11)
    n = 20_000
    wo = _dirs(rng.uniform(-1, 1, n), rng.uniform(0, 2 * np.pi, n))
    u = rng.random((n, 2))
    a, b = ALL[name].sample(wo, u, RADIANCE), ALL[name].sample(wo, u, IMPORTANCE)
    for key in ("wi", "pdf_w", "valid", "delta"):
        np.testing.assert_array_equal(a[key], b[key])


@pytest.mark.parametrize("name", sorted(ALL))
def test_reciprocity_and_the_adjoint(name: str) -> None:
    bsdf = ALL[name]
    rng = np.random.default_rng(7)
    n = 20_000
    wo = _dirs(rng.uniform(-1, 1, n), rng.uniform(0, 2 * np.pi, n))
    wi = _dirs(rng.uniform(-1, 1, n), rng.uniform(0, 2 * np.pi, n))
    # The Importance form is the Radiance form with the directions swapped, for every BSDF
    # (up to float32 rounding of the half vector where refraction is ill-conditioned: 1e-3 of
    # the pairs may differ by more than 0.1 %).
    adjoint, swapped = bsdf.eval_f(wo, wi, IMPORTANCE), bsdf.eval_f(wi, wo, RADIANCE)
    close = np.isclose(adjoint, swapped, rtol=1e-3, atol=1e-6).all(axis=1)
    assert close.mean() >= 0.999, close.mean()
    refraction = wo[:, 2] * wi[:, 2] < 0
    f = bsdf.eval_f(wo, wi, RADIANCE)
    if "rough dielectric" in name:
        # Rough refraction is not symmetric: f(wo, wi) / f(wi, wo) = (eta_wo / eta_wi)^2.
        ior = 1.5 if name == "rough dielectric" else 1.33
        ratio = f[refraction, 0] / np.maximum(bsdf.eval_f(wi, wo, RADIANCE)[refraction, 0], 1e-30)
        expected = np.where(wo[refraction, 2] > 0, 1 / ior**2, ior**2)
        live = f[refraction, 0] > 1e-4
        assert live.sum() > 100
        # float32 half vectors near grazing refraction: a few pairs in 1,000 are off by > 1 %.
        assert np.mean(np.isclose(ratio[live], expected[live], rtol=1e-2)) >= 0.995
    else:
        np.testing.assert_allclose(f, swapped, rtol=1e-3, atol=1e-6)


def _albedo(
    bsdf: Any, wo: np.ndarray, mode: Any, n: int = 400_000
) -> tuple[np.ndarray, np.ndarray]:
    s = bsdf.sample(np.broadcast_to(wo, (n, 3)), np.random.default_rng(9).random((n, 2)), mode)
    w = s["weight"].astype(np.float64)
    return w.mean(axis=0), w.std(axis=0) / math.sqrt(n)


def test_energy_bounds_and_single_scattering_loss() -> None:
    white = lambda a, d: _core.Bsdf.rough_conductor(distribution=d, alpha_u=a, alpha_v=a)  # noqa: E731
    for name, bsdf, modes in [
        *[
            (f"{d} {a}", white(a, d), (RADIANCE,))
            for d in ("beckmann", "ggx")
            for a in (0.01, 0.3, 1.0)
        ],
        ("rough plastic", rough_plastic(0.3), (RADIANCE,)),
        ("plastic", plastic(), (RADIANCE,)),
        ("rough glass", rough_dielectric(0.3), (IMPORTANCE,)),  # radiance gains eta^2 inside
        ("thin glass", _core.Bsdf.thin_dielectric(), (RADIANCE, IMPORTANCE)),
    ]:
        for mode in modes:
            for cz in (1.0, 0.7, 0.2):
                mean, err = _albedo(bsdf, _dirs(cz, 0.3), mode)
                assert np.all(mean <= 1 + 4 * err + 1e-6), (name, cz, mean)
    # A white rough conductor (F = 1) of alpha 0.01 keeps all its energy.
    assert _albedo(white(0.01, "ggx"), _dirs(0.9, 0.0), RADIANCE)[0][0] == pytest.approx(
        1.0, abs=5e-3
    )


def _mitsuba_albedo(d: str, alpha: float, cz: float, n: int = 8000) -> tuple[float, float]:
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    b = mi.load_dict({"type": "roughconductor", "distribution": d, "alpha": alpha})
    si, ctx = mi.SurfaceInteraction3f(), mi.BSDFContext()
    si.wi = mi.Vector3f(math.sqrt(1 - cz * cz), 0.0, cz)
    rng = np.random.default_rng(4)
    w = [
        b.sample(ctx, si, float(u), mi.Point2f(*v))[1][0]
        for u, v in zip(rng.random(n), rng.random((n, 2)), strict=True)
    ]
    return float(np.mean(w)), float(np.std(w) / math.sqrt(n))


@pytest.mark.parametrize(("d", "alpha"), [("ggx", 1.0), ("beckmann", 1.0), ("ggx", 0.3)])
def test_single_scattering_energy_loss_matches_mitsuba(d: str, alpha: float) -> None:
    """The energy a single-scattering microfacet surface loses (no multiple bounces between
    microfacets) is part of the model: a white rough conductor's albedo at normal and grazing
    incidence agrees with Mitsuba's, and alpha x 1.2 (the negative control) does not."""
    for cz in (1.0, 0.2):
        ref, ref_err = _mitsuba_albedo(d, alpha, cz)
        for scale, same in ((1.0, True), (1.2, False)):
            bsdf = _core.Bsdf.rough_conductor(
                distribution=d, alpha_u=alpha * scale, alpha_v=alpha * scale
            )
            ours, err = _albedo(bsdf, _dirs(cz, 0.0), RADIANCE)
            z = (ours[0] - ref) / math.hypot(err[0], ref_err)
            print(
                f"\n{d} alpha {alpha * scale:.2f} cos {cz}: ours {ours[0]:.4f}, "
                f"Mitsuba {ref:.4f} (z {z:.2f})"
            )
            assert (abs(z) < 4) == same


def _fresnel_complex(cos_i: np.ndarray, eta: complex) -> np.ndarray:
    """Unpolarised reflectance of a conductor from complex amplitudes (Born and Wolf)."""
    sin2 = 1 - cos_i**2
    cos_t = np.sqrt(1 - sin2 / eta**2 + 0j)
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return 0.5 * (np.abs(rs) ** 2 + np.abs(rp) ** 2)


def test_conductor_fresnel_against_complex_arithmetic() -> None:
    eta, k = AU
    bsdf = _core.Bsdf.conductor(eta=eta, k=k)
    cos = np.linspace(0.01, 1.0, 50)
    wo = _dirs(cos, np.zeros_like(cos))
    s = bsdf.sample(wo, np.full((50, 2), 0.5), RADIANCE)
    assert s["delta"].all()
    for c in range(3):
        np.testing.assert_allclose(
            s["weight"][:, c], _fresnel_complex(cos, complex(eta[c], k[c])), rtol=2e-4
        )
    # "none" (eta 0, k 1) reflects everything; Mitsuba's gold is yellow.
    mirror = _core.Bsdf.conductor()
    np.testing.assert_allclose(mirror.sample(wo, np.full((50, 2), 0.5))["weight"], 1.0, rtol=1e-6)
    normal = s["weight"][-1]
    assert normal[0] > normal[1] > normal[2]


def test_thin_dielectric_lobes() -> None:
    bsdf = _core.Bsdf.thin_dielectric(ior=1.5)
    n = 200_000
    for cz in (0.9, -0.4):
        wo = _dirs(cz, 0.5)
        s = bsdf.sample(np.broadcast_to(wo, (n, 3)), np.random.default_rng(3).random((n, 2)))
        R = _core.fresnel_dielectric(np.array([abs(cz)]), 1.5)[0][0]
        expected = 2 * R / (1 + R)
        reflected = s["wi"][:, 2] * cz > 0
        assert abs(reflected.mean() - expected) < 5 * math.sqrt(expected * (1 - expected) / n)
        np.testing.assert_allclose(
            s["wi"][~reflected], np.broadcast_to(-wo, s["wi"][~reflected].shape), atol=1e-6
        )


def test_named_metals_match_mitsuba() -> None:
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    table = dualight.materials.named_metals()
    assert len(table) >= 60
    worst = 0.0
    for name in ("Au", "Ag", "Al", "Cu", "Cr", "W", "a-C", "TiN"):
        params = mi.traverse(mi.load_dict({"type": "conductor", "material": name}))
        for key, ours in zip(("eta.value", "k.value"), table[name], strict=True):
            theirs = np.array(params[key], dtype=np.float64).ravel()
            worst = max(worst, float(np.max(np.abs(theirs - ours))))
            np.testing.assert_allclose(ours, theirs, rtol=1e-6)
    print(f"\nnamed metals: largest |ours - Mitsuba| = {worst:.2g}")


def test_bad_parameters_raise() -> None:
    with pytest.raises(ValueError, match="alpha_u must be finite"):
        _core.Bsdf.rough_conductor(alpha_u=float("nan"), alpha_v=0.1)
    with pytest.raises(ValueError, match="distribution must be"):
        _core.Bsdf.rough_dielectric(distribution="phong")
    with pytest.raises(ValueError, match="ior must differ from 1"):
        _core.Bsdf.rough_dielectric(ior=1.0)
    with pytest.raises(ValueError, match="conductor k must be finite"):
        _core.Bsdf.conductor(k=(1.0, -1.0, 1.0))
    with pytest.raises(ValueError, match="unknown metal 'Unobtainium'"):
        dualight.Conductor(material="Unobtainium")
    with pytest.raises(ValueError, match="material or eta and k, not both"):
        dualight.Conductor(material="Au", eta=1.0)
    with pytest.raises(ValueError, match="alpha or alpha_u and alpha_v"):
        dualight.RoughConductor(alpha=0.1, alpha_u=0.2, alpha_v=0.2)
    with pytest.raises(ValueError, match="both alpha_u and alpha_v"):
        dualight.RoughDielectric(alpha_u=0.2)
    with pytest.raises(ValueError, match="transmitting"):
        dualight.TwoSided(dualight.RoughDielectric())
    with pytest.raises(ValueError, match="diffuse_reflectance must be finite"):
        dualight.Plastic(diffuse_reflectance=1.5)


def test_materials_describe_themselves_and_export_to_mitsuba() -> None:
    gold = dualight.RoughConductor(material="Au", alpha_u=0.1, alpha_v=0.3, distribution="ggx")
    assert gold.flags == {"glossy", "reflection"} and not gold.is_diffuse_reflector
    assert dualight.Plastic().flags == {"diffuse", "specular", "reflection"}
    assert dualight.RoughPlastic().flags == {"diffuse", "glossy", "reflection"}
    assert dualight.ThinDielectric().flags == {"specular", "reflection", "transmission"}
    both = dualight.TwoSided(gold)
    assert both.two_sided and not gold.two_sided
    d = both._mitsuba_bsdf()
    assert d["type"] == "twosided" and d["bsdf"]["type"] == "roughconductor"
    assert d["bsdf"]["alpha_u"] == 0.1 and d["bsdf"]["alpha_v"] == 0.3
    assert dualight.TwoSided(dualight.Diffuse()) == dualight.Diffuse()
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    for material in (
        both,
        dualight.RoughDielectric(alpha=0.2),
        dualight.ThinDielectric(),
        dualight.Plastic(nonlinear=True),
        dualight.RoughPlastic(distribution="ggx"),
        dualight.Conductor(material="Cu"),
    ):
        mi.load_dict(material._mitsuba_bsdf())  # Mitsuba accepts every parameter
