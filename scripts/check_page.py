"""Open an HTML page in headless Chromium and check that every image on it loads.

    python scripts/check_page.py out/index.html     # exit 1 if an image is missing or broken

A copy of the page with a small probe script is written beside it (so relative image paths
resolve as in the original), loaded with ``chromium --headless --dump-dom``, and removed. The
probe records, for every ``<img>``, whether the browser decoded it (``complete`` and a
non-zero ``naturalWidth``) and its size. Needs Debian's ``chromium`` package.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

PROBE = """<script>
window.addEventListener("load", () => {
  const images = [...document.images].map(img => ({
    src: img.getAttribute("src"), ok: img.complete && img.naturalWidth > 0,
    width: img.naturalWidth, height: img.naturalHeight}));
  const pre = document.createElement("pre");
  pre.id = "image-probe";
  pre.textContent = JSON.stringify(images);
  document.body.appendChild(pre);
});
</script>"""


def chromium() -> str | None:
    """The Chromium executable, if installed."""
    return shutil.which("chromium") or shutil.which("chromium-browser")


def probe_images(page: Path, timeout: float = 60.0) -> list[dict]:
    """Every image of ``page`` as Chromium sees it: ``src``, ``ok``, ``width``, ``height``."""
    exe = chromium()
    if exe is None:
        raise RuntimeError("chromium is not installed (apt-get install chromium)")
    text = page.read_text()
    if "</body>" not in text:
        raise ValueError(f"{page} has no </body>")
    probe = page.with_name(f".probe-{page.name}")
    probe.write_text(text.replace("</body>", PROBE + "</body>", 1))
    try:
        result = subprocess.run(
            [
                exe,
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--allow-file-access-from-files",
                "--virtual-time-budget=10000",
                "--dump-dom",
                probe.resolve().as_uri(),
            ],
            capture_output=True,
            text=True,
            timeout=timeout,
            check=False,
        )
    finally:
        probe.unlink()
    found = re.search(r'<pre id="image-probe">(.*?)</pre>', result.stdout, re.S)
    if found is None:
        raise RuntimeError(f"chromium did not run the probe: {result.stderr[-2000:]}")
    return json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print(__doc__)
        return 2
    images = probe_images(Path(argv[0]))
    broken = [im["src"] for im in images if not im["ok"]]
    print(f"{len(images)} images, {len(images) - len(broken)} loaded, {len(broken)} broken")
    for src in broken:
        print(f"  broken: {src}")
    return 1 if broken or not images else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
