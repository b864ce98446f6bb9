"""What a rendered page of the site holds, read from its HTML: the ids a link may point at,
the links, the code blocks and the images (tests/test_site.py)."""

from __future__ import annotations

from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit


@dataclass
class Page:
    ids: set[str] = field(default_factory=set)
    links: list[str] = field(default_factory=list)  # href of each <a>
    images: list[str] = field(default_factory=list)  # src of each <img>
    code_blocks: int = 0  # <pre> inside a highlighted block


class _Reader(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.page = Page()
        self._highlight_depth = 0  # open <div class="highlight"> elements

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = {name: value or "" for name, value in attrs}
        if "id" in values:
            self.page.ids.add(values["id"])
        if tag == "a" and "href" in values:
            self.page.links.append(values["href"])
        if tag == "a" and "name" in values:
            self.page.ids.add(values["name"])
        if tag == "img":
            self.page.images.append(values.get("src", ""))
        if tag == "div" and "highlight" in values.get("class", "").split():
            self._highlight_depth += 1
        if tag == "pre" and self._highlight_depth:
            self.page.code_blocks += 1

    def handle_endtag(self, tag: str) -> None:
        if tag == "div" and self._highlight_depth:
            self._highlight_depth -= 1  # approximate: highlight divs hold no other divs


def read_page(html: str) -> Page:
    reader = _Reader()
    reader.feed(html)
    return reader.page


def broken_links(site: Path) -> list[str]:
    """Every link between the site's own pages (and to its files) that names a missing file
    or a missing anchor: 'page.html: href (why)'."""
    site = site.resolve()
    pages = {path: read_page(path.read_text(errors="replace")) for path in site.rglob("*.html")}
    problems = []
    for path, page in pages.items():
        for href in page.links + page.images:
            parts = urlsplit(href)
            if parts.scheme or parts.netloc or href.startswith("mailto:"):
                continue  # outside the site: sphinx linkcheck's job, which needs a network
            target = (path.parent / unquote(parts.path)).resolve() if parts.path else path
            where = f"{path.relative_to(site)}: {href}"
            if not target.is_file():
                problems.append(f"{where} (no file {target})")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else set()
                if unquote(parts.fragment) not in ids:
                    problems.append(f"{where} (no anchor #{parts.fragment})")
    return problems
