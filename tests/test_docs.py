"""Every shell and Python block of README.md, the site's pages (python/doc/),
bridge_plugin/README.md, protocol/PROTOCOL.md and each examples/*/README.md, extracted from the
Markdown and run as a user would (tests/docs_blocks.py says how a block is marked). Blocks that
need Docker, Nav2 or a GPU are marked and skipped, saying so.

Each document runs in a network of its own (tests/private_network.py): its commands use
Zenoh's default port 7447 as written, beside a Zenoh router that may already listen on 7447
here and other planner hosts, and reach none of them. Where no such network can be made, the
blocks run on this machine's own network if 7447 is free, and are skipped, naming the cause,
if it is not."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import ROOT, in_project_env
from tests.docs_blocks import Block, blocks, used_files
from tests.private_network import ZENOH_DEFAULT_PORT, PrivateNetwork, port_is_free

pytestmark = pytest.mark.integration

SITE = ROOT / "python" / "doc"

DOCS = [
    ROOT / "README.md",
    # the site (tests/test_site.py builds it), not what its build generates
    *sorted(p for p in SITE.rglob("*.md") if not p.relative_to(SITE).parts[0].startswith("_")),
    ROOT / "bridge_plugin" / "README.md",
    ROOT / "protocol" / "PROTOCOL.md",
    *sorted(ROOT.glob("examples/*/README.md")),  # the gallery's (tests/test_examples.py too)
]
ALL_BLOCKS = [block for doc in DOCS for block in blocks(doc, ROOT)]


class DocRun:
    """One document's run: its user directory, and the blocks left running in the
    background until the document's last block has run."""

    def __init__(self, doc: Path) -> None:
        self.doc = doc
        self._tmp = tempfile.TemporaryDirectory(prefix=f"nav2_pyif_docs_{doc.stem}_")
        self.user_dir = Path(self._tmp.name)
        for name, text in used_files(doc, ROOT).items():  # a tutorial's earlier files
            (self.user_dir / name).parent.mkdir(parents=True, exist_ok=True)
            (self.user_dir / name).write_text(text)
        self.done: set[int] = set()
        self.background: list[tuple[Block, subprocess.Popen[bytes], Path]] = []
        self.network: PrivateNetwork | None = PrivateNetwork()
        #: why this document's commands cannot run here, if they cannot
        self.cannot_run: str | None = None
        why_not = self.network.open()
        if why_not is not None:
            self.network = None
            if not port_is_free(ZENOH_DEFAULT_PORT):
                self.cannot_run = (
                    f"port {ZENOH_DEFAULT_PORT}, which the documented commands use, is taken "
                    f"here (a Zenoh router?) and no network of the tests' own can be made "
                    f"({why_not})"
                )

    def argv(self, command: str) -> list[str]:
        """``command`` as a user runs it, in this document's own network if there is one."""
        argv = in_project_env(command)
        return self.network.command(argv) if self.network is not None else argv

    def cwd(self, block: Block) -> Path:
        return ROOT if block.options.get("cwd") == "repo" else self.user_dir

    def run(self, block: Block) -> None:
        """Run ``block`` after the earlier files and background blocks it may rely on."""
        for earlier in blocks(self.doc, ROOT):
            if earlier.line >= block.line:
                break
            if (
                earlier.line not in self.done
                and "skip" not in earlier.options
                and (earlier.user_file or "background" in earlier.options)
            ):
                self._run(earlier)
        self._run(block)

    def _run(self, block: Block) -> None:
        self.done.add(block.line)
        if "file" in block.options:
            shown = (ROOT / block.options["file"]).read_text()
            assert block.text == shown, f"{block.name} differs from {block.options['file']}"
            return
        if block.user_file:
            path = self.user_dir / block.user_file
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(block.text)
            return
        if block.is_test:
            test_file = self.user_dir / f"test_doc_{block.line}.py"
            test_file.write_text(block.text)
            command = f"python -m pytest -q -p no:cacheprovider {test_file.name}"
        elif block.lang == "python":
            script = self.user_dir / f"doc_{block.line}.py"
            script.write_text(block.text)
            command = f"python {script.name}"
        else:
            command = block.text
        if "background" in block.options:
            self._start(block, command)
            return
        result = subprocess.run(
            self.argv(f"set -eo pipefail\n{command}"),
            cwd=self.cwd(block),
            capture_output=True,
            text=True,
            timeout=float(block.options.get("timeout", 600)),
        )
        output = result.stdout + result.stderr
        assert result.returncode == 0, f"{block.name} exited {result.returncode}:\n{output}"
        if "expect" in block.options:
            assert re.search(block.options["expect"], output), f"{block.name}:\n{output}"

    def _start(self, block: Block, command: str) -> None:
        log = self.user_dir / f"background_{block.line}.log"
        with open(log, "wb") as out:
            proc = subprocess.Popen(
                self.argv(command),
                cwd=self.cwd(block),
                stdout=out,
                stderr=subprocess.STDOUT,
                start_new_session=True,  # its own process group: stopped as a whole
            )
        self.background.append((block, proc, log))
        deadline = time.monotonic() + float(block.options.get("timeout", 60))
        while not re.search(block.options["background"], log.read_text(errors="replace")):
            assert proc.poll() is None, f"{block.name} exited {proc.returncode}:\n{log.read_text()}"
            assert time.monotonic() < deadline, f"{block.name} not ready:\n{log.read_text()}"
            time.sleep(0.1)

    def stop(self) -> list[str]:
        """SIGINT every background block as a user's Ctrl-C would; what did not end cleanly."""
        problems = []
        for block, proc, log in self.background:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
            try:
                code = proc.wait(15)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                problems.append(f"{block.name} still running 15 s after SIGINT")
                continue
            if code not in (0, 128 + signal.SIGINT):
                problems.append(f"{block.name} exited {code} on SIGINT:\n{log.read_text()}")
        self.background.clear()
        if self.network is not None:
            self.network.close()
        self._tmp.cleanup()
        return problems


@pytest.fixture(scope="module")
def doc_runs() -> Iterator[dict[Path, DocRun]]:
    runs: dict[Path, DocRun] = {}
    yield runs
    problems = [p for run in runs.values() for p in run.stop()]
    assert not problems, "\n".join(problems)


@pytest.mark.timeout(900)
@pytest.mark.parametrize("block", ALL_BLOCKS, ids=[b.name for b in ALL_BLOCKS])
def test_doc_block_runs_as_written(block: Block, doc_runs: dict[Path, DocRun]) -> None:
    if "skip" in block.options:
        pytest.skip(f"{block.name}: {block.options['skip']}")
    if block.doc not in doc_runs:
        # One document at a time: its background processes hold the ports the next one uses.
        for other in list(doc_runs.values()):
            problems = other.stop()
            assert not problems, "\n".join(problems)
        doc_runs.clear()
        doc_runs[block.doc] = DocRun(block.doc)
    run = doc_runs[block.doc]
    if run.cannot_run is not None and not block.user_file and "file" not in block.options:
        pytest.skip(f"{block.name}: {run.cannot_run}")
    run.run(block)


def test_every_document_has_blocks_that_run() -> None:
    for doc in DOCS:
        if doc.is_relative_to(SITE) and not blocks(doc, ROOT):
            continue  # a page without commands: the reference's, the explanation's
        runnable = [b for b in blocks(doc, ROOT) if "skip" not in b.options]
        assert runnable, f"{doc} has no block the tests run"
