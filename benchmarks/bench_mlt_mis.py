"""Kelemen's MIS of large steps in PSSMLT and MMLT: relMSE with and without, at equal mutations
and at equal time, on the Cornell box and Veach's door (64x64, ``max_depth`` 8).

Error is relMSE (pbrt-v4's definition) against the tests' Mitsuba references, minus the
reference's own noise term, as in ``bench_bdpt.py``. Each scene and method renders ``--seeds``
seeds with ``large_step_mis`` off and on, alternating, so that load from other processes hits
both alike: first at ``--mpp`` mutations per pixel, then at a ``time_limit`` of twice the mean
wall time of those renders (the bootstrap and the direct light take a fixed part of it, so the
chains get more than half). Direct light (BDPT, ``direct_spp`` 128) is the same in both
variants for a seed. Reports the mean relMSE over seeds with its standard error, the ratio
plain / MIS, and the seeds' paired ratios (geometric mean and its range). The time-limited
renders are noisier (the mutations they get vary with the load, and much of their time is the
bootstrap and the direct light), so the equal-mutation ratio of efficiencies
``1 / (relMSE * seconds)`` is the steadier equal-time figure (``efficiency_ratio``).

Writes ``benchmarks/results/bench_mlt_mis.json``.

    python benchmarks/bench_mlt_mis.py               # 8 seeds, 64 mutations per pixel
    python benchmarks/bench_mlt_mis.py --seeds 2 --mpp 8   # a smoke run
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

import dualight

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from bench_bdpt import RESULTS, load_reference  # noqa: E402
from bench_bdpt import SCENES as ALL_SCENES  # noqa: E402
from bench_bdpt import errors as error_terms  # noqa: E402

SCENES = {name: ALL_SCENES[name] for name in ("cornell", "door")}
METHODS = ("pssmlt", "mmlt")


def relmse(image: dualight.Image, ref: np.ndarray, ref_var: np.ndarray) -> float:
    """relMSE minus the reference's own noise term, as bench_bdpt reports it."""
    every_pixel = np.ones(ref.shape[:2], dtype=bool)
    return error_terms(np.asarray(image), ref, ref_var, every_pixel)["relmse"]


def summary(values: list[float]) -> dict[str, float]:
    v = np.array(values)
    return {"mean": float(v.mean()), "stderr": float(v.std(ddof=1) / np.sqrt(len(v)))}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", type=int, default=8)
    parser.add_argument("--mpp", type=int, default=64)
    args = parser.parse_args()
    out: dict = {
        "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform()},
        "seeds": args.seeds,
        "mutations_per_pixel": args.mpp,
        "results": {},
    }
    for name, (reference, make) in SCENES.items():
        scene = make()
        ref, ref_var, _ = load_reference(reference)
        for method in METHODS:
            row: dict = {}
            for mode in ("mutations", "time"):
                errors: dict[bool, list[float]] = {False: [], True: []}
                seconds: dict[bool, list[float]] = {False: [], True: []}
                mutations: dict[bool, list[int]] = {False: [], True: []}
                budget = (
                    {"mutations_per_pixel": args.mpp}
                    if mode == "mutations"
                    else {"spp": None, "time_limit": row["time_limit"]}
                )
                for seed in range(args.seeds):
                    for mis in (False, True):
                        start = time.perf_counter()
                        image = dualight.render(
                            scene,
                            method,
                            max_depth=8,
                            seed=seed,
                            progress=False,
                            mlt={"large_step_mis": mis},
                            **budget,
                        )
                        seconds[mis].append(time.perf_counter() - start)
                        errors[mis].append(relmse(image, ref, ref_var))
                        mutations[mis].append(image.stats["mutations"])
                r = {
                    ("mis" if mis else "plain"): {
                        "relmse": summary(errors[mis]),
                        "relmse_per_seed": errors[mis],
                        "seconds": float(np.mean(seconds[mis])),
                        "mutations_per_pixel": float(np.mean(mutations[mis])) / 64**2,
                    }
                    for mis in (False, True)
                }
                paired = np.array(errors[False]) / np.array(errors[True])
                r["ratio_plain_over_mis"] = (
                    r["plain"]["relmse"]["mean"] / r["mis"]["relmse"]["mean"]
                )
                r["paired_ratio"] = {
                    "geometric_mean": float(np.exp(np.mean(np.log(paired)))),
                    "min": float(paired.min()),
                    "max": float(paired.max()),
                }
                line = (
                    f"{name} {method} equal {mode}: relMSE plain "
                    f"{r['plain']['relmse']['mean']:.4g} +- {r['plain']['relmse']['stderr']:.2g}, "
                    f"MIS {r['mis']['relmse']['mean']:.4g} +- {r['mis']['relmse']['stderr']:.2g} "
                    f"(ratio {r['ratio_plain_over_mis']:.3f}, paired "
                    f"{r['paired_ratio']['geometric_mean']:.3f} in [{paired.min():.3f}, "
                    f"{paired.max():.3f}]; {r['plain']['seconds']:.2f} s / "
                    f"{r['mis']['seconds']:.2f} s, {r['plain']['mutations_per_pixel']:.0f} / "
                    f"{r['mis']['mutations_per_pixel']:.0f} mutations per pixel)"
                )
                if mode == "mutations":
                    row["time_limit"] = 2.0 * float(np.mean(seconds[False] + seconds[True]))
                    r["efficiency_ratio"] = (
                        r["plain"]["relmse"]["mean"] * r["plain"]["seconds"]
                    ) / (r["mis"]["relmse"]["mean"] * r["mis"]["seconds"])
                    line += f", efficiency MIS / plain {r['efficiency_ratio']:.3f}"
                row[mode] = r
                print(line, flush=True)
            out["results"][f"{name}_{method}"] = row
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "bench_mlt_mis.json").write_text(json.dumps(out, indent=2) + "\n")


if __name__ == "__main__":
    main()
