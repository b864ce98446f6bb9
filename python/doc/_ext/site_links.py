"""The repository's Markdown documents as site pages: their links rewritten for Sphinx.

On GitHub, PROTOCOL.md links ``vectors/keys.json`` and BENCHMARKS.md links ``RELIABILITY.md``,
relative to their own folder. Included into a page of the site, a link must name a page of
the site (``/explanation/reliability_runs.md``), a file to download (``path:``) or nothing
(a folder: the link's text stays, as code)."""

from __future__ import annotations

import os
import re
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[3]

#: generated name -> the repository's document it copies
REPOSITORY_DOCUMENTS = {
    "protocol.md": REPOSITORY / "protocol" / "PROTOCOL.md",
    "reliability.md": REPOSITORY / "RELIABILITY.md",
    "benchmarks.md": REPOSITORY / "BENCHMARKS.md",
}
#: the repository's documents (relative paths) -> the site page that shows each
SITE_PAGES = {
    "protocol/PROTOCOL.md": "reference/protocol.md",
    "RELIABILITY.md": "explanation/reliability_runs.md",
    "BENCHMARKS.md": "explanation/benchmarks.md",
    "README.md": "index.md",
}
_LINK = re.compile(r"(!?)\[([^\]]*)\]\(([^)\s]+)\)")
_SCHEME = re.compile(r"^[a-z][a-z0-9+.-]*:")


def site_target(source: Path, target: str, srcdir: Path) -> str | None:
    """Where a link of ``source`` to ``target`` points on the site (a srcdir-rooted path,
    ``path:`` for a download), or None when it points at no file."""
    path, _, anchor = target.partition("#")
    resolved = (source.parent / path).resolve()
    anchor = f"#{anchor}" if anchor else ""
    try:
        in_repository = resolved.relative_to(REPOSITORY).as_posix()
    except ValueError:
        return None
    if in_repository in SITE_PAGES:
        return f"/{SITE_PAGES[in_repository]}{anchor}"
    if resolved.suffix == ".md" and resolved.is_relative_to(srcdir):
        return f"/{resolved.relative_to(srcdir).as_posix()}{anchor}"
    if resolved.is_file():
        return "/" + os.path.relpath(resolved, srcdir)
    return None


def for_the_site(source: Path, srcdir: Path) -> str:
    def rewrite(match: re.Match[str]) -> str:
        bang, text, target = match.groups()
        if target.startswith("#") or _SCHEME.match(target):
            return match.group(0)
        where = site_target(source, target, srcdir)
        if where is None:
            return text if text.startswith("`") else f"`{text}`"
        if bang or where.endswith(".md") or ".md#" in where:
            return f"{bang}[{text}]({where})"
        return f"[{text}](path:{where})"  # a file of the repository, offered as a download

    return _LINK.sub(rewrite, source.read_text())
