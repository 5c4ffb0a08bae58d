"""Area emitters whose radiance is a texture (issue 20; Mitsuba 3's ``area`` emitter with a
``bitmap`` or ``checkerboard`` ``radiance``): validation, scene files and Mitsuba's dict, and
radiosity's patch and element means. The comparisons with Mitsuba 3 are the ``lamp`` cases of
test_pathspace_vs_mitsuba.py and test_pssmlt.py; the core's lookups and power are checked in
tests/cpp/test_emitter.cpp."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest

import dualight
from dualight import scenes
from dualight.textures import Bitmap, Checkerboard

QUAD = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
FACES = [[0, 1, 2, 3]]


@pytest.mark.parametrize(
    ("texture", "message"),
    [
        (Bitmap(data=-np.ones((2, 2, 3))), r"emission: the texture's values must lie in \[0, "),
        (Checkerboard(1.0, 2e12), r"emission: the texture's values must lie in \[0, "),
        (Bitmap(data=np.zeros((2, 2, 3))), "the emission texture is black"),
    ],
)
def test_add_mesh_refuses_bad_emission_textures(texture, message: str) -> None:
    scene = dualight.Scene()
    with pytest.raises(ValueError, match=message):
        scene.add_mesh(QUAD, FACES, emission=texture, name="lamp")
    assert not scene.meshes


def test_a_textured_light_is_an_emitter_of_its_textures_mean() -> None:
    scene = scenes.cornell_box((16, 16), variant="lamp")
    light = scene.meshes[-1]
    assert isinstance(light.emission_texture, Bitmap)
    np.testing.assert_allclose(light.emission, scenes.CORNELL_LIGHT_RADIANCE, rtol=1e-5)
    assert light.is_emitter and scene.has_emitters
    plugin = light._mitsuba_emitter()
    assert plugin["type"] == "area" and plugin["radiance"]["type"] == "bitmap"
    copy = pickle.loads(pickle.dumps(scene))
    a = dualight.render(scene, "bdpt", spp=2, seed=1, progress=False)
    b = dualight.render(copy, "bdpt", spp=2, seed=1, progress=False)
    assert np.array_equal(np.asarray(a), np.asarray(b))


def test_mitsuba_xml_round_trip(tmp_path: Path) -> None:
    """The texture from an array goes to an EXR beside the XML as the emitter's ``radiance``;
    read back, it renders the same image."""
    scene = scenes.cornell_box((16, 16), variant="lamp", texture_shift=0.25)
    dualight.save_mitsuba_xml(scene, tmp_path / "s.xml")
    assert '<texture type="bitmap" name="radiance">' in (tmp_path / "s.xml").read_text()
    back = dualight.load_mitsuba_xml(tmp_path / "s.xml")
    read = back.meshes[-1].emission_texture
    assert isinstance(read, Bitmap)
    np.testing.assert_array_equal(read.texels, scene.meshes[-1].emission_texture.texels)
    a = dualight.render(scene, "path", spp=4, seed=3, progress=False)
    b = dualight.render(back, "path", spp=4, seed=3, progress=False)
    np.testing.assert_allclose(np.asarray(a), np.asarray(b), rtol=1e-5, atol=1e-6)


def test_mitsuba_xml_reads_a_checkerboard_radiance_and_refuses_it_on_a_sphere(
    tmp_path: Path,
) -> None:
    def load(shape: str) -> dualight.Scene:
        (tmp_path / "s.xml").write_text(
            f'<scene version="3.0.0"><shape type="{shape}"><emitter type="area">'
            '<texture type="checkerboard" name="radiance"><rgb name="color0" value="4"/>'
            '<rgb name="color1" value="0"/></texture></emitter></shape></scene>'
        )
        return dualight.load_mitsuba_xml(tmp_path / "s.xml")

    (mesh,) = load("rectangle").meshes
    assert isinstance(mesh.emission_texture, Checkerboard)
    assert mesh.emission == (2.0, 2.0, 2.0) and mesh.material.rgb_reflectance == (0, 0, 0)
    with pytest.raises(ValueError, match="an emitted radiance texture on a sphere"):
        load("sphere")


def test_radiosity_takes_each_patchs_mean_radiance() -> None:
    """The uniform solvers' E is pi x the texture's mean over each patch: the lamp's patches
    differ, their area-weighted mean is the texture's; <R, B> = <I, E>, and the light the
    patches reflect to the camera, <R, B - E>, agrees with the path tracer's (its paths of
    more than one segment) up to radiosity's discretisation; a light 10 % dimmer fails that.
    (The lamp seen directly is left out: its patches' means, seen in perspective, stand for
    a texture coarser than they are.) Hierarchical radiosity's elements likewise."""
    from dualight import radiosity

    def solved(scale: float) -> radiosity.Solution:
        scene = scenes.cornell_box((32, 32), variant="lamp", light_scale=scale)
        return radiosity.solve(scene, method="gauss_seidel", max_edge=80.0)

    solution = solved(1.0)
    np.testing.assert_allclose(solution.measurement_primal, solution.measurement_dual, rtol=1e-3)
    patches = solution.patches
    lamp = patches.mesh_index == patches.mesh_index.max()
    E = patches.emission[lamp]
    assert E[:, 0].std() > 0.3 * E[:, 0].mean()  # the texture varies over the lamp
    mean = (E * patches.areas[lamp, None]).sum(0) / patches.areas[lamp].sum() / np.pi
    np.testing.assert_allclose(mean, scenes.CORNELL_LIGHT_RADIANCE, rtol=0.01)
    scene = scenes.cornell_box((32, 32), variant="lamp")
    path = np.asarray(dualight.render(scene, "path", spp=512, seed=4, progress=False))
    # The same seed: the first segments are the same samples, and the lamp seen directly
    # (most of the blue image's variance) cancels.
    seen = np.asarray(dualight.render(scene, "path", spp=512, seed=4, max_depth=1, progress=False))
    reflected = (path - seen).mean(axis=(0, 1))

    def ratio(s: radiosity.Solution) -> np.ndarray:
        return np.sum(s.R * (s.B - s.E), axis=0) / reflected

    control = ratio(solved(0.9))
    print(f"\n<R, B - E> / path {np.round(ratio(solution), 4)}; light x0.9 {np.round(control, 4)}")
    assert np.all(np.abs(ratio(solution) - 1) < TOLERANCE)
    assert np.any(np.abs(control - 1) > TOLERANCE)
    # Hierarchical radiosity: each element emits pi x the texture's mean over it, at every
    # level (the lamp's leaves differ), and agrees as closely.
    tree = radiosity.solve(scene, method="hierarchical", epsilon=1e-4)
    assert tree.duality_gap < 1e-5
    leaves = tree.E[tree.patches.mesh_index == tree.patches.mesh_index.max(), 0]
    assert leaves.min() < 0.5 * leaves.max()
    print(f"hierarchical <R, B - E> / path {np.round(ratio(tree), 4)}")
    assert np.all(np.abs(ratio(tree) - 1) < TOLERANCE)


# Radiosity's discretisation at max_edge 80, as test_emitters.py's first-shot tests allow.
TOLERANCE = 0.05
