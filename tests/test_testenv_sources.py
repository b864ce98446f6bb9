"""testenv/build.sh's sources step from git mirrors: one run names every repository whose
version the mirrors lack (and what each has instead) and still lays out the others, and a mirror
that is a clone with a work tree (OWNER+NAME/repo/.git) is found like a bare one."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from tests.testenv_build import run_build

pytestmark = [
    pytest.mark.integration,  # runs build.sh and git
    pytest.mark.skipif(
        shutil.which("git") is None or shutil.which("bash") is None, reason="needs git and bash"
    ),
]


def _git(*args: str, cwd: Path) -> None:
    subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@t", *args],
        cwd=cwd,
        check=True,
        capture_output=True,
    )


def _repository(at: Path, tags: list[str]) -> None:
    """A git repository at `at` with one commit per tag, each tagged."""
    at.mkdir(parents=True)
    _git("init", "-q", cwd=at)
    for tag in tags:
        (at / "VERSION").write_text(tag + "\n")
        _git("add", "VERSION", cwd=at)
        _git("commit", "-q", "-m", tag, cwd=at)
        _git("tag", tag, cwd=at)


def _bare_mirror(mirrors: Path, name: str, tags: list[str], scratch: Path) -> None:
    work = scratch / name.replace("/", "+")
    _repository(work, tags)
    _git(
        "clone",
        "-q",
        "--bare",
        str(work),
        str(mirrors / name.replace("/", "+") / "repo"),
        cwd=scratch,
    )


def _repos_file(
    path: Path, entries: list[tuple[str, str]], urls: dict[str, str] | None = None
) -> None:
    """A .repos file of ``entries`` (name, version), each at ``urls[name]`` or a URL of no
    known host."""
    lines = ["repositories:"]
    for name, version in entries:
        url = (urls or {}).get(name, f"https://example.invalid/{name}.git")
        lines += [f"  {name}:", "    type: git", f"    url: {url}", f"    version: {version}"]
    path.write_text("\n".join(lines) + "\n")


def _sources(tmp_path: Path, mirrors: Path, repos: Path) -> subprocess.CompletedProcess[str]:
    """build.sh's sources step, from ``mirrors``, into tmp_path/src."""
    return run_build(
        tmp_path, "--mirrors", str(mirrors), "--repos", str(repos), "humble", "sources"
    )


def test_sources_names_every_missing_version_and_lays_out_the_rest(tmp_path: Path) -> None:
    mirrors, scratch = tmp_path / "mirrors", tmp_path / "scratch"
    mirrors.mkdir()
    scratch.mkdir()
    _bare_mirror(mirrors, "org/old_one", ["1.0.0", "1.1.0"], scratch)
    _bare_mirror(mirrors, "org/present", ["2.0.0"], scratch)
    _bare_mirror(mirrors, "org/old_two", ["3.0.0"], scratch)
    # A snapshot that came as a clone with a work tree, not a bare repository.
    _repository(mirrors / "org+cloned" / "repo", ["4.0.0"])
    repos = tmp_path / "test.repos"
    _repos_file(
        repos,
        [
            ("org/old_one", "1.2.0"),
            ("org/present", "2.0.0"),
            ("org/old_two", "3.1.0"),
            ("org/cloned", "4.0.0"),
            ("org/absent", "5.0.0"),
        ],
    )
    sources = tmp_path / "src"
    result = _sources(tmp_path, mirrors, repos)
    assert result.returncode == 1, result.stderr
    assert (
        "org/old_one: " in result.stderr
        and "has no 1.2.0 (its newest release: 1.1.0" in result.stderr
    )
    assert "has no 3.1.0 (its newest release: 3.0.0" in result.stderr
    assert "org/absent: no mirror under" in result.stderr
    assert "3 of 5 repositories lack their version" in result.stderr
    # Those the mirrors have are laid out, after the first missing one too.
    assert (sources / "org/present/VERSION").read_text() == "2.0.0\n"
    assert (sources / "org/cloned/VERSION").read_text() == "4.0.0\n"
    assert not (sources / "org/old_one/VERSION").exists()


def test_a_github_entry_is_found_by_its_url(tmp_path: Path) -> None:
    """An entry whose github.com URL names another repository than its name (a bloom release
    repository, or a second version of one repository) is laid out from that repository's
    mirror under the entry's name."""
    mirrors, scratch = tmp_path / "mirrors", tmp_path / "scratch"
    mirrors.mkdir()
    scratch.mkdir()
    _bare_mirror(mirrors, "org-gbp/thing-release", ["upstream/1.0.0"], scratch)
    _bare_mirror(mirrors, "org/lib", ["1.8.0", "1.9.0"], scratch)
    repos = tmp_path / "test.repos"
    _repos_file(
        repos,
        [("org/thing", "upstream/1.0.0"), ("org/lib", "1.9.0"), ("org/lib-1.8", "1.8.0")],
        urls={
            "org/thing": "https://github.com/org-gbp/thing-release.git",
            "org/lib": "https://github.com/org/lib.git",
            "org/lib-1.8": "https://github.com/org/lib.git",
        },
    )
    result = _sources(tmp_path, mirrors, repos)
    assert result.returncode == 0, result.stderr
    sources = tmp_path / "src"
    assert (sources / "org/thing/VERSION").read_text() == "upstream/1.0.0\n"
    assert (sources / "org/lib/VERSION").read_text() == "1.9.0\n"
    assert (sources / "org/lib-1.8/VERSION").read_text() == "1.8.0\n"


def test_an_entry_with_a_comment_after_its_name_is_its_own(tmp_path: Path) -> None:
    """ "  NAME:  # why" is an entry: its url and version are not taken as the entry above's."""
    mirrors, scratch = tmp_path / "mirrors", tmp_path / "scratch"
    mirrors.mkdir()
    scratch.mkdir()
    _bare_mirror(mirrors, "org/first", ["1.0.0"], scratch)
    _bare_mirror(mirrors, "org/second", ["2.0.0"], scratch)
    repos = tmp_path / "test.repos"
    _repos_file(repos, [("org/first", "1.0.0"), ("org/second", "2.0.0")])
    text = repos.read_text().replace("  org/second:\n", "  org/second:  # a reason\n")
    repos.write_text(text)
    result = _sources(tmp_path, mirrors, repos)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "src/org/first/VERSION").read_text() == "1.0.0\n"
    assert (tmp_path / "src/org/second/VERSION").read_text() == "2.0.0\n"
