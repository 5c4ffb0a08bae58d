"""dualight's path tracer against Mitsuba 3's `path` integrator on the Cornell box.

Both renderers get the same scene (``Scene.to_mitsuba``), resolution, spp, ``max_depth``,
``rr_depth`` and all cores. Each runs with uniform random numbers (dualight ``independent``,
Mitsuba ``independent``: the same algorithm, so this measures the implementations) and with
its low-discrepancy sampler (dualight ``sobol``, Mitsuba ``ldsampler``). For each spp the
script times the render call alone (after a warm-up render, so Mitsuba's LLVM kernels are
compiled and dualight's BVH is built) and measures relMSE against a high-spp Mitsuba reference.
Monte Carlo error falls as 1/time (faster with low-discrepancy samplers), so
``1 / (relMSE * seconds)`` is each renderer's efficiency; the ratio of efficiencies is the ratio
of times to equal error. An Embree-only cast of as many incoherent rays as dualight traced gives
the ray-tracing limit.

Writes ``benchmarks/results/bench_path.json`` and ``bench_path.png`` (relMSE against seconds).

    python benchmarks/bench_path.py               # 128x128, spp 4..256, reference 8192 spp
    python benchmarks/bench_path.py --quick       # 64x64, fewer spp, for a smoke run
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path
from typing import Any

import numpy as np

import dualight
from dualight import _core, metrics
from dualight import mitsuba as dmi
from dualight.plotting import save_relmse_against_time

RESULTS = Path(__file__).resolve().parent / "results"


def reference_image(scene: dualight.Scene, spp: int, max_depth: int, rr_depth: int) -> np.ndarray:
    """High-spp Mitsuba reference, cached as EXR beside the results."""
    cam = scene.camera
    assert cam is not None
    cache = RESULTS / "cache" / f"cornell_{cam.width}x{cam.height}_d{max_depth}_spp{spp}.exr"
    if cache.exists():
        return np.asarray(dualight.Image.load(cache))
    cache.parent.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    mean, _ = dmi.reference(scene, spp, seed=987654, max_depth=max_depth, rr_depth=rr_depth)
    print(f"reference: {spp} spp with Mitsuba in {time.perf_counter() - start:.1f} s")
    dualight.Image(mean, stats={"spp": spp, "renderer": "mitsuba"}).save(cache)
    return mean


def time_dualight(
    scene: dualight.Scene, sampler: str, spp: int, max_depth: int, rr_depth: int, seed: int
) -> tuple[np.ndarray, float, dict[str, Any]]:
    dualight.render(scene, spp=1, max_depth=max_depth, progress=False)  # BVH built, warm caches
    start = time.perf_counter()
    image = dualight.render(
        scene,
        spp=spp,
        max_depth=max_depth,
        rr_depth=rr_depth,
        seed=seed,
        sampler=sampler,
        progress=False,
    )
    return np.asarray(image), time.perf_counter() - start, image.stats


def time_mitsuba(
    scene: dualight.Scene,
    variant: str,
    sampler: str,
    spp: int,
    max_depth: int,
    rr_depth: int,
    seed: int,
) -> tuple[np.ndarray, float]:
    import mitsuba as mi

    dmi.variant(variant)
    desc = scene.to_mitsuba(spp=spp, max_depth=max_depth, rr_depth=rr_depth)
    desc["sensor"]["sampler"]["type"] = sampler
    mscene = mi.load_dict(desc)
    np.asarray(mi.render(mscene, spp=spp, seed=seed + 1000))  # warm-up: JIT compile
    start = time.perf_counter()
    image = np.asarray(mi.render(mscene, spp=spp, seed=seed), dtype=np.float32)
    return image, time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--resolution", type=int, default=128)
    parser.add_argument("--spp", type=str, default="4,16,64,256")
    parser.add_argument("--ref-spp", type=int, default=8192)
    parser.add_argument("--max-depth", type=int, default=8)
    parser.add_argument("--rr-depth", type=int, default=5)
    parser.add_argument("--variants", type=str, default="scalar_rgb,llvm_ad_rgb")
    parser.add_argument("--quick", action="store_true", help="64x64, spp 4..64, ref 2048")
    args = parser.parse_args()
    if args.quick:
        args.resolution, args.spp, args.ref_spp = 64, "4,16,64", 2048
    spps = [int(s) for s in args.spp.split(",")]
    res = (args.resolution, args.resolution)
    scene = dualight.scenes.cornell_box(resolution=res)
    ref = reference_image(scene, args.ref_spp, args.max_depth, args.rr_depth)

    runs: list[dict[str, Any]] = []
    variants = []
    for v in args.variants.split(","):
        try:
            dmi.variant(v)
            variants.append(v)
        except RuntimeError as err:
            print(f"skipping Mitsuba {v}: {err}")
    pairs = [("independent", "independent"), ("sobol", "ldsampler")]
    for spp in spps:
        for ours_sampler, theirs_sampler in pairs:
            img, secs, stats = time_dualight(
                scene, ours_sampler, spp, args.max_depth, args.rr_depth, seed=spp
            )
            runs.append(
                {
                    "renderer": "dualight",
                    "sampler": ours_sampler,
                    "spp": spp,
                    "seconds": secs,
                    "relmse": metrics.relmse(img, ref),
                    "rays": stats["rays"],
                }
            )
            for v in variants:
                img, secs = time_mitsuba(
                    scene, v, theirs_sampler, spp, args.max_depth, args.rr_depth, seed=spp
                )
                runs.append(
                    {
                        "renderer": f"mitsuba_{v}",
                        "sampler": theirs_sampler,
                        "spp": spp,
                        "seconds": secs,
                        "relmse": metrics.relmse(img, ref),
                    }
                )
    for r in runs:
        r["samples_per_second"] = res[0] * res[1] * r["spp"] / r["seconds"]
        r["efficiency"] = 1.0 / (r["relmse"] * r["seconds"])
        print(
            f"{r['renderer']:>20} {r['sampler']:>11} {r['spp']:5d} spp {r['seconds']:8.3f} s "
            f"{r['samples_per_second'] / 1e6:6.2f} M spl/s relMSE {r['relmse']:.3e}"
        )

    def run(renderer: str, sampler: str, spp: int) -> dict[str, Any]:
        return next(
            r
            for r in runs
            if r["renderer"] == renderer and r["sampler"] == sampler and r["spp"] == spp
        )

    # Ratios at the largest spp, where timing noise and fixed costs matter least.
    top = max(spps)
    ours = run("dualight", "independent", top)
    ratios = {}
    for v in variants:
        for ours_sampler, theirs_sampler in pairs + [("sobol", "independent")]:
            a, b = run("dualight", ours_sampler, top), run(f"mitsuba_{v}", theirs_sampler, top)
            ratios[f"dualight {ours_sampler} / {v} {theirs_sampler}"] = {
                "samples_per_second": a["samples_per_second"] / b["samples_per_second"],
                "time_to_equal_relmse": a["efficiency"] / b["efficiency"],
            }
    limit = _core.cast_random_rays(scene._compile(), scene.camera._compile(), int(ours["rays"]))
    ours_rays_per_second = ours["rays"] / ours["seconds"]
    summary = {
        "scene": "cornell",
        "resolution": list(res),
        "max_depth": args.max_depth,
        "rr_depth": args.rr_depth,
        "reference_spp": args.ref_spp,
        "machine": {"cpu_count": __import__("os").cpu_count(), "platform": platform.platform()},
        "runs": runs,
        "ratios_vs_mitsuba_at_spp": top,
        "ratios": ratios,
        "dualight_rays_per_second": ours_rays_per_second,
        "embree_limit_rays_per_second": limit["rays_per_second"],
        "fraction_of_embree_limit": ours_rays_per_second / limit["rays_per_second"],
    }
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "bench_path.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"\nat {top} spp, dualight vs Mitsuba (>1 means dualight is faster):")
    for v, r in ratios.items():
        print(
            f"  {v:>12}: samples/s x{r['samples_per_second']:.2f}, "
            f"time to equal relMSE x{r['time_to_equal_relmse']:.2f}"
        )
    print(
        f"  dualight traces {ours_rays_per_second / 1e6:.1f} M rays/s = "
        f"{100 * summary['fraction_of_embree_limit']:.0f}% of the Embree-only limit "
        f"({limit['rays_per_second'] / 1e6:.1f} M rays/s)"
    )

    curves, styles = {}, {}
    for name in ["dualight"] + [f"mitsuba_{v}" for v in variants]:
        for sampler in sorted({r["sampler"] for r in runs if r["renderer"] == name}):
            label = f"{name} ({sampler})"
            rs = [r for r in runs if r["renderer"] == name and r["sampler"] == sampler]
            curves[label] = [(r["seconds"], r["relmse"]) for r in rs]
            styles[label] = "o-" if sampler == "independent" else "s--"
    title = f"Cornell box {res[0]}x{res[1]}, path tracing, max_depth {args.max_depth}"
    save_relmse_against_time(
        {title: curves},
        RESULTS / "bench_path.png",
        panel_size=(6, 4.5),
        dpi=120,
        ylabel="relMSE vs reference",
        styles=styles,
    )
    print(f"wrote {RESULTS / 'bench_path.json'} and bench_path.png")


if __name__ == "__main__":
    main()
