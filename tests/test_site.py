"""The documentation site (python/doc/) builds with Sphinx, warnings as errors; every link
between its pages lands on a page and an anchor that exist; and the rendered tutorial, API
and architecture pages, opened in headless Chromium, show their text, code blocks and images.
One build per session, shared by the tests (its commands run in tests/test_docs.py)."""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import ROOT, in_project_env
from tests.site_pages import broken_links, read_page

pytestmark = pytest.mark.integration

SOURCE = ROOT / "python" / "doc"
#: pages a new user reads first, and what each must show: (code blocks, images) at least
RENDERED = {
    "tutorials/first_controller.html": (4, 0),
    "reference/api.html": (1, 0),
    "explanation/architecture.html": (0, 1),
    "index.html": (0, 1),
}


@pytest.fixture(scope="session")
def site() -> Iterator[Path]:
    """The site, built once: sphinx-build -W (a warning fails the build), from scratch."""
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_site_") as out:
        built = subprocess.run(
            in_project_env(f"python -m sphinx -W --keep-going -E -q -b html {SOURCE} {out}/html"),
            cwd=ROOT,
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert built.returncode == 0, built.stdout + built.stderr
        yield Path(out) / "html"


def test_the_site_builds_warning_free(site: Path) -> None:
    for page in ["index", *(p.removesuffix(".html") for p in RENDERED)]:
        assert (site / f"{page}.html").is_file(), page


def test_reference_pages_are_generated_from_the_code(site: Path) -> None:
    commands = (site / "reference" / "commands.html").read_text()
    for option in ["--batch-window", "--call-timeout", "--allow-remote-reload"]:
        assert option in commands, f"the commands page misses {option}"
    parameters = (site / "reference" / "plugin_parameters.html").read_text()
    assert "python_delegates" in parameters and "configure_timeout" in parameters
    api = (site / "reference" / "api.html").read_text()
    assert 'id="nav2_pyif.global_planner.GlobalPlanner.create_plan"' in api
    assert (site / "_images" / "architecture.png").is_file()


def test_links_between_pages_land_on_pages_and_anchors_that_exist(site: Path) -> None:
    problems = broken_links(site)
    assert not problems, "\n".join(problems)


def test_the_link_checker_sees_a_broken_link(tmp_path: Path) -> None:
    (tmp_path / "a.html").write_text('<h1 id="top">A</h1><a href="b.html#missing">b</a>')
    (tmp_path / "b.html").write_text('<h1 id="here">B</h1><a href="a.html#top">a</a>')
    (tmp_path / "c.html").write_text('<a href="gone.html">gone</a>')
    problems = broken_links(tmp_path)
    assert len(problems) == 2, problems
    assert "no anchor #missing" in problems[0] + problems[1]


def chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if found := shutil.which(name):
            return found
    pytest.skip("headless Chromium is not installed (scripts/test.sh installs Debian's chromium)")


def render(page: Path, out: Path) -> tuple[str, np.ndarray]:
    """The page's DOM after rendering, and its screenshot as an (H, W, 3) float array."""
    browser = chromium()
    shot = out / f"{page.stem}.png"
    common = [
        browser,
        "--headless",
        "--no-sandbox",  # as root in a container; the page is our own file
        "--disable-gpu",
        "--hide-scrollbars",
        f"--user-data-dir={out / 'profile'}",
        "--window-size=1280,1400",
    ]
    dom = subprocess.run(
        [*common, "--dump-dom", page.as_uri()], capture_output=True, text=True, timeout=120
    )
    assert dom.returncode == 0, dom.stderr
    taken = subprocess.run(
        [*common, f"--screenshot={shot}", page.as_uri()], capture_output=True, timeout=120
    )
    assert taken.returncode == 0 and shot.is_file(), taken.stderr
    import matplotlib.image

    return dom.stdout, np.asarray(matplotlib.image.imread(shot))[..., :3]


@pytest.mark.parametrize("name", sorted(RENDERED))
def test_rendered_page_shows_its_text_code_and_images(
    site: Path, name: str, tmp_path: Path
) -> None:
    dom, pixels = render(site / name, tmp_path)
    page = read_page(dom)
    least_code, least_images = RENDERED[name]
    assert page.code_blocks >= least_code, f"{name}: {page.code_blocks} code blocks in the DOM"
    assert len(page.images) >= least_images, f"{name}: images {page.images}"
    for src in page.images:
        assert (site / name).parent.joinpath(src).resolve().is_file(), f"{name}: no {src}"
    # The screenshot: the body column has ink from top to bottom, not a blank page.
    width = pixels.shape[1]
    body = pixels[:, width // 4 : width - 60]
    inked_rows = (np.abs(body - body[0, 0]).sum(axis=2) > 0.3).any(axis=1)
    bands = np.array_split(inked_rows, 7)
    assert sum(band.any() for band in bands) >= 6, f"{name}: blank regions in the screenshot"
    if least_code:  # a code block's background (Pygments' colour) is on the screen
        assert (np.abs(body - body[0, 0]).sum(axis=2) > 0.02).mean() > 0.05, name
    if least_images:  # an image's pixels: colours that no text or background has
        saturation = body.max(axis=2) - body.min(axis=2)
        assert (saturation > 0.08).sum() > 2000, f"{name}: no image to see on the screen"


# What rosdoc2 itself warns of on any ament_python package with its own Sphinx project: its
# sphinx-apidoc pages describe the modules our API page describes too, its copy of the pages
# (user_docs/) is in no toctree, and its theme (Read the Docs') takes none of alabaster's
# options. Anything else is ours.
ROSDOC2_OWN_WARNINGS = (
    "duplicate object description",
    "document isn't included in any toctree",
    "unsupported theme option",
)


def test_rosdoc2_builds_the_package_documentation(tmp_path: Path) -> None:
    """docs.ros.org's tool builds the ROS package nav2_pyif's documentation from python/
    (package.xml, doc/conf.py), with no warning of ours, and the tutorials are in it."""
    if shutil.which("rosdoc2", path=str(ROOT / ".venv" / "bin")) is None:
        pytest.skip("rosdoc2 is not installed: python -m pip install -e '.[dev]'")
    built = subprocess.run(
        in_project_env(f"rosdoc2 build --package-path {ROOT / 'python'}"),
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=900,
    )
    log = built.stdout + built.stderr
    assert built.returncode == 0, log[-4000:]
    ours = [
        line
        for line in log.splitlines()
        if "WARNING" in line and not any(known in line for known in ROSDOC2_OWN_WARNINGS)
    ]
    assert not ours, "\n".join(ours)
    output = tmp_path / "docs_output" / "nav2_pyif"
    tutorial = (output / "tutorials" / "first_controller.html").read_text()
    assert "compute_velocity_commands" in tutorial
    assert (output / "_images" / "architecture.png").is_file()
