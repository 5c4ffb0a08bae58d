"""The path tracer, the light tracer and BDPT against the stored Mitsuba 3 references
(dualight/data/references): Welch tests with both images' variances and CIE Delta E 2000,
each with a negative control that must fail the same comparison. (The path tracer's Cornell
and furnace rows are in test_path_vs_mitsuba.py.) BDPT renders with its own default Russian
roulette (from vertex 2), the path and light tracers with the reference's (Mitsuba's, from 5).

How each render is judged, and why (``Judge``):

* By default as in the foundation: per pixel and per 8x8 block, Delta E on pixels.
* Where an estimator's per-pixel estimates are heavy-tailed at test budgets, the per-pixel
  normal approximation fails: rare, bright paths are missing from most pixels, whose mean and
  sample variance are then both too low together (|z| of 10-20 on pixels whose blocks agree,
  always on the low side, while the image mean stays within 0.1 % of the reference). Blocks
  average enough paths for it to hold, so such renders are judged on blocks, and Delta E on
  4x4 block means (on pixels it would measure noise); per-pixel figures are printed. This
  holds for every estimator on the door scene (light only through a gap) and for the path
  tracer and BDPT on the caustic box: caustics seen in the mirror sphere or through the glass
  (specular vertex next to the camera, then a diffuse one: no strategy but "hit the small
  light" can make those paths) keep heavy tails in the spheres' pixels. One sampling strategy
  alone (``render(strategies="bsdf" | "light")``) is heavy-tailed by design, where the other
  one would have found the light (Veach's figure 9.2): on the Cornell box BSDF sampling
  leaves the shadowed pixels at the walls' edges and under the blocks low (195 pixels with
  |z| > 5.5, 80 % of them low, all 8x8 blocks within |z| 2.6 at 1024 spp; BDPT's Delta E on
  4x4 blocks was 1.09 at 512 spp, all blocks passing, so it takes 1024); BDPT's light
  sampling alone on Veach's plates leaves one 4x4 block at |z| 5.4 (8x8 blocks within 2.1).
* The light tracer cannot render light that reaches the camera by a specular bounce (a mirror
  or glass seen directly): those pixels are masked out of its comparisons
  (``dualight.metrics.renderable_by_light_tracing``), and nowhere else.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pytest

import dualight
from dualight import metrics, radiosity, scenes
from dualight.bench import REFERENCE_DIR as REFERENCES

PASS = 0.9975  # the foundation's pass fraction: with 64 blocks, every block must pass


@dataclass(frozen=True)
class Judge:
    pixel_test: bool = True  # else per-pixel results are reported, not asserted (see above)
    blocks: tuple[int, ...] = (8,)
    delta_e_block: int = 1


PIXELS = Judge()
BLOCKS = Judge(pixel_test=False, blocks=(4, 8), delta_e_block=4)
LARGE_BLOCKS = Judge(pixel_test=False, blocks=(16,), delta_e_block=4)


@dataclass(frozen=True)
class Case:
    reference: str
    build: Callable[..., dualight.Scene]  # keyword arguments: the negative control's change
    wrong: dict
    spp: dict[str, int]  # per method: enough for the negative control to fail
    judges: dict[str, Judge] = field(default_factory=dict)  # per method; default PIXELS
    # More keywords of render; a callable value is called with the scene (a radiosity
    # solution for guide_from, solved for the scene being rendered).
    options: dict = field(default_factory=dict)
    long: tuple[str, ...] = ()  # methods left to make test-long, for make test's time


CASES = {
    "cornell": Case(
        "cornell_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), **kw),
        {"light_scale": 0.97},
        {"light": 1024, "bdpt": 512},
    ),
    # The path tracer took 2048 spp until its roulette took out refraction's 1 / eta^2, which
    # cut its error per sample 1.47x; at 1024 its 16x16 blocks pass at seeds 21-24 (max |z|
    # 1.9-3.1) and the control's pass 6-19 %.
    "caustics": Case(
        "caustics_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="caustics", **kw),
        {"light_scale": 0.97},
        {"path": 1024, "light": 2048, "bdpt": 512},
        {"path": LARGE_BLOCKS, "bdpt": LARGE_BLOCKS},
    ),
    # The light tracer's run (21 s) is long, for make test's time (issue 23): BDPT's light
    # tracing strategies (t = 1) cover the door in make test, the light tracer the other scenes.
    "door": Case(
        "door_64",
        lambda **kw: scenes.door_ajar(resolution=(64, 64), **kw),
        {"light_scale": 0.9},
        {"path": 1536, "light": 2048, "bdpt": 512},
        {"path": BLOCKS, "light": BLOCKS, "bdpt": BLOCKS},
        long=("light",),
    ),
    # Issue 19's materials. Rough gold, frosted glass and a rough-plastic floor: the caustic
    # box's heavy tails (light focused by the frosted sphere, seen through it or in the gold)
    # call for 16x16 blocks in the path tracer and BDPT; the control makes every surface 20 %
    # rougher.
    "glossy": Case(
        "glossy_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="glossy", **kw),
        {"roughness_scale": 1.2},
        {"path": 512, "light": 256, "bdpt": 128},
        {"path": LARGE_BLOCKS, "light": BLOCKS, "bdpt": LARGE_BLOCKS},
    ),
    # Smooth copper, a thin-glass bubble and a smooth-plastic floor; the control changes the
    # floor's coat and the bubble to IOR 1.7. BDPT's paths through the specular chains have
    # heavy tails: at 128 spp the worst 16x16 block over seeds 21-32 lay at |z| 4.6 (seed 25)
    # with the usual MIS rule through chains and at 4.1 (seed 21) with the chains' own
    # densities (mis_weight.cpp); at 256 spp the worst is 3.6.
    "coated": Case(
        "coated_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="coated", **kw),
        {"ior": 1.7},
        {"path": 512, "light": 512, "bdpt": 256},
        {"path": LARGE_BLOCKS, "light": BLOCKS, "bdpt": LARGE_BLOCKS},
    ),
    # Issue 19's shading normals: coarse spheres (320 triangles) shaded by their vertex
    # normals, a white one and a glass one. The light tracer and BDPT agree with the path
    # tracer only through the adjoint correction of importance transport; the control renders
    # the same triangles flat. The path tracer's paths through the glass have heavy tails: at
    # 1024 spp one of the 16 blocks lay at z -4.6 (seed 21; -4.4 at seed 22 before its roulette
    # took out refraction's 1 / eta^2), at 8192 spp every |z| < 2.3, so it takes 2048 (seeds
    # 21-26: worst |z| 1.8-3.0).
    "smooth": Case(
        "smooth_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="smooth", **kw),
        {"sphere_normals": False},
        {"path": 2048, "light": 1024, "bdpt": 256},
        {"path": LARGE_BLOCKS, "bdpt": LARGE_BLOCKS},
    ),
    # Issue 19's textures: a bitmap back wall, a checkerboard floor and a block of
    # checkerboard roughness; the control moves every texture along u by 1/32 (half a texel of
    # the wall's bitmap, an eighth of a floor square).
    # The block's alpha 0.05 squares mirror the light: heavy tails, as on the glossy box (at
    # 512 spp a few 8x8 blocks of the path and light tracers lie low, max |z| 4.1 and 4.4, all
    # on the block; at 2048 spp the path tracer's 8x8 blocks pass), so 16x16 blocks there.
    "textured": Case(
        "textured_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="textured", **kw),
        {"texture_shift": 1 / 32},
        {"path": 512, "light": 512, "bdpt": 256},
        {"path": LARGE_BLOCKS, "light": LARGE_BLOCKS, "bdpt": BLOCKS},
    ),
    # Issue 20's lights without a surface: the classic box lit by a point light and by a spot
    # light (delta positions: the path tracer finds them by next-event estimation only, the
    # light tracer from their subpaths only). Controls: the light 3 % dimmer; the spot's
    # cutoff 45 degrees instead of 50 (its flux kept, the beam wider at its core). The spot's
    # path tracer takes 2048 spp: at 1024 its per-pixel Delta E was 1.01, noise (its 8x8
    # blocks all passed, max |z| 2.5).
    "point": Case(
        "point_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="point", **kw),
        {"light_scale": 0.97},
        {"path": 1024, "light": 1024, "bdpt": 256},
    ),
    "spot": Case(
        "spot_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="spot", **kw),
        {"spot_cutoff": 45.0},
        {"path": 2048, "light": 1024, "bdpt": 256},
    ),
    # Issue 20's emitters at infinity, lighting the box through its open top: a directional
    # light (next-event estimation only for the path tracer), a constant sky and an
    # environment map with a sun in it (escaping rays see them, MIS-weighted against
    # next-event estimation). The light tracer's subpaths start at a direction at infinity and
    # enter from the distant disk; BDPT's camera subpaths end at the environment's vertex at
    # infinity. Controls: the sun and the sky 3 % dimmer; the map turned 30 degrees about y.
    # The light tracer sees the sky only through splats of directions at infinity: the pixels
    # on the walls' top edges, whose sky is a sliver (1.6 % of the pixel at (9, 8)), get a few
    # each (Poisson, about 5 at 8192 spp; at 32768 spp its value there agrees), heavy tails
    # as on the door, so its renders of the sky and the map are judged on blocks.
    "sun": Case(
        "sun_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="sun", **kw),
        {"light_scale": 0.97},
        {"path": 1024, "light": 1024, "bdpt": 256},
    ),
    "sky": Case(
        "sky_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="sky", **kw),
        {"light_scale": 0.97},
        {"path": 1024, "light": 1024, "bdpt": 256},
        {"light": BLOCKS},
    ),
    "envmap": Case(
        "envmap_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="envmap", **kw),
        {"env_rotation": 30.0},
        {"path": 512, "light": 512, "bdpt": 256},
        {"light": BLOCKS},
    ),
    # Issue 20's textured area light: the classic box's ceiling light emits a bitmap, warm at
    # one end and cool at the other in a checker of bright and dim texels (Mitsuba's `area`
    # emitter with a `radiance` texture). Control: the texture moved by half its width along
    # u, its warm and cool ends swapped (the same power).
    "lamp": Case(
        "lamp_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="lamp", **kw),
        {"texture_shift": 0.5},
        {"path": 512, "light": 512, "bdpt": 128},
    ),
    # Issue 21's classic scenes. Veach's MIS plates, with MIS and by light sampling alone
    # (render(strategies="light")); the control makes every plate 20 % rougher. BSDF sampling
    # alone is tested on the Cornell box (below): on the plates it finds the smallest light
    # from the diffuse floor once in about 40,000 samples, so at test budgets most pixels
    # there have not seen it yet (mean and variance both low, |z| in the hundreds), the
    # heavy tail Veach's figure shows.
    "veach_mis": Case(
        "veach_mis_64",
        lambda **kw: scenes.veach_mis(resolution=(64, 64), **kw),
        {"roughness_scale": 1.2},
        {"path": 256, "bdpt": 128},
        {"path": BLOCKS, "bdpt": BLOCKS},
    ),
    # BDPT by light sampling alone has the heavy tail of next-event estimation on the sharp
    # plates (a rare sample in the narrow lobe carries much of a pixel): seeds 21-31 left one
    # 8x8 block low (z -4.7 to -6.0, always the plates' row) in 4 of 11 renders, with the light
    # pool (16) as with 1 (which here only changes the random numbers: every path's weight goes
    # to s = 0 or 1), and one 16x16 block low in 1 (pool 1) and 2 (pool 16) of 11; the control
    # failed at every seed. So 16x16 blocks (issue 23); 1024 spp did not help (2 of 11 at 8x8).
    "veach_mis_light": Case(
        "veach_mis_64",
        lambda **kw: scenes.veach_mis(resolution=(64, 64), **kw),
        {"roughness_scale": 1.2},
        {"path": 512, "bdpt": 512},
        {"path": BLOCKS, "bdpt": LARGE_BLOCKS},
        {"strategies": "light"},
    ),
    # One strategy alone on the Cornell box, whose light BSDF sampling finds often enough.
    "cornell_bsdf": Case(
        "cornell_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), **kw),
        {"light_scale": 0.97},
        {"path": 1024, "bdpt": 1024},
        {"path": BLOCKS, "bdpt": BLOCKS},
        {"strategies": "bsdf"},
        long=("bdpt",),
    ),
    "cornell_light": Case(
        "cornell_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), **kw),
        {"light_scale": 0.97},
        {"path": 1024, "bdpt": 512},
        options={"strategies": "light"},
        long=("bdpt",),
    ),
    # BDPT with Russian roulette from each subpath's first vertex on (the reference's is 5, BDPT's
    # default 2, which the other BDPT rows run): wherever the roulette starts, the expectation
    # must stay the same. The roulette's 1 / q weights make the tails heavier: at 512 spp one
    # 8x8 block of seeds 22-27 lay at |z| 4.3 (seed 23), which fell to 3.0 at 4096 spp (no bias);
    # at 1024, seeds 21-28 pass (max block |z| 2.3-3.6) and the control's blocks pass 6 %.
    "cornell_rr1": Case(
        "cornell_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), **kw),
        {"light_scale": 0.97},
        {"bdpt": 1024},
        options={"rr_depth": 1},
    ),
    # Veach's bidirectional room: lit only by the ceiling and the shade above a hidden bulb,
    # a glass egg on the table. Control: the bulb 5 % dimmer. The path tracer's light in the
    # egg (the ceiling's caustic, seen through the glass) is heavy-tailed: at 512 spp a 4x4
    # block lay at |z| 5.2 and Delta E on 4x4 blocks was 1.05 (relMSE 0.2; BDPT's 0.0017).
    "veach_bidir": Case(
        "veach_bidir_64",
        lambda **kw: scenes.veach_bidir(resolution=(64, 64), **kw),
        {"light_scale": 0.95},
        {"path": 1024, "bdpt": 128},
        {"path": LARGE_BLOCKS, "bdpt": BLOCKS},
    ),
    # The door with glossy objects; control: the objects 20 % rougher.
    # BDPT's run (24 s) is long, for make test's time (issue 23): make test keeps BDPT on the door
    # and on the glossy and coated boxes, and this scene's path tracer.
    "door_glossy": Case(
        "door_glossy_64",
        lambda **kw: scenes.door_ajar(resolution=(64, 64), variant="glossy", **kw),
        {"light_scale": 0.9},
        {"path": 1536, "bdpt": 512},
        {"path": BLOCKS, "bdpt": BLOCKS},
        long=("bdpt",),
    ),
    # Issue 22's path guiding: the path tracer guided by radiance, the light tracer by
    # importance, each trained first (a quarter of spp on top) and then sampling directions from
    # the guide or the BSDF by one-sample MIS. Unbiased: the same tests and controls as unguided.
    # On the door the guided path tracer's tails are heavier than the unguided one's (a path
    # through the gap that the guide missed weighs 1 / bsdf_fraction more at every guided
    # vertex): its 4x4 blocks fall low (z to -6.0, 3 seeds at 1536 spp, 8x8 blocks within 2.6,
    # seed 21's to -4.2), so it is judged on 16x16 blocks. Guided BDPT (both guides, MIS
    # with the mixtures' densities both ways) is judged as unguided BDPT.
    "cornell_guided": Case(
        "cornell_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), **kw),
        {"light_scale": 0.97},
        {"path": 1024, "light": 1024, "bdpt": 512},
        options={"guiding": True},
    ),
    "caustics_guided": Case(
        "caustics_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="caustics", **kw),
        {"light_scale": 0.97},
        {"path": 2048, "light": 2048, "bdpt": 512},
        {"path": LARGE_BLOCKS, "bdpt": LARGE_BLOCKS},
        # Guided BDPT here keeps the reference's roulette (5): at its default (2) seed 21 left
        # one 16x16 block low at z -3.82 (the sphere caustics' heavy tails, worse with the
        # roulette's 1 / q weights), while seeds 22-25 passed (max |z| 2.1-2.9) and seeds 26-32
        # had every block within |z| 2.7, both signs; issue 23. The other guided BDPT rows run
        # the default.
        options={"guiding": True, "rr_depth": 5},
        long=("path", "light", "bdpt"),
    ),
    "door_guided": Case(
        "door_64",
        lambda **kw: scenes.door_ajar(resolution=(64, 64), **kw),
        {"light_scale": 0.9},
        {"path": 1536, "light": 2048, "bdpt": 512},
        {"path": LARGE_BLOCKS, "light": BLOCKS, "bdpt": BLOCKS},
        options={"guiding": True},
        long=("path", "light", "bdpt"),
    ),
    # Guides seeded from a radiosity and importance solution (render(guide_from=...)): the
    # first training iteration samples them. Unbiased whatever the seed guide.
    "cornell_seeded": Case(
        "cornell_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), **kw),
        {"light_scale": 0.97},
        {"path": 1024, "light": 1024, "bdpt": 512},
        options={
            "guiding": True,
            "guide_from": lambda scene: radiosity.solve(scene, "gauss_seidel", max_edge=110.0),
        },
        long=("light", "bdpt"),
    ),
    # Guided BDPT through glossy lobes (the mixtures' densities at rough conductors, rough
    # glass and rough plastic in both MIS directions); judged as unguided BDPT there.
    "glossy_guided": Case(
        "glossy_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), variant="glossy", **kw),
        {"roughness_scale": 1.2},
        {"bdpt": 128},
        {"bdpt": LARGE_BLOCKS},
        options={"guiding": True},
        long=("bdpt",),
    ),
}
RUNS = [
    pytest.param(name, method, marks=[pytest.mark.long] if method in case.long else [])
    for name, case in sorted(CASES.items())
    for method in case.spp
]


def _reference(name: str) -> tuple[np.ndarray, np.ndarray, dict]:
    mean = dualight.Image.load(REFERENCES / f"{name}_mean.exr")
    var = dualight.Image.load(REFERENCES / f"{name}_var.exr")
    return np.asarray(mean), np.asarray(var), mean.stats


@dataclass(frozen=True)
class Outcome:
    pixel: metrics.WelchResult
    blocks: dict[int, metrics.WelchResult]
    delta_e: float
    relmse: float

    def passed(self, judge: Judge) -> bool:
        return (
            (not judge.pixel_test or self.pixel.pass_fraction >= PASS)
            and all(b.pass_fraction >= PASS for b in self.blocks.values())
            and self.delta_e < 1.0
        )

    def __str__(self) -> str:
        blocks = ", ".join(
            f"{k}x{k} blocks {100 * b.pass_fraction:.2f}% (max |z| {b.max_z:.3g})"
            for k, b in self.blocks.items()
        )
        return (
            f"pixels {100 * self.pixel.pass_fraction:.2f}% (max |z| {self.pixel.max_z:.3g}), "
            f"{blocks}, dE2000 mean {self.delta_e:.3g}, relMSE {self.relmse:.3g}"
        )


def _compare(case: Case, method: str, seed: int, **wrong) -> Outcome:
    judge = case.judges.get(method, PIXELS)
    ref, ref_var, info = _reference(case.reference)
    scene = case.build(**wrong)
    options = {k: v(scene) if callable(v) else v for k, v in case.options.items()}
    image = dualight.render(
        scene,
        method,
        spp=case.spp[method],
        max_depth=info["max_depth"],
        # BDPT at its own default roulette (rr_depth 2, what users run; the roulette leaves the
        # expectation alone), the path and light tracers at the reference's (Mitsuba's 5).
        rr_depth=options.pop("rr_depth", None if method == "bdpt" else info["rr_depth"]),
        seed=seed,
        progress=False,
        **options,
    )
    mask = metrics.renderable_by_light_tracing(scene) if method == "light" else None
    keep = np.ones(ref.shape[:2], dtype=bool) if mask is None else mask
    mean, var = np.asarray(image), image.variance

    def welch(block: int) -> metrics.WelchResult:
        return metrics.welch_test(mean, var, ref, ref_var, block=block, mask=mask)

    b = judge.delta_e_block
    keep3 = np.repeat(keep[..., None], 3, axis=2).astype(np.float64)
    block_mask = None if mask is None else metrics.block_mean(keep3, b)[..., 0] == 1.0
    delta_e = metrics.delta_e2000(
        metrics.block_mean(mean, b), metrics.block_mean(ref, b), mask=block_mask
    )["mean"]
    return Outcome(
        pixel=welch(1),
        blocks={k: welch(k) for k in judge.blocks},
        delta_e=delta_e,
        relmse=metrics.relmse(mean[keep][None], ref[keep][None]),
    )


@pytest.mark.parametrize(("name", "method"), RUNS)
def test_matches_mitsuba_and_the_negative_control_fails(name: str, method: str) -> None:
    case = CASES[name]
    judge = case.judges.get(method, PIXELS)
    result = _compare(case, method, seed=21)
    print(f"\n{name} {method} vs Mitsuba: {result}")
    assert result.passed(judge), result
    wrong = _compare(case, method, seed=21, **case.wrong)
    print(f"{name} {method} {case.wrong} vs Mitsuba: {wrong}")
    assert not wrong.passed(judge)
    assert min(b.pass_fraction for b in wrong.blocks.values()) < PASS
