"""The code blocks of the project's Markdown documents, as tests run them.

A block runs as written. A comment on the line before its fence says how, when it needs more
than "run it in the user's directory and expect exit code 0":

    <!-- doc-test: skip="needs Docker" -->          skipped visibly, with that reason
    <!-- doc-test: cwd=repo -->                      run from the repository root
    <!-- doc-test: background="ready" -->            start it, wait until its output matches
                                                      the regex, leave it running until the
                                                      document's last block has run, then
                                                      SIGINT it: it must end by itself
    <!-- doc-test: expect="now serving" -->          its output must match the regex
    <!-- doc-test: file=docs/zenoh/x.json5 -->       the block is that file of the repository
    <!-- doc-test: uses=python/doc/tutorials/a.md -->  the files a user writes in that document
                                                      (and in those it uses) are there first:
                                                      a tutorial goes on from the one before

Python blocks whose first line is ``# some/path.py`` are files a user writes (they go into the
user's directory); a Python block with ``def test_`` runs under pytest there; any other Python
block runs with ``python -c``. Shell blocks run with bash, the project's environment sourced
(``.venv/nav2_pyif_env.sh``), as after README's "To use the tools by hand", each document's in
a network of its own (tests/test_docs.py): as written, Zenoh's default port 7447 included.
"""

from __future__ import annotations

import re
import shlex
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

RUNNABLE = {"bash", "sh", "python"}
#: the site's deployment guide, whose certificates the TLS tests make as a user would
DEPLOYMENT_GUIDE = "python/doc/howto/deployment.md"
# A MyST directive's fence (```{include} FILE) opens a block too: its closing fence is no opening.
_FENCE = re.compile(r"^```(\w*|\{[\w:-]+\}[^`]*?)\s*$")
_MARKER = re.compile(r"^<!--\s*doc-test:(.*?)-->\s*$")
_FILE_HEADER = re.compile(r"^# ([\w./-]+\.py)\s*$")


@dataclass(frozen=True)
class Block:
    doc: Path
    label: str  # the document as the tests name it, e.g. python/doc/howto/deployment.md
    line: int  # of the opening fence, 1-based
    lang: str
    text: str
    options: dict[str, str] = field(default_factory=dict)

    @property
    def name(self) -> str:
        return f"{self.label}:{self.line}"

    @property
    def user_file(self) -> str | None:
        """The path a Python block says it is (its first line), if any."""
        match = _FILE_HEADER.match(self.text.splitlines()[0]) if self.text else None
        return match.group(1) if match and self.lang == "python" else None

    @property
    def is_test(self) -> bool:
        return self.lang == "python" and re.search(r"^def test_", self.text, re.M) is not None


def parse_options(marker: str) -> dict[str, str]:
    options = {}
    for word in shlex.split(marker):
        name, sep, value = word.partition("=")
        options[name] = value if sep else "1"
    return options


def blocks(doc: Path, root: Path) -> list[Block]:
    """Every fenced block of ``doc`` that runs (shell, Python) or names a file it shows."""
    label = str(doc.relative_to(root))
    out: list[Block] = []
    lines = doc.read_text().splitlines()
    i = 0
    while i < len(lines):
        fence = _FENCE.match(lines[i])
        if not fence:
            i += 1
            continue
        start, lang = i, fence.group(1)
        end = next(j for j in range(i + 1, len(lines)) if lines[j].startswith("```"))
        previous = next((lines[j] for j in range(start - 1, -1, -1) if lines[j].strip()), "")
        marker = _MARKER.match(previous)
        options = parse_options(marker.group(1)) if marker else {}
        text = "\n".join(lines[start + 1 : end]) + "\n"
        if lang in RUNNABLE or "file" in options:
            out.append(Block(doc, label, start + 1, lang, text, options))
        i = end + 1
    return out


def used_files(doc: Path, root: Path, seen: frozenset[Path] = frozenset()) -> dict[str, str]:
    """The user files (path -> text) that ``doc``'s ``uses=`` documents write, and theirs."""
    files: dict[str, str] = {}
    for block in blocks(doc, root):
        used = block.options.get("uses")
        if used and root / used not in seen:
            files.update(used_files(root / used, root, seen | {doc}))
            files.update({b.user_file: b.text for b in blocks(root / used, root) if b.user_file})
    return files


def guide_certificates(directory: Path, router_address: str) -> Path:
    """Run the deployment guide's openssl commands in ``directory`` (they make ``tls/``), the
    router's address in place of the guide's example address; the ``tls/`` directory made.
    (The Nav2 launch tests use it too: standard library only here.)"""
    root = Path(__file__).resolve().parents[1]
    (block,) = [b for b in blocks(root / DEPLOYMENT_GUIDE, root) if "openssl req" in b.text]
    script = block.text.replace("IP:192.168.1.20", f"IP:{router_address}")
    done = subprocess.run(
        ["bash", "-c", f"set -eo pipefail\n{script}"],
        cwd=directory,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    return directory / "tls"
