"""Skipping what a scene does not need: the scene's features, and for each skip that it
happens where the scene allows it, never where it does not, and leaves the answer unchanged
(with a negative control: the same test fails for a deliberately wrong scene)."""

from __future__ import annotations

import numpy as np
import pytest

import dualight as dl
from dualight import metrics, scenes
from dualight.radiosity import solve

RES = (32, 32)


def _furnace(rho: float = 0.5, camera_inside: bool = True) -> dl.Scene:
    furnace = scenes.furnace(rho, 1.0, resolution=RES)
    if camera_inside:
        return furnace
    outside = dl.Camera(
        origin=(0.5, 0.5, -2.0), target=(0.5, 0.5, 0.5), up=(0, 1, 0), fov=40.0, resolution=RES
    )
    scene = dl.Scene(camera=outside)
    # A cube seen from outside: its faces turned outwards, so the camera sees them.
    cube = furnace.meshes[0]
    scene.add_mesh(
        cube.vertices, cube.triangles[:, ::-1], reflectance=(rho,) * 3, emission=(1.0,) * 3
    )
    return scene


# features -------------------------------------------------------------------------------------
def test_features_of_the_standard_scenes() -> None:
    furnace = scenes.furnace().features
    assert furnace["closed"] and furnace["convex_enclosure"] and furnace["unoccluded"]
    assert furnace["all_diffuse"] and not furnace["specular"]
    assert furnace["emitter_triangles"] == 12

    cornell = scenes.cornell_box(RES).features
    # Open at the front, and the blocks (and the light hanging below the ceiling) occlude.
    assert not cornell["closed"] and not cornell["convex_enclosure"]
    assert cornell["convexity_checked"] and cornell["all_diffuse"]

    caustics = scenes.cornell_box(RES, variant="caustics").features
    assert caustics["specular"] and caustics["dielectric"] and not caustics["all_diffuse"]
    assert not caustics["unoccluded"]


def test_a_single_quad_is_a_convex_enclosure_but_not_closed() -> None:
    scene = dl.Scene()
    scene.add_mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]], emission=(1, 1, 1))
    features = scene.features
    assert features["convex_enclosure"] and not features["closed"]


def test_the_camera_outside_the_enclosure_is_reported() -> None:
    inside = dl.render(_furnace(), "path", spp=1, progress=False)
    outside = dl.render(_furnace(camera_inside=False), "path", spp=1, progress=False)
    assert inside.stats["scene"]["camera_enclosed"]
    assert not outside.stats["scene"]["camera_enclosed"]
    assert outside.stats["scene"]["emitters_facing_camera"] > 0


# shadow rays in a convex enclosure --------------------------------------------------------------
@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_unneeded_shadow_rays_are_skipped_and_the_image_is_unchanged(method: str) -> None:
    kw = dict(spp=128, progress=False)
    on = dl.render(_furnace(), method, seed=1, **kw)
    off = dl.render(_furnace(), method, seed=1, skip=False, **kw)
    assert on.stats["skipped"]["shadow_rays"] > 0 and on.stats["skipped"]["enabled"]
    assert off.stats["skipped"]["shadow_rays"] == 0
    # Every ray the skip saves was a shadow ray of the full render.
    assert off.stats["rays"] - on.stats["rays"] == on.stats["skipped"]["shadow_rays"]
    # Same seed: the same paths, and every skipped ray would have found its target visible.
    np.testing.assert_allclose(np.asarray(on), np.asarray(off), rtol=1e-6, atol=1e-7)
    # Independent seeds: equal in expectation (Welch, per 4x4 block), and the same test
    # rejects a furnace of albedo 0.45 instead of 0.5 (negative control).
    other = dl.render(_furnace(), method, seed=2, skip=False, **kw)
    wrong = dl.render(_furnace(0.45), method, seed=2, skip=False, **kw)
    ok = metrics.welch_test(on, on.variance, other, other.variance, block=4)
    bad = metrics.welch_test(on, on.variance, wrong, wrong.variance, block=4)
    assert ok.pass_fraction == 1.0, ok.max_z
    assert bad.pass_fraction < 1.0, bad.max_z


# strategies that find nothing: scenes lit by delta lights only --------------------------------
def test_strategies_that_cannot_find_delta_lights_are_skipped_and_said() -> None:
    """With only point, spot or directional lights no path hits an emitter: BDPT does not
    evaluate s = 0 and MMLT does not offer it; the stats say so, and say nothing of it where
    an area light or an environment can be hit. (BDPT's images of such scenes stayed
    bit-identical to those before the skip: issue 20's note.)"""
    said = "s = 0: every emitter is a delta light (no path hits one)"
    point = scenes.cornell_box((16, 16), variant="point")
    kw = dict(spp=8, seed=3, max_depth=5, progress=False)
    img = dl.render(point, "bdpt", **kw)
    assert img.stats["skipped"]["strategies"] == [said]
    mmlt = dl.render(point, "mmlt", mutations_per_pixel=2, max_depth=5, progress=False)
    assert mmlt.stats["skipped"]["strategies"] == [said]
    kept = dl.render(point, "mmlt", mutations_per_pixel=2, max_depth=5, progress=False, skip=False)
    assert "strategies" not in kept.stats["skipped"]
    for lit in (scenes.cornell_box((16, 16)), scenes.cornell_box((16, 16), variant="sky")):
        assert "strategies" not in dl.render(lit, "bdpt", **kw).stats["skipped"]


@pytest.mark.parametrize("method", ["pssmlt", "mlt"])
def test_metropolis_methods_skip_shadow_rays_too(method: str) -> None:
    kw = dict(mutations_per_pixel=8, progress=False, mlt={"bootstrap": 4000, "direct_spp": 4})
    on = dl.render(_furnace(), method, seed=1, **kw)
    off = dl.render(_furnace(), method, seed=1, skip=False, **kw)
    assert on.stats["skipped"]["shadow_rays"] > 0 and off.stats["skipped"]["shadow_rays"] == 0
    np.testing.assert_allclose(np.asarray(on), np.asarray(off), rtol=1e-5, atol=1e-6)


def test_no_shadow_ray_is_skipped_where_something_could_block_it() -> None:
    cornell = dl.render(scenes.cornell_box(RES), "bdpt", spp=2, progress=False)
    assert cornell.stats["skipped"]["shadow_rays"] == 0
    # The cube seen from outside is convex, but the camera is not inside it.
    outside = dl.render(_furnace(camera_inside=False), "bdpt", spp=2, progress=False)
    assert outside.stats["skipped"]["shadow_rays"] == 0
    glass = dl.render(scenes.cornell_box(RES, variant="caustics"), "path", spp=1, progress=False)
    assert glass.stats["skipped"]["shadow_rays"] == 0


# MLT mutations -----------------------------------------------------------------------------------
def test_mlt_leaves_out_specular_perturbations_in_a_diffuse_scene() -> None:
    kw = dict(mutations_per_pixel=4, progress=False, mlt={"bootstrap": 4000, "direct_spp": 2})
    diffuse = dl.render(scenes.cornell_box(RES), "mlt", seed=3, **kw)
    assert diffuse.stats["skipped"]["mutations"] == [
        "caustic_perturbation",
        "multi_chain_perturbation",
    ]
    full = dl.render(scenes.cornell_box(RES), "mlt", seed=3, skip=False, **kw)
    assert full.stats["skipped"]["mutations"] == []
    # They never suited a path of a diffuse scene: the chains make the same draws.
    np.testing.assert_array_equal(np.asarray(diffuse), np.asarray(full))
    caustics = dl.render(scenes.cornell_box(RES, variant="caustics"), "mlt", seed=3, **kw)
    assert caustics.stats["skipped"]["mutations"] == []
    assert caustics.stats["mutation_types"]["caustic_perturbation"]["proposed"] > 0


# radiosity ---------------------------------------------------------------------------------------
def test_radiosity_skips_visibility_rays_in_a_convex_enclosure() -> None:
    kw = dict(max_edge=0.25)
    on = solve(scenes.furnace(0.5, 1.0), "direct", **kw)
    off = solve(scenes.furnace(0.5, 1.0), "direct", skip=False, **kw)
    assert on.stats["skipped"]["visibility_rays"] > 0
    assert on.stats["form_factors"]["rays"] == 0 and off.stats["form_factors"]["rays"] > 0
    np.testing.assert_allclose(on.B, off.B, rtol=1e-6)
    # The analytic furnace value holds; albedo 0.45 (negative control) misses it.
    exact = scenes.furnace_radiance(0.5, 1.0) * np.pi
    wrong = solve(scenes.furnace(0.45, 1.0), "direct", **kw)
    assert np.max(np.abs(on.B / exact - 1)) < 1e-4
    assert np.max(np.abs(wrong.B / exact - 1)) > 1e-2


def test_hierarchical_radiosity_skips_visibility_rays_in_a_convex_enclosure() -> None:
    on = solve(scenes.furnace(0.5, 1.0), "hierarchical", epsilon=1e-2)
    off = solve(scenes.furnace(0.5, 1.0), "hierarchical", epsilon=1e-2, skip=False)
    assert on.stats["skipped"]["visibility_rays"] > 0
    assert off.stats["skipped"]["visibility_rays"] == 0
    np.testing.assert_allclose(on.measurement_primal, off.measurement_primal, rtol=1e-6)


def test_a_view_only_solve_computes_rows_of_important_patches_only() -> None:
    sealed = scenes.rooms(n=4, doors=False)  # the camera's room is closed off from the others
    kw = dict(max_edge=1.0)
    view = solve(sealed, "direct", view_only=True, **kw)
    full = solve(sealed, "direct", **kw)
    skipped = view.stats["skipped"]["rows"]
    n = view.stats["patches"]
    assert 0.5 * n < skipped < n  # three of the four rooms
    assert view.solved is not None and np.count_nonzero(view.solved) == n - skipped
    assert full.stats["skipped"]["rows"] == 0 and full.solved is None
    # The same measurement, from both sides; importance is zero off the important patches.
    np.testing.assert_allclose(view.measurement_primal, full.measurement_primal, rtol=1e-6)
    np.testing.assert_allclose(view.measurement_dual, full.measurement_dual, rtol=1e-6)
    assert np.all(view.I[~view.solved] == 0)
    np.testing.assert_allclose(view.B[view.solved], full.B[view.solved], rtol=1e-5, atol=1e-9)
    # Negative control: a brighter light in the camera's room changes the measurement.
    brighter = solve(
        scenes.rooms(n=4, doors=False, light_radiance=11.0), "direct", view_only=True, **kw
    )
    assert np.all(np.abs(brighter.measurement_primal / full.measurement_primal - 1) > 1e-2)
    # With doors, every room matters for the view: nothing is skipped.
    open_plan = solve(scenes.rooms(n=4), "gauss_seidel", view_only=True, **kw)
    assert open_plan.stats["skipped"]["rows"] == 0


def test_a_view_only_solution_refuses_other_views() -> None:
    sealed = scenes.rooms(n=4, doors=False)
    view = solve(sealed, "gauss_seidel", view_only=True, max_edge=1.0)
    view.render()  # its own view is fine
    elsewhere = scenes.rooms(n=4, doors=False, camera_room=3).camera
    with pytest.raises(ValueError, match="view_only"):
        view.render(elsewhere)
    with pytest.raises(ValueError, match="view_only"):
        solve(sealed, "gauss_seidel", precomputed=(view.form_factors, view.stats["form_factors"]))


def test_skip_options_are_checked() -> None:
    with pytest.raises(TypeError, match="skip"):
        dl.render(_furnace(), "path", spp=1, progress=False, skip="no")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="view_only"):
        solve(scenes.furnace(), "direct", view_only=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="skip=True"):
        solve(scenes.furnace(), "direct", view_only=True, skip=False)
    with pytest.raises(ValueError, match="hierarchical"):
        solve(scenes.furnace(), "hierarchical", view_only=True)
