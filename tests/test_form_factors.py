"""Form factors against closed forms from Howell's catalogue, and closure, reciprocity, culling
and occlusion.

The closed forms are from J. R. Howell, *A Catalog of Radiation Heat Transfer Configuration
Factors* (thermalradiation.net; also Siegel and Howell, *Thermal Radiation Heat Transfer*,
appendix of configuration factors). Each accuracy check has a negative control: the same
formula with one geometry parameter 5-10 % off must miss by far more than the tolerance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import dualight
from dualight import _core, scenes
from dualight.radiosity import PatchMesh, form_factor_checks, form_factors

TOL = 1e-3  # relative, for every analytic case


# Closed forms ---------------------------------------------------------------------------------
def element_to_parallel_disc(r: float, h: float, a: float = 0.0) -> float:
    """Plane element to a parallel disc of radius r at distance h, the element's normal through
    the disc's plane at distance a from its centre (Howell, section B: "plane element to plane
    parallel disk", on and off axis). a = 0 gives r^2 / (h^2 + r^2)."""
    return 0.5 * (
        1.0 - (a * a + h * h - r * r) / math.sqrt((a * a + h * h + r * r) ** 2 - 4 * r * r * a * a)
    )


def parallel_rectangles(a: float, b: float, c: float) -> float:
    """Identical, parallel, directly opposed rectangles a x b at distance c (Howell, section C),
    X = a/c, Y = b/c."""
    x, y = a / c, b / c
    return (
        2.0
        / (math.pi * x * y)
        * (
            math.log(math.sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)))
            + x * math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))
            + y * math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x))
            - x * math.atan(x)
            - y * math.atan(y)
        )
    )


def perpendicular_rectangles(w: float, h: float, length: float) -> float:
    """From a rectangle w x length to a rectangle h x length sharing its length-long edge, at
    90 degrees (Howell, section C: "two finite rectangles of same length, having one common edge,
    and at an angle of 90 deg to each other"), W = w/l, H = h/l."""
    W, H = w / length, h / length  # noqa: N806 - the catalogue's names
    s = W * W + H * H
    angles = (
        W * math.atan(1 / W) + H * math.atan(1 / H) - math.sqrt(s) * math.atan(1 / math.sqrt(s))
    )
    logs = 0.25 * (
        math.log((1 + W * W) * (1 + H * H) / (1 + s))
        + W * W * math.log(W * W * (1 + s) / ((1 + W * W) * s))
        + H * H * math.log(H * H * (1 + s) / ((1 + H * H) * s))
    )
    return (angles + logs) / (math.pi * W)


def coaxial_discs(r1: float, r2: float, h: float) -> float:
    """Disc of radius r1 to a parallel coaxial disc of radius r2 at distance h (Howell, section
    C): F = (X - sqrt(X^2 - 4 (R2/R1)^2)) / 2, X = 1 + (1 + R2^2) / R1^2, R_i = r_i / h."""
    R1, R2 = r1 / h, r2 / h  # noqa: N806
    X = 1 + (1 + R2 * R2) / (R1 * R1)  # noqa: N806
    return 0.5 * (X - math.sqrt(X * X - 4 * (R2 / R1) ** 2))


def test_closed_forms_match_catalogue_values() -> None:
    # Tabulated values: parallel unit squares at distance 1: 0.1998; perpendicular unit
    # squares with a common edge: 0.2000; discs r1 = 0.1, r2 = 0.2, h = 0.5: 0.1339.
    assert parallel_rectangles(1, 1, 1) == pytest.approx(0.1998, abs=1e-4)
    assert perpendicular_rectangles(1, 1, 1) == pytest.approx(0.20004, abs=1e-5)
    assert coaxial_discs(0.1, 0.2, 0.5) == pytest.approx(0.1339, abs=1e-4)
    # Reciprocity of the closed forms themselves.
    assert 2 * perpendicular_rectangles(2, 1, 1) == pytest.approx(perpendicular_rectangles(1, 2, 1))
    assert math.pi * 1.0 * coaxial_discs(1, 2, 0.7) == pytest.approx(
        math.pi * 4.0 * coaxial_discs(2, 1, 0.7)
    )


# Geometry helpers -----------------------------------------------------------------------------
def _quad_scene(*quads: list[list[float]]) -> dualight.Scene:
    scene = dualight.Scene()
    for q in quads:
        scene.add_mesh(np.asarray(q, dtype=np.float64), [[0, 1, 2, 3]])
    return scene


def _fan(radius: float, m: int, z: float, *, facing_up: bool) -> tuple[np.ndarray, np.ndarray]:
    """A disc in the plane z as a fan of m triangles around its centre; normal +z or -z."""
    t = 2 * np.pi * np.arange(m) / m
    rim = np.stack([radius * np.cos(t), radius * np.sin(t), np.full(m, z)], axis=1)
    vertices = np.concatenate([[[0.0, 0.0, z]], rim])
    faces = np.array([[0, 1 + k, 1 + (k + 1) % m] for k in range(m)])
    return vertices, faces if facing_up else faces[:, ::-1]


def _area_preserving_radius(r: float, m: int) -> float:
    """Circumradius of the regular m-gon whose area is pi r^2."""
    return r * math.sqrt(2 * math.pi / (m * math.sin(2 * math.pi / m)))


def _rows(F: _core.FormFactors) -> np.ndarray:
    return np.repeat(np.arange(F.n), np.diff(np.asarray(F.indptr)).astype(np.int64))


def _dense(F: _core.FormFactors) -> np.ndarray:
    out = np.zeros((F.n, F.n))
    out[_rows(F), np.asarray(F.indices)] = np.asarray(F.values)
    return out


def _mesh_to_mesh(patches: PatchMesh, F: _core.FormFactors, a: int, b: int) -> float:
    """Form factor from scene mesh a to mesh b: sum_{i in a} A_i sum_{j in b} F_ij / A_a."""
    rows, cols = _rows(F), np.asarray(F.indices)
    values = np.asarray(F.values, dtype=np.float64)
    m, areas = patches.mesh_index, patches.areas
    sel = (m[rows] == a) & (m[cols] == b)
    return float(np.sum(areas[rows[sel]] * values[sel]) / areas[m == a].sum())


def _relative_error(value: float, exact: float) -> float:
    return abs(value / exact - 1.0)


# 1. Differential area to a coaxial disc --------------------------------------------------------
FAN = 512  # inscribed 512-gon: area short of the disc's by 1 - sin(2 pi/M) M/(2 pi) = 2.5e-5


def _element_to_fan(point: tuple[float, float, float], r: float, h: float) -> float:
    """Sum of point_polygon_form_factor over the fan triangles (the integral is additive);
    the fan faces -z, towards the element at z = 0 looking up."""
    vertices, faces = _fan(r, FAN, h, facing_up=False)
    return sum(_core.point_polygon_form_factor(point, (0, 0, 1), vertices[f]) for f in faces)


@pytest.mark.parametrize(
    ("r", "h", "a"),
    [(1.0, 1.0, 0.0), (0.5, 2.0, 0.0), (3.0, 0.5, 0.0), (1.0, 1.0, 0.5), (1.0, 1.0, 2.0)],
)
def test_point_to_disc(r: float, h: float, a: float) -> None:
    assert 1 - math.sin(2 * math.pi / FAN) * FAN / (2 * math.pi) < 1e-4
    value = _element_to_fan((a, 0.0, 0.0), r, h)
    exact = element_to_parallel_disc(r, h, a)
    assert _relative_error(value, exact) < TOL, (value, exact)
    # Negative control: the disc 1.5 times as far (F near 1 for r = 6 h is insensitive to h).
    assert _relative_error(value, element_to_parallel_disc(r, 1.5 * h, a)) > 10 * TOL


def test_point_polygon_form_factor_conventions() -> None:
    facing = np.array([[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]], dtype=np.float64)  # normal -z
    centre = (0.5, 0.5, 0.0)
    # A unit square seen from its centre's foot at distance 1: 0.2395 (catalogue value).
    assert _core.point_polygon_form_factor(centre, (0, 0, 1), facing) == pytest.approx(
        0.23946, abs=1e-5
    )
    assert _core.point_polygon_form_factor(centre, (0, 0, 1), facing[::-1]) == 0.0  # faces away
    assert _core.point_polygon_form_factor(centre, (0, 0, -1), facing) == 0.0  # point faces away
    assert _core.point_polygon_form_factor((5, 5, 1), (0, 0, -1), facing) == 0.0  # in its plane
    for bad in (facing[:2], np.tile(facing, (3, 1))[:9]):
        with pytest.raises(ValueError, match="3 to 8 vertices"):
            _core.point_polygon_form_factor(centre, (0, 0, 1), bad)


# 2. Parallel directly opposed squares (and one rectangle) -------------------------------------
def _parallel_scene(a: float, b: float, c: float) -> dualight.Scene:
    bottom = [[0, 0, 0], [a, 0, 0], [a, b, 0], [0, b, 0]]  # normal +z
    top = [[0, 0, c], [0, b, c], [a, b, c], [a, 0, c]]  # normal -z
    return _quad_scene(bottom, top)


@pytest.mark.parametrize(("a", "b", "c"), [(1, 1, 2), (1, 1, 1), (1, 1, 0.5), (1, 2, 1)])
def test_parallel_rectangles(a: float, b: float, c: float) -> None:
    # Smooth kernel (no shared edge): one division of each input triangle's longest edge per
    # 0.5 is plenty with the 7-point rule (errors 3e-9 to 5e-6).
    patches = PatchMesh(_parallel_scene(a, b, c), max_edge=0.5)
    F, _ = form_factors(patches, quadrature=7, shadow_rays=0)
    exact = parallel_rectangles(a, b, c)
    for value in (_mesh_to_mesh(patches, F, 0, 1), _mesh_to_mesh(patches, F, 1, 0)):
        assert _relative_error(value, exact) < TOL, (value, exact)
        assert _relative_error(value, parallel_rectangles(a, b, 1.05 * c)) > 10 * TOL


# 3. Perpendicular rectangles with a common edge -----------------------------------------------
def _perpendicular_scene(w: float, h: float) -> dualight.Scene:
    """Floor w deep (normal +y) and wall h high (normal +z) sharing the unit edge on the x axis."""
    floor = [[0, 0, 0], [0, 0, w], [1, 0, w], [1, 0, 0]]
    wall = [[0, 0, 0], [1, 0, 0], [1, h, 0], [0, h, 0]]
    return _quad_scene(floor, wall)


@pytest.mark.parametrize(("w", "h"), [(1.0, 1.0), (2.0, 1.0), (0.5, 1.5)])
def test_perpendicular_rectangles_with_common_edge(w: float, h: float) -> None:
    # The kernel is singular along the shared edge (at its ends): the quadrature on the
    # receiving side converges like max_edge^2 there. Measured relative errors of F(floor ->
    # wall), quadrature 7, for w x h = 2 x 1 at max_edge 2, 1, 0.5, 0.25: 2.4e-3, 1.1e-3, 3.9e-4,
    # 1.2e-4 (0.5 x 1.5: 3.7e-3, 9.2e-4, 4.1e-4, 1.5e-4). Unit squares converge much faster
    # (5.5e-5 with a single patch per triangle).
    scene = _perpendicular_scene(w, h)
    errors = []
    for max_edge in (1.0, 0.5, 0.25):
        patches = PatchMesh(scene, max_edge=max_edge)
        F, _ = form_factors(patches, quadrature=7, shadow_rays=0)
        errors.append(
            [
                _relative_error(_mesh_to_mesh(patches, F, 0, 1), perpendicular_rectangles(w, h, 1)),
                _relative_error(_mesh_to_mesh(patches, F, 1, 0), perpendicular_rectangles(h, w, 1)),
            ]
        )
    finest = errors[-1]
    assert max(finest) < TOL, errors
    if w != h:  # converging, not merely lucky
        assert errors[0][0] > errors[1][0] > errors[2][0], errors
    # Negative control: the floor 10 % deeper.
    value = _mesh_to_mesh(patches, F, 0, 1)
    assert _relative_error(value, perpendicular_rectangles(1.1 * w, h, 1)) > 10 * TOL


def test_single_patch_centroid_rule_is_not_good_enough_at_a_shared_edge() -> None:
    # Shows the perpendicular test can fail: one patch per triangle and the 1-point rule.
    patches = PatchMesh(_perpendicular_scene(2.0, 1.0), max_edge=4.0)
    F, _ = form_factors(patches, quadrature=1, shadow_rays=0)
    value = _mesh_to_mesh(patches, F, 0, 1)
    assert _relative_error(value, perpendicular_rectangles(2, 1, 1)) > 0.1


# 4. Coaxial parallel discs --------------------------------------------------------------------
@pytest.mark.parametrize(("r1", "r2", "h"), [(1.0, 1.0, 1.0), (0.5, 2.0, 1.0), (2.0, 1.0, 0.5)])
def test_coaxial_discs(r1: float, r2: float, h: float) -> None:
    # Fans of 32 triangles with the area-preserving radius, patches no longer than h.
    m = 32
    scene = dualight.Scene()
    scene.add_mesh(*_fan(_area_preserving_radius(r1, m), m, 0.0, facing_up=True))
    scene.add_mesh(*_fan(_area_preserving_radius(r2, m), m, h, facing_up=False))
    patches = PatchMesh(scene, max_edge=h)
    F, _ = form_factors(patches, quadrature=7, shadow_rays=0)
    value = _mesh_to_mesh(patches, F, 0, 1)
    exact = coaxial_discs(r1, r2, h)
    assert _relative_error(value, exact) < TOL, (value, exact)
    reverse = _mesh_to_mesh(patches, F, 1, 0)
    assert _relative_error(reverse, coaxial_discs(r2, r1, h)) < TOL, reverse
    assert _relative_error(value, coaxial_discs(r1, r2, 1.1 * h)) > 10 * TOL


# 5. Closure -----------------------------------------------------------------------------------
CUBE = scenes.furnace(0.5, 1.0)  # six inward-facing unit quads


@pytest.mark.parametrize("shadow_rays", [0, 4])
def test_closed_cube_rows_sum_to_one(shadow_rays: int) -> None:
    # Measured: every row sum within 1.1e-8 of 1, with and without shadow rays.
    patches = PatchMesh(CUBE, max_edge=0.25)
    F, stats = form_factors(patches, quadrature=3, shadow_rays=shadow_rays, seed=3)
    sums = np.asarray(F.row_sums())
    worst = float(np.abs(sums - 1).max())
    assert worst < TOL, worst
    assert stats["row_sum_min"] == pytest.approx(sums.min())
    assert stats["row_sum_max"] == pytest.approx(sums.max())


def test_open_cube_rows_do_not_sum_to_one() -> None:
    # Negative control: without its top, the cube's rows lose the top's share.
    cube = CUBE.meshes[0]
    keep = ~np.all(cube.vertices[cube.triangles][:, :, 2] == 1.0, axis=1)  # drop the z = 1 face
    assert keep.sum() == 10
    scene = dualight.Scene()
    scene.add_mesh(cube.vertices, cube.triangles[keep])
    patches = PatchMesh(scene, max_edge=0.5)
    F, _ = form_factors(patches, quadrature=3, shadow_rays=0)
    sums = np.asarray(F.row_sums())
    assert sums.max() < 1 - 10 * TOL
    floor = patches.normals[:, 2] > 0.5
    assert np.average(sums[floor], weights=patches.areas[floor]) == pytest.approx(
        1 - parallel_rectangles(1, 1, 1), rel=TOL
    )


# 6. Reciprocity and the checks' summary -------------------------------------------------------
def test_reciprocity_on_parallel_squares() -> None:
    patches = PatchMesh(_parallel_scene(1, 1, 1), max_edge=0.25)
    F, stats = form_factors(patches, quadrature=7, shadow_rays=0)
    D = _dense(F)  # noqa: N806
    AF = patches.areas[:, None] * D  # noqa: N806
    nz = (AF > 0) | (AF.T > 0)
    rel = np.abs(AF - AF.T)[nz] / np.maximum(AF, AF.T)[nz]
    assert rel.max() < 1e-5, rel.max()  # measured 7e-7
    assert stats["reciprocity_max_relative_error"] == pytest.approx(rel.max(), rel=1e-6, abs=1e-9)
    assert 0 <= stats["reciprocity_mean_relative_error"] <= stats["reciprocity_max_relative_error"]
    sums = D.sum(axis=1)
    assert stats["row_sum_min"] == pytest.approx(sums.min(), rel=1e-6)
    assert stats["row_sum_max"] == pytest.approx(sums.max(), rel=1e-6)
    assert stats["row_sum_mean"] == pytest.approx(parallel_rectangles(1, 1, 1), rel=TOL)
    n = len(patches)
    assert stats["nonzeros"] == F.nonzeros == 2 * (n // 2) ** 2  # every cross pair, no others
    assert stats["pairs_facing"] == stats["pairs_tested"] == 2 * (n // 2) ** 2
    assert stats["rays"] == 0 and stats["quadrature"] == 7 and stats["shadow_rays"] == 0


def test_form_factor_checks_on_a_known_matrix() -> None:
    # Two patches, areas 1 and 2: A0 F01 = 0.5 = A1 F10 with F10 = 0.25 is reciprocal;
    # F10 = 0.3 is not (|0.5 - 0.6| / 0.6 = 1/6).
    areas = np.array([1.0, 2.0])
    good = _core.FormFactors.from_csr(2, [0, 1, 2], [1, 0], [0.5, 0.25])
    checks = form_factor_checks(good, areas)
    assert checks["reciprocity_max_relative_error"] == 0.0
    assert checks["row_sum_min"] == 0.25 and checks["row_sum_max"] == 0.5
    assert checks["row_sum_mean"] == pytest.approx((1 * 0.5 + 2 * 0.25) / 3)
    bad = _core.FormFactors.from_csr(2, [0, 1, 2], [1, 0], [0.5, 0.3])
    checks = form_factor_checks(bad, areas)
    assert checks["reciprocity_max_relative_error"] == pytest.approx(1 / 6, rel=1e-6)
    one_way = _core.FormFactors.from_csr(2, [0, 1, 1], [1], [0.5])  # F10 missing
    assert form_factor_checks(one_way, areas)["reciprocity_max_relative_error"] == 1.0
    with pytest.raises(ValueError, match="inconsistent"):
        _core.FormFactors.from_csr(2, [0, 1, 3], [1, 0], [0.5, 0.25])
    with pytest.raises(ValueError, match="out of range"):
        _core.FormFactors.from_csr(2, [0, 1, 2], [1, 2], [0.5, 0.25])


# 7. Culling and occlusion ---------------------------------------------------------------------
UNIT = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]  # z = 0, normal +z


@pytest.mark.parametrize(
    ("other", "case"),
    [
        ([[2, 0, 0], [3, 0, 0], [3, 1, 0], [2, 1, 0]], "coplanar"),
        ([[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], "sees the other's back"),
        ([[0, 0, -1], [0, 1, -1], [1, 1, -1], [1, 0, -1]], "behind, facing away"),
    ],
)
def test_pairs_that_cannot_exchange_give_exactly_zero(other: list, case: str) -> None:
    patches = PatchMesh(_quad_scene(UNIT, other), max_edge=0.25)
    F, stats = form_factors(patches, quadrature=7, shadow_rays=4)
    assert F.nonzeros == 0, case
    assert stats["pairs_tested"] == 0 and stats["rays"] == 0, case


def test_blocker_occludes_with_shadow_rays_only() -> None:
    top = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]  # faces the unit square
    blocker = [[-1, -1, 0.5], [2, -1, 0.5], [2, 2, 0.5], [-1, 2, 0.5]]  # wider than both
    patches = PatchMesh(_quad_scene(UNIT, top, blocker), max_edge=0.25)
    exact = parallel_rectangles(1, 1, 1)
    F, _ = form_factors(patches, quadrature=7, shadow_rays=0)
    for a, b in ((0, 1), (1, 0)):
        assert _relative_error(_mesh_to_mesh(patches, F, a, b), exact) < TOL
    F, stats = form_factors(patches, quadrature=7, shadow_rays=4, seed=5)
    assert stats["rays"] > 0
    for a, b in ((0, 1), (1, 0)):
        assert _mesh_to_mesh(patches, F, a, b) < 1e-6
    assert _mesh_to_mesh(patches, F, 1, 2) > 0.5  # the blocker is what the top square sees


@pytest.mark.parametrize("gap", [1e-3, 1e-5])
def test_wall_blocks_a_patch_that_touches_it(gap: float) -> None:
    # A ceiling (y = 1, facing down, x in [0, 1]) and a floor strip (y = 0, facing up, x in
    # [1, 1 + gap]) on the two sides of a wall x = 1 from floor to ceiling: every segment from
    # one to the other crosses the wall, so with shadow rays both form factors must be 0.
    ceiling = [[0, 1, 0], [1, 1, 0], [1, 1, 1], [0, 1, 1]]
    strip = [[1, 0, 0], [1, 0, 1], [1 + gap, 0, 1], [1 + gap, 0, 0]]
    wall = [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]]
    open_patches = PatchMesh(_quad_scene(ceiling, strip), max_edge=2.0)
    F_open, _ = form_factors(open_patches, quadrature=3, shadow_rays=0)
    unoccluded = _mesh_to_mesh(open_patches, F_open, 0, 1)
    assert unoccluded > 0  # without the wall they exchange light
    patches = PatchMesh(_quad_scene(ceiling, strip, wall), max_edge=2.0)
    F, _ = form_factors(patches, quadrature=3, shadow_rays=16)
    assert _mesh_to_mesh(patches, F, 1, 0) == 0.0  # strip -> ceiling
    leak = _mesh_to_mesh(patches, F, 0, 1)  # ceiling -> strip
    # Geometry is float32: a strip of width `gap` next to x = 1 holds gap / ulp(1) distinct
    # x values, and targets that round to x = 1.0 lie on the wall's bottom edge, where hit or
    # miss is undecidable. Only that share may leak; wider strips must be exactly dark.
    ulps = gap / np.spacing(np.float32(1.0))
    if ulps > 1000:
        assert leak == 0.0
    else:
        assert leak <= 2.0 / ulps * unoccluded, (leak, unoccluded)


def test_form_factor_options_are_validated() -> None:
    patches = PatchMesh(_parallel_scene(1, 1, 1), max_edge=1.0)
    with pytest.raises(ValueError, match="quadrature"):
        form_factors(patches, quadrature=5)
    with pytest.raises(ValueError, match="shadow_rays"):
        form_factors(patches, shadow_rays=-1)
