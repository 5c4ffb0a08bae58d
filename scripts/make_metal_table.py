"""Regenerate ``python/dualight/data/metals.json``: the RGB complex IOR (eta, k) of Mitsuba 3's
named conductors as its ``*_rgb`` variants use them (spectral data integrated to sRGB by
Mitsuba itself), so ``Conductor(material="Au")`` matches ``<bsdf type="conductor">`` with
``material="Au"``. Run with Mitsuba installed: ``python scripts/make_metal_table.py``.
"""

from __future__ import annotations

import json
from pathlib import Path

# Mitsuba 3's conductor documentation lists these names (data/ior/<name>.{eta,k}.spd).
NAMES = (
    "a-C Ag Al AlAs AlAs_palik AlSb AlSb_palik Au Be Be_palik Cr CsI CsI_palik Cu Cu_palik "
    "Cu2O Cu2O_palik CuO CuO_palik d-C d-C_palik Hg Hg_palik HgTe HgTe_palik Ir Ir_palik K "
    "K_palik Li Li_palik MgO MgO_palik Mo Mo_palik Na_palik Nb Nb_palik Ni_palik Rh Rh_palik "
    "Se Se_palik SiC SiC_palik SnTe SnTe_palik Ta Ta_palik Te Te_palik ThF4 ThF4_palik TiC "
    "TiC_palik TiN TiN_palik TiO2 TiO2_palik VC VC_palik V_palik VN VN_palik W W_palik"
).split()


def main() -> None:
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    table = {}
    for name in NAMES:
        try:
            params = mi.traverse(mi.load_dict({"type": "conductor", "material": name}))
        except Exception as exc:  # noqa: BLE001 - a name this Mitsuba lacks is reported and skipped
            print(f"skipped {name}: {exc}")
            continue
        table[name] = {
            "eta": [float(c) for c in params["eta.value"]],
            "k": [float(c) for c in params["k.value"]],
        }
    out = Path(__file__).resolve().parents[1] / "python/dualight/data/metals.json"
    payload = {"source": f"mitsuba {mi.__version__} scalar_rgb", "metals": table}
    out.write_text(json.dumps(payload, indent=1) + "\n")
    print(f"wrote {len(table)} metals to {out}")


if __name__ == "__main__":
    main()
