"""Each mutation of path-space MLT on its own keeps the target density (issue 6), and the
transition densities the mutations report are right.

Stationarity. Chains start from paths resampled from the bootstrap in proportion to their
weight, and the image is b_hat x (the chains' averages): over bootstraps, b_hat x (the start
distribution) equals f exactly, and a kernel that leaves f invariant keeps it. So chains that
use a single mutation (staying put where it does not suit; `_testing.check_mlt_single_mutation`)
still give an unbiased image although they are not ergodic, and a mutation whose acceptance is
wrong gives a biased one. Each mutation's image is compared with BDPT's on the same scene
(direct_spp = 0: the chains carry all the light, as in BDPT's image), and the same comparison
must fail when the acceptance inverts the transition ratio T(y -> x) / T(x -> y) (the
stationary density then leans on T(x -> y)^2 instead of on nothing).

What is compared (luminance: Rec. 709 weights of linear RGB):
* the image's sum per channel: b_hat times the chains' mean colour;
* its shape: each 8 x 8 block's sum per channel divided by the image's luminance sum. b_hat's
  noise is common to every block, so dividing it out sharpens the test of where the chains
  spend their time; the sums test b_hat.
Errors are in standard errors: the spread over NS = 24 independent seeds (bootstrap and chains;
Student-t with 23 degrees of freedom) plus BDPT's own variance (for the shares a bound that takes
the block and the sum as fully anti-correlated). 3 sums + 3 x 16 blocks = 51 tests at a
family-wise level of 1 % (Sidak) need |t| < 4.42 at 23 degrees of freedom: T_MAX = 4.5. Blocks
under 5 % of the mean block luminance are left out (see Scenes).

Scenes. The caustic Cornell box (32 x 32, up to 4 segments) suits the bidirectional and lens
subpath mutations and the lens perturbation. Only 3.5 % of its chains' steps find a caustic
path, though, and there the caustic and multi-chain perturbations' inverted controls pass (max
|t| 2.9 and 2.7, as the correct kernels' 2.9 and 2.7): the few chains that move are lost in the
noise of those that stay put. Two scenes hold nothing but caustic paths, a floor lit through a
specular sphere out of the camera's view: `_mirror_caustic` (L S D E off a convex mirror) for
the caustic perturbation, `_glass_caustic` (mostly L S S D E through glass, direct light apart)
for the multi-chain perturbation, whose controls do not fail on the mirror with chains of this
length (its T ratio changes slowly there; only 64 chains of 4096 steps made the inverted one
fail, at 6.7). On the glass scene the caustic perturbation's controls pass (max |t| 1.1 and 1.6):
its wrong kernels move light within the bright caustic's blocks. Blocks under 5 % of the mean
block luminance (a caustic's faint fringe) are left out: few chains reach them, the spread
over seeds is then heavy-tailed and underestimates their error (|t| up to 12 for a correct
kernel with 64 chains).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pytest

import dualight
from dualight import _core, _testing, scenes

NS = 24  # seeds per image set
T_MAX = 4.5
BLOCK = 8
MIN_BLOCK = 0.05  # share of the mean block luminance under which a block is left out
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


_QUAD = np.array([[0, 2, 1], [0, 3, 2]])


def _floor_scene(height: float) -> dualight.Scene:
    """A floor seen from a camera at `height` looking down at it (the scenes below add a light
    and a specular sphere out of the camera's view)."""
    cam = dualight.Camera(
        origin=(0, height, -2.2), target=(0, 0, 0.4), up=(0, 1, 0), fov=50, resolution=(32, 32)
    )
    scene = dualight.Scene(camera=cam)
    floor = np.array([[-1.5, 0, -1.5], [1.5, 0, -1.5], [1.5, 0, 1.5], [-1.5, 0, 1.5]], float)
    scene.add_mesh(floor, _QUAD, reflectance=(0.7, 0.6, 0.5), name="floor")
    return scene


def _light(y: float, facing_up: bool, z: float) -> np.ndarray:
    s = 0.1
    corners = [[-s, y, -s], [s, y, -s], [s, y, s], [-s, y, s]]
    return np.array(corners if facing_up else corners[::-1], float) + [0, 0, z]


def _mirror_caustic() -> dualight.Scene:
    """A floor lit only through a convex mirror sphere by a small light facing up at it; the
    camera, below the light's plane, sees neither the light's front nor the mirror, so every
    path that carries light in 3 segments is L S D E."""
    scene = _floor_scene(0.8)
    v, f = scenes.icosphere(centre=(0, 1.6, 0.4), radius=0.45, subdivisions=3)
    scene.add_mesh(v, f, material=dualight.Mirror(), name="mirror")
    light = _light(1.0, True, 0.4)
    scene.add_mesh(light, _QUAD, reflectance=(0, 0, 0), emission=(20, 20, 20), name="light")
    return scene


def _glass_caustic() -> dualight.Scene:
    """A glass sphere under a small light facing down focuses it on the floor; both are above
    the camera's view, so the chains (paths of 3 and 4 segments; the direct light is rendered
    apart) hold L S S D E through the sphere and L S D E off its surface."""
    scene = _floor_scene(0.9)
    v, f = scenes.icosphere(centre=(0, 1.4, 0.5), radius=0.4, subdivisions=3)
    scene.add_mesh(v, f, material=dualight.Dielectric(ior=1.5), name="glass")
    light = _light(2.0, False, 0.5)
    scene.add_mesh(light, _QUAD, reflectance=(0, 0, 0), emission=(20, 20, 20), name="light")
    return scene


SCENES = {
    "caustic_box": lambda: scenes.cornell_box(resolution=(32, 32), variant="caustics"),
    "mirror_caustic": _mirror_caustic,
    "glass_caustic": _glass_caustic,
    # Issue 19: rough gold, frosted glass and a rough-plastic floor. Glossy vertices are
    # connectable (only Dirac lobes make a vertex specular), so every mutation treats them as
    # it treats diffuse ones.
    "glossy_box": lambda: scenes.cornell_box(resolution=(32, 32), variant="glossy"),
    # Issue 20: the open-top box under an environment map and a sun. Paths end at a
    # vertex at infinity, which the light side's walks start from (the distant disk) and the
    # camera side's never reach (its density from there is 0, as a point light's).
    "envmap_box": lambda: scenes.cornell_box(resolution=(32, 32), variant="envmap"),
    "sun_box": lambda: scenes.cornell_box(resolution=(32, 32), variant="sun"),
    # The classic box whose ceiling light emits a texture: new light subpaths start at the
    # texture's value at their point (its surface coordinates).
    "lamp_box": lambda: scenes.cornell_box(resolution=(32, 32), variant="lamp"),
}


@dataclass(frozen=True)
class Case:
    scene: str
    max_depth: int
    direct_spp: int  # 0: the chains carry all the light; > 0: paths of 1-2 segments by BDPT
    chains: int
    mutations_per_pixel: int
    min_acceptance: float = 0.1  # of the mutation's proposals: the chains must move


# Long chains where the mutation moves little per step, so that a wrong stationary density
# has time to show.
CASES = {
    "bidirectional": Case("caustic_box", 4, 0, 1024, 64),
    "lens_subpath": Case("caustic_box", 4, 0, 1024, 64),
    "lens_perturbation": Case("caustic_box", 4, 0, 256, 128),
    "caustic_perturbation": Case("mirror_caustic", 3, 0, 1024, 64),
    "multi_chain_perturbation": Case("glass_caustic", 4, 128, 1024, 64),
    "bidirectional (glossy)": Case("glossy_box", 4, 0, 1024, 64),
    "lens_perturbation (glossy)": Case("glossy_box", 4, 0, 256, 128),
    # Under the map 7 % of the bidirectional mutation's proposals are accepted (4 % under a
    # constant sky): most new light subpaths enter from the distant disk and miss the box's
    # opening, so the proposal fails. Its chains still move (1024 chains x 64 mutations per
    # pixel); the floor of this case is 5 %. Inverting T's ratio fails it (max |t| 27).
    "bidirectional (envmap)": Case("envmap_box", 4, 0, 1024, 64, min_acceptance=0.05),
    "lens_subpath (envmap)": Case("envmap_box", 4, 0, 1024, 64),
    "bidirectional (sun)": Case("sun_box", 4, 0, 1024, 64),
    "bidirectional (lamp)": Case("lamp_box", 4, 0, 1024, 64),
}


def _blocks(image: np.ndarray) -> np.ndarray:
    """Per channel sums of BLOCK x BLOCK blocks: (blocks, 3)."""
    h, w, _ = image.shape
    return image.reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK, 3).sum(axis=(1, 3)).reshape(-1, 3)


@functools.cache
def _reference(scene_name: str, max_depth: int) -> tuple[np.ndarray, np.ndarray]:
    """BDPT's blocks and their variances (1024 spp: its variance is small beside the chains')."""
    scene = SCENES[scene_name]()
    image = dualight.render(scene, "bdpt", spp=1024, max_depth=max_depth, seed=7, progress=False)
    return _blocks(np.asarray(image, np.float64)), _blocks(np.asarray(image.variance, np.float64))


def _single_mutation_images(mutation: str, transition_ratio: str) -> tuple[np.ndarray, dict]:
    """NS images' blocks (NS, blocks, 3) and the summed counts of the mutation."""
    case = CASES[mutation]
    scene = SCENES[case.scene]()
    compiled, camera = scene._compile(), scene.camera._compile()
    blocks, counts = [], {"proposed": 0, "accepted": 0, "mutations": 0}
    for seed in range(NS):
        options = _core.MltOptions(
            mutations_per_pixel=case.mutations_per_pixel,
            max_depth=case.max_depth,
            seed=seed,
            chains=case.chains,
            bootstrap=20000,
            direct_spp=case.direct_spp,
        )
        name = mutation.split(" ")[0]  # "lens_perturbation (glossy)": the scene's variant
        out = _testing.check_mlt_single_mutation(compiled, camera, options, name, transition_ratio)
        blocks.append(_blocks(np.asarray(out["mean"], np.float64)))
        stats = out["stats"]["mutation_types"][name]
        counts["proposed"] += stats["proposed"]
        counts["accepted"] += stats["accepted"]
        counts["mutations"] += out["stats"]["mutations"]
    return np.array(blocks), counts


def _t_values(
    blocks: np.ndarray, ref: np.ndarray, ref_var: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """t of the channel sums (3,) and of the blocks' shares of the luminance sum (kept, 3)."""
    sums, ref_sums, ref_sum_var = blocks.sum(axis=1), ref.sum(axis=0), ref_var.sum(axis=0)
    t_sums = (sums.mean(axis=0) - ref_sums) / np.sqrt(
        sums.var(axis=0, ddof=1) / len(blocks) + ref_sum_var
    )
    lum = sums @ LUMINANCE
    shares = blocks / lum[:, None, None]
    ref_lum, ref_lum_var = ref_sums @ LUMINANCE, ref_sum_var @ LUMINANCE**2
    ref_shares = ref / ref_lum
    # Bound of the ratio's variance (delta method, correlation -1 between block and sum).
    ref_share_var = (np.sqrt(ref_var) / ref_lum + ref * np.sqrt(ref_lum_var) / ref_lum**2) ** 2
    keep = ref @ LUMINANCE > MIN_BLOCK * ref_lum / len(ref)
    shares, ref_shares, ref_share_var = shares[:, keep], ref_shares[keep], ref_share_var[keep]
    t_blocks = (shares.mean(axis=0) - ref_shares) / np.sqrt(
        shares.var(axis=0, ddof=1) / len(blocks) + ref_share_var
    )
    return t_sums, t_blocks


def _max_t(mutation: str, transition_ratio: str) -> tuple[float, float, dict]:
    """Max |t| of the channel sums and of the block shares, and the mutation's counts."""
    case = CASES[mutation]
    blocks, counts = _single_mutation_images(mutation, transition_ratio)
    t_sums, t_blocks = _t_values(blocks, *_reference(case.scene, case.max_depth))
    return float(np.abs(t_sums).max()), float(np.abs(t_blocks).max()), counts


# Marked long (make test-long) for make test's time: the sun's bidirectional chains and the
# map's lens subpaths (make test keeps the map's bidirectional chains, which start light
# subpaths at infinity and connect to it; the textured lamp's bidirectional chains stay too:
# its block tests against Mitsuba with the Metropolis methods are long).
LONG_CASES = {"bidirectional (sun)", "lens_subpath (envmap)"}


@pytest.mark.parametrize(
    "mutation",
    [pytest.param(m, marks=[pytest.mark.long] if m in LONG_CASES else []) for m in sorted(CASES)],
)
def test_single_mutation_chains_match_bdpt(mutation: str) -> None:
    """Chains of one mutation give BDPT's image (|t| < T_MAX for every channel sum and block
    share); the mutation is proposed for at least 15 % of the chains' steps and accepted for at
    least its case's floor of its proposals (10 %), so the chains move. Inverting T's ratio in
    the acceptance (the stationary density becomes f T(x->y)^2-like instead of f) fails the
    same test."""
    t_sum, t_block, counts = _max_t(mutation, "used")
    proposed_share = counts["proposed"] / counts["mutations"]
    acceptance = counts["accepted"] / counts["proposed"]
    assert proposed_share > 0.15 and acceptance > CASES[mutation].min_acceptance, (
        proposed_share,
        acceptance,
    )
    assert t_sum < T_MAX and t_block < T_MAX, f"max |t|: sums {t_sum:.2f}, blocks {t_block:.2f}"
    c_sum, c_block, _ = _max_t(mutation, "inverted")
    assert max(c_sum, c_block) > T_MAX, f"control max |t|: sums {c_sum:.2f}, blocks {c_block:.2f}"


def test_single_mutation_hook_rejects_unknown_names() -> None:
    scene = scenes.cornell_box(resolution=(8, 8))
    options = _core.MltOptions(mutations_per_pixel=1, bootstrap=100, chains=4)
    args = (scene._compile(), scene.camera._compile(), options)
    with pytest.raises(ValueError, match="unknown mutation"):
        _testing.check_mlt_single_mutation(*args, "lens")
    with pytest.raises(ValueError, match="transition_ratio"):
        _testing.check_mlt_single_mutation(*args, "lens_subpath", "swapped")


# Finite differences: corners are traced in float, so the image's area carries rounding of
# about 1e-7 x (coordinates) / (square side) per side: 1e-4 to 1e-3 with these steps (halving
# them doubles the error, so rounding, not the O(step^2) curvature, dominates).
FD_TOLERANCE = 5e-3


@pytest.mark.parametrize(
    "mutation", ["lens_perturbation", "caustic_perturbation", "multi_chain_perturbation"]
)
def test_perturbation_densities_match_finite_differences(mutation: str) -> None:
    """The density each perturbation reports for its proposal y, per block of its map (the film
    offset to the first non-specular vertex from the camera; an angular offset at a diffuse
    vertex to the next one through the specular chain), equals the area density measured on the
    surface: the area of the image of a 0.02 px square of film (or a 1e-3 rad square of
    directions), traced through the same facets, per unit film area (whole film: x pixels) or
    per steradian. Specular vertices follow full_path.h's Radiance-form convention, where f and
    T both carry the folded G(a, s) G(s, b) in place of the geometric unfolded G_u(a, b), so
    for chains of one flat reflection (icosphere facets) the reported factor times
    G_u / (G G) is compared: it is the geometric Jacobian if and only if f / T, which the
    acceptance uses, is f's geometric value over it. Longer chains and refractions are left
    out. The blocks' reported factors must multiply to the T(x -> y) that `propose` returned
    (checked in C++). Control: the reported density without the cosine at the moved vertex
    (the solid-angle-to-area factor) is off by more than 10 x the tolerance for most checks."""
    scene = SCENES["caustic_box"]()
    options = _core.MltOptions(max_depth=4, seed=3, direct_spp=0)
    checks = np.array(
        _testing.check_mlt_perturbation_densities(
            scene._compile(), scene.camera._compile(), options, mutation, 2000, 4, 0.02, 1e-3
        )
    )
    block, specular, reported, measured, cos_end = checks.T
    assert len(checks) >= 200 and (specular == 1).sum() >= 50, (len(checks), (specular == 1).sum())
    if mutation == "multi_chain_perturbation":
        assert (block == 1).sum() >= 50  # the angular block at the diffuse vertex
    error = np.abs(reported / measured - 1)
    assert error.max() < FD_TOLERANCE, f"max relative error {error.max():.2e}"
    control = np.abs(reported / cos_end / measured - 1)
    assert np.median(control) > 10 * FD_TOLERANCE, np.median(control)


@pytest.mark.parametrize("vertex", [0, 1])
def test_bidirectional_density_estimates_an_area(vertex: int) -> None:
    """Horvitz-Thompson check of the bidirectional mutation's T(x -> y): over proposals from a
    fixed x, the mean of 1{y regenerates x_v alone, x'_v in A} / T(x -> y) estimates A's area,
    T having the move's probability and the sum over the ways (light walk, eye walk, or the
    emitter sample for v = 0) that make x'_v. v = 0: A is the light (exact area; x_1 sees all of
    it); v = 1: A is the non-specular surface that x_0 and x_2 both see (its area from 200,000
    uniform points). Both walks carry about half of T for v = 1, the emitter sample nearly all
    for v = 0. |z| < 4 with the estimate's standard error and the area's. Controls that must
    fail it: T twice too large (the probability 1/2 of each side counted twice); for v = 1 T
    with only the light walk's share move * pdf_light / 2 (as if the eye walk could not make
    x'_v: it carries about 40 % of T there), and T without the cosine at x'_v. (The control
    was 1 / (move * pdf_light) before issue 18: neither of those, and at z = 2.76 for v = 1
    once the random streams were independent.)"""
    scene = SCENES["caustic_box"]()
    options = _core.MltOptions(max_depth=4, seed=3, direct_spp=128)
    n = 200000
    d = _testing.check_mlt_bidirectional_density(
        scene._compile(), scene.camera._compile(), options, vertex, n, 200000
    )
    move, pdf_light, pdf_eye = (np.array(d[k]) for k in ("move", "pdf_light", "pdf_eye"))
    assert len(move) > 5000

    def z(inv_t: np.ndarray) -> float:
        terms = np.concatenate([inv_t, np.zeros(n - len(inv_t))])
        return (terms.mean() - d["area"]) / np.sqrt(terms.var(ddof=1) / n + d["area_se"] ** 2)

    inv_t = np.array(d["inv_t"])
    np.testing.assert_allclose(inv_t * move * (pdf_light + pdf_eye) / 2, 1.0, rtol=1e-9)
    assert abs(z(inv_t)) < 4.0, z(inv_t)
    assert abs(z(inv_t / 2)) > 4.0
    if vertex == 1:
        assert abs(z(2 / (move * pdf_light))) > 4.0
        assert abs(z(np.array(d["cos"]) * inv_t)) > 4.0
