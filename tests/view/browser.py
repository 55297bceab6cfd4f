"""Open a page in headless Chromium (Debian's `chromium` package) with no network: take a
screenshot and dump the DOM after the page's scripts ran. Tests that use it skip when no
Chromium is installed (`apt-get install -y chromium`)."""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--enable-unsafe-swiftshader", "--hide-scrollbars", "--mute-audio")
#: Host resolution fails for every name: the page must need no network.
NO_NETWORK = "--host-resolver-rules=MAP * ~NOTFOUND"


def chromium() -> str | None:
    """The Chromium executable, or None."""
    return next((found for found in map(shutil.which, NAMES) if found), None)


def require_chromium() -> str:
    found = chromium()
    if found is None:
        pytest.skip("headless Chromium is not installed (Debian: apt-get install -y chromium)")
    return found


def _run(page: Path, *extra: str) -> subprocess.CompletedProcess:
    with tempfile.TemporaryDirectory(prefix="robotdesc-chromium-") as profile:
        return subprocess.run([require_chromium(), *FLAGS, NO_NETWORK,
                               f"--user-data-dir={profile}", *extra, page.resolve().as_uri()],
                              capture_output=True, check=False, text=True, timeout=180)


def screenshot(page: Path, png: Path, size: tuple[int, int] = (1200, 800),
               budget_ms: int = 4000) -> np.ndarray:
    """The page rendered at `size` (width, height) as an (h, w, 3) uint8 array, after
    `budget_ms` of the page's virtual time."""
    from PIL import Image

    done = _run(page, f"--screenshot={png}", f"--window-size={size[0]},{size[1]}",
                f"--virtual-time-budget={budget_ms}")
    assert png.is_file(), f"no screenshot: {done.stderr[-2000:]}"
    return np.asarray(Image.open(png).convert("RGB"))


def dump_dom(page: Path, size: tuple[int, int] = (1200, 800)) -> str:
    """The DOM after the page's scripts ran, serialised."""
    done = _run(page, "--dump-dom", f"--window-size={size[0]},{size[1]}",
                "--virtual-time-budget=4000")
    assert done.returncode == 0 and "<html" in done.stdout, done.stderr[-2000:]
    return done.stdout


def drawn_pixels(pixels: np.ndarray, background=(244, 245, 248), threshold: int = 80) -> float:
    """The share of pixels that differ from the viewer's background by more than
    `threshold` in some channel (the ground grid differs by about 45, so it does not count)."""
    difference = np.abs(pixels.astype(int) - np.asarray(background)).max(axis=2)
    return float((difference > threshold).mean())
