"""Sphinx configuration of the nav2_pyif site (MyST Markdown).

It sits in ``python/doc/``, the ``doc`` folder beside the ROS package ``nav2_pyif``'s
package.xml, where rosdoc2 (docs.ros.org's tool) looks for a package's Sphinx project; it
builds the same with plain ``sphinx-build python/doc OUT`` (tests/test_site.py does, with
``-W``). Tables and the architecture figure are generated from the code at build time by
``_ext/nav2_pyif_docs.py``."""

from __future__ import annotations

import re
import sys
from pathlib import Path
from xml.etree import ElementTree


def _this_folder() -> Path:
    """This file's folder. rosdoc2 runs this file through exec() from a conf.py it writes
    elsewhere, where ``__file__`` is its own: that file names this one in its exec line."""
    here = Path(__file__).resolve()
    wrapped = re.search(r'exec\(open\("([^"]+)"\)', here.read_text())
    return Path(wrapped.group(1)).resolve().parent if wrapped else here.parent


HERE = _this_folder()
REPOSITORY = HERE.parents[1]


def _link_the_repository_beside(wrapped: Path) -> None:
    """rosdoc2 builds this folder from its own build folder, and a copy of it one level
    deeper (``user_docs/``), where the pages' links into the repository
    (``../../docs/office_pure_pursuit.png``) would point at nothing: link the repository's
    top-level folders where those links lead."""
    for beside in (wrapped.parent, wrapped.parents[1]):
        for folder in REPOSITORY.iterdir():
            link = beside / folder.name
            if folder.is_dir() and not folder.name.startswith(".") and not link.exists():
                link.symlink_to(folder)


if Path(__file__).resolve().parent != HERE:
    _link_the_repository_beside(Path(__file__).resolve().parent)
sys.path.insert(0, str(HERE / "_ext"))

PACKAGE_XML = ElementTree.parse(HERE.parent / "package.xml").getroot()

project = "nav2_pyif"
author = "nav2_pyif maintainers"
copyright = "nav2_pyif maintainers, Apache-2.0"
release = version = PACKAGE_XML.findtext("version") or "0"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinxarg.ext",
    "nav2_pyif_docs",
]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_generated/*.md"]
# Headings up to #### get anchors, so pages link to sections as GitHub's Markdown does.
myst_heading_anchors = 4
# Links resolve to pages, sections and Python objects (not to sphinx-argparse's commands).
myst_ref_domains = ["std", "py"]
myst_enable_extensions = ["colon_fence"]

autodoc_member_order = "bysource"
autodoc_typehints = "description"

html_theme = "alabaster"
html_title = f"nav2_pyif {release}"
html_theme_options = {
    "description": "Python planners for Nav2, over Zenoh",
    "page_width": "1180px",  # code blocks of 100 columns fit without a scroll bar
}
