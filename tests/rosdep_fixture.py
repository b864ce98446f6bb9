"""The rosdep keys of the repository's package.xml files, against a recorded excerpt of
ros/rosdistro and the file lists of the Debian packages those keys resolve to.

The tests (tests/test_rosdep_keys.py) read what is recorded under tests/fixtures/rosdep/ and
need no network. A maintainer re-records it when a key, rosdistro or a release changes:

    git clone --bare https://github.com/ros/rosdistro /tmp/rosdistro
    python -m tests.rosdep_fixture --rosdistro /tmp/rosdistro      # as root: apt-get update

It reads, at the rosdistro clone's HEAD (or --commit), the release platforms of the target
distributions, which of them releases each ROS package we name, and the entries of
rosdep/base.yaml and rosdep/python.yaml for every other key. For each Debian release among
the platforms it then resolves those keys and records the packages' Depends and file lists
(``apt-get download`` and ``dpkg -c``, from deb.debian.org, with apt lists kept in a private
directory so the machine's own sources are untouched). Ubuntu's archive is not reachable from
where this was first recorded: its platforms are written as unavailable, with the reason, and
the tests skip them saying so.
"""

from __future__ import annotations

import argparse
import datetime
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

ROOT = Path(__file__).resolve().parents[1]
FIXTURE = ROOT / "tests" / "fixtures" / "rosdep"
ROSDISTRO = FIXTURE / "rosdistro.yaml"
#: The ROS 2 distributions whose platforms the project supports (Humble's, Jazzy's and
#: Lyrical's). Kilted shares Jazzy's platforms.
DISTRIBUTIONS = ("humble", "jazzy", "lyrical")
#: The operating systems whose packages rosdep installs for our users.
SYSTEMS = ("debian", "ubuntu")
#: rosdistro's rosdep files that hold system (non-ROS) keys for C++ and Python packages.
ROSDEP_FILES = ("base.yaml", "python.yaml")
#: package.xml elements that name dependencies (REP 149).
DEPENDENCY_TAGS = (
    "depend",
    "build_depend",
    "build_export_depend",
    "buildtool_depend",
    "buildtool_export_depend",
    "exec_depend",
    "run_depend",
    "test_depend",
    "doc_depend",
)
#: What every build machine has anyway (build-essential's C library); not listed.
TOOLCHAIN_PACKAGES = {"libc6-dev", "libc-dev"}
UBUNTU_UNAVAILABLE = (
    "Ubuntu's archive is not reachable from the "
    "machine this was recorded on, and no file list of these Ubuntu packages was found in the "
    "searchable copies of public pages; none is recorded rather than one guessed from Debian's"
)


@dataclass(frozen=True)
class Platform:
    """One release rosdep resolves keys for, e.g. debian:bookworm, and the ROS distribution
    that targets it."""

    distribution: str
    system: str
    codename: str

    @property
    def name(self) -> str:
        return f"{self.system}:{self.codename}"

    @property
    def file_list(self) -> Path:
        return FIXTURE / f"{self.system}-{self.codename}.yaml"


# --- reading: package.xml ------------------------------------------------------------------


def package_xmls(root: Path = ROOT) -> list[Path]:
    """Every package.xml of the repository (not of build trees or virtualenvs)."""
    skip = {".venv", "build", "install", "log", ".git", "node_modules"}
    return sorted(p for p in root.rglob("package.xml") if not skip & set(p.relative_to(root).parts))


def package_keys(xml: Path) -> dict[str, list[str]]:
    """The dependency keys of one package.xml: key -> the tags that name it, each followed by
    ` if <condition>` where the element has a REP 149 condition."""
    keys: dict[str, list[str]] = {}
    for element in ET.parse(xml).getroot():
        if element.tag in DEPENDENCY_TAGS and element.text:
            condition = element.get("condition")
            tag = f"{element.tag} if {condition}" if condition else element.tag
            keys.setdefault(element.text.strip(), []).append(tag)
    return keys


def applies(where: str, distribution: str) -> bool:
    """Whether a key named at ``where`` ("path: tag" or "path: tag if <condition>") is a
    dependency on ``distribution``. Conditions are REP 149's, limited to what our package.xml
    files use: `$ROS_DISTRO == name` and `!=`, joined by `and`."""
    if " if " not in where:
        return True
    condition = where.split(" if ", 1)[1]
    for clause in condition.split(" and "):
        found = re.fullmatch(r"\s*\$ROS_DISTRO\s*(==|!=)\s*(\w+)\s*", clause)
        if not found:
            raise ValueError(f"a condition this check cannot read: {condition!r} ({where})")
        if (found.group(2) == distribution) != (found.group(1) == "=="):
            return False
    return True


def all_keys(root: Path = ROOT) -> dict[str, list[str]]:
    """Every key of every package.xml: key -> "package.xml path: tag" where it is named. The
    repository's own packages (nav2_pyif_bridge depends on nav2_pyif) are not keys: they are
    in the workspace, which `rosdep install --from-paths src --ignore-src` leaves to colcon."""
    xmls = package_xmls(root)
    own = {name for xml in xmls for name in package_field(xml, "name")}
    out: dict[str, list[str]] = {}
    for xml in xmls:
        for key, tags in package_keys(xml).items():
            if key not in own:
                out.setdefault(key, []).extend(f"{xml.relative_to(root)}: {t}" for t in tags)
    return out


def package_field(xml: Path, tag: str) -> list[str]:
    """The texts of a top-level element of a package.xml (version, license, name, ...)."""
    return [(e.text or "").strip() for e in ET.parse(xml).getroot().findall(tag)]


# --- reading: the recorded excerpt -----------------------------------------------------------


def load_yaml(path: Path) -> dict[str, Any]:
    with open(path, encoding="utf-8") as f:
        data = yaml.safe_load(f)
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a mapping")
    return data


def platforms(excerpt: dict[str, Any]) -> list[Platform]:
    """The Debian/Ubuntu release platforms of the target distributions, as recorded."""
    out = []
    for distribution in DISTRIBUTIONS:
        released = excerpt["distributions"][distribution]["release_platforms"]
        for system in SYSTEMS:
            out += [Platform(distribution, system, c) for c in released.get(system, [])]
    return out


def rosdep_entry(excerpt: dict[str, Any], key: str) -> tuple[str, Any] | None:
    """(file, entry) of a system key in the recorded rosdep files, or None."""
    for name in ROSDEP_FILES:
        entries = excerpt["rosdep"].get(name) or {}
        if key in entries:
            return name, entries[key]
    return None


def resolve(entry: Any, system: str, codename: str) -> list[str]:
    """The packages a rosdep entry names for one release, as rosdep resolves it (REP 111):
    a list; or per release with '*' for the others; or an installer's {packages: [...]}.
    [] when the entry names none for this system (the key does not resolve there)."""
    if not isinstance(entry, dict) or system not in entry:
        return []
    rule = entry[system]
    if isinstance(rule, dict) and not {"packages", "apt"} & set(rule):
        rule = rule.get(codename, rule.get("*"))
    if isinstance(rule, dict):
        rule = rule.get("apt", rule)
        rule = rule.get("packages") if isinstance(rule, dict) else rule
    if rule is None:
        return []
    if isinstance(rule, str):
        return [rule]
    return [str(p) for p in rule]


def installed_with(packages: dict[str, Any], names: Iterable[str]) -> list[str]:
    """The recorded packages apt installs with `names`: them and, transitively, their
    recorded Depends."""
    seen: list[str] = []
    todo = list(names)
    while todo:
        name = todo.pop()
        if name in seen or name not in packages:
            continue
        seen.append(name)
        todo += packages[name].get("depends", [])
    return seen


# --- recording -------------------------------------------------------------------------------


def _git(rosdistro: Path, *args: str) -> str:
    return subprocess.run(
        ["git", "-C", str(rosdistro), *args], capture_output=True, text=True, check=True
    ).stdout


def _distribution_packages(distribution: dict[str, Any]) -> dict[str, dict[str, str]]:
    """package -> {repository, version} of a distribution.yaml's released packages."""
    out: dict[str, dict[str, str]] = {}
    for repo_name, repo in (distribution.get("repositories") or {}).items():
        release = repo.get("release")
        if not release:
            continue
        for package in release.get("packages", [repo_name]):
            out[package] = {"repository": repo_name, "version": str(release.get("version"))}
    return out


def record_rosdistro(rosdistro: Path, commit: str, keys: Iterable[str]) -> dict[str, Any]:
    """The excerpt of rosdistro at `commit` for our keys."""
    keys = sorted(keys)
    sha = _git(rosdistro, "rev-parse", commit).strip()
    distributions: dict[str, Any] = {}
    ros_keys: set[str] = set()
    for name in DISTRIBUTIONS:
        data = yaml.safe_load(_git(rosdistro, "show", f"{sha}:{name}/distribution.yaml"))
        released = _distribution_packages(data)
        ros_keys |= {k for k in keys if k in released}
        distributions[name] = {
            "release_platforms": data["release_platforms"],
            "packages": {k: released.get(k) for k in keys if k in released},
        }
    for name in DISTRIBUTIONS:  # a ROS key one distribution lacks is recorded as missing
        packages = distributions[name]["packages"]
        for key in sorted(ros_keys - set(packages)):
            packages[key] = None
    rosdep: dict[str, Any] = {}
    for name in ROSDEP_FILES:
        data = yaml.safe_load(_git(rosdistro, "show", f"{sha}:rosdep/{name}"))
        rosdep[name] = {k: data[k] for k in keys if k in data and k not in ros_keys}
    return {
        "source": "https://github.com/ros/rosdistro",
        "commit": sha,
        "commit_date": _git(rosdistro, "show", "-s", "--format=%cI", sha).strip(),
        "read": datetime.date.today().isoformat(),
        "note": (
            "Only the entries for the keys of this repository's package.xml files. ROS "
            "packages: which repository of each distribution.yaml releases them (null: not "
            "released there). System keys: their rosdep entries, verbatim."
        ),
        "distributions": distributions,
        "rosdep": rosdep,
    }


class Apt:
    """apt-get and apt-cache on one Debian release, with private lists (the machine's own
    sources and package state are neither read nor changed)."""

    def __init__(self, workdir: Path, codename: str) -> None:
        self.dir = workdir / codename
        for sub in ("lists/partial", "cache/archives/partial", "etc", "debs"):
            (self.dir / sub).mkdir(parents=True, exist_ok=True)
        self.source = f"deb http://deb.debian.org/debian {codename} main"
        keyring = "/usr/share/keyrings/debian-archive-keyring.gpg"
        (self.dir / "etc" / "sources.list").write_text(
            self.source.replace("deb ", f"deb [signed-by={keyring}] ", 1) + "\n"
        )
        (self.dir / "status").touch()
        self.options = [
            f"-oDir::Etc::sourcelist={self.dir / 'etc' / 'sources.list'}",
            "-oDir::Etc::sourceparts=/nonexistent",
            f"-oDir::State::Lists={self.dir / 'lists'}",
            f"-oDir::Cache={self.dir / 'cache'}",
            f"-oDir::State::status={self.dir / 'status'}",
        ]
        self._run("apt-get", "update", "-qq")

    def _run(self, tool: str, *args: str, cwd: Path | None = None) -> str:
        return subprocess.run(
            [tool, *self.options, *args], capture_output=True, text=True, check=True, cwd=cwd
        ).stdout

    def show(self, package: str) -> dict[str, str]:
        """The candidate's control fields (Package, Version, Depends, Source, ...)."""
        text = self._run("apt-cache", "show", "--no-all-versions", package)
        fields = {}
        for line in text.splitlines():
            match = re.match(r"^([A-Za-z-]+): (.*)$", line)
            if match:
                fields[match.group(1)] = match.group(2)
        return fields

    def files(self, package: str) -> list[str]:
        """The files the package installs (dpkg -c), without its documentation."""
        self._run("apt-get", "download", "-qq", package, cwd=self.dir / "debs")
        (deb,) = (self.dir / "debs").glob(f"{package}_*.deb")
        listing = subprocess.run(
            ["dpkg", "-c", str(deb)], capture_output=True, text=True, check=True
        ).stdout
        out = []
        for line in listing.splitlines():
            if line.startswith("d"):
                continue
            path = line.split(None, 5)[5].split(" -> ")[0].removeprefix(".")
            if not re.match(r"^/usr/share/(doc|man|lintian)/", path):
                out.append(path)
        return sorted(out)


def _depends(fields: dict[str, str]) -> list[str]:
    """Depends, each as its first alternative's package name."""
    out = []
    for item in fields.get("Depends", "").split(","):
        name = item.split("|")[0].strip().split(" ")[0].split(":")[0]
        if name:
            out.append(name)
    return out


def record_debian(workdir: Path, platform: Platform, excerpt: dict[str, Any]) -> dict[str, Any]:
    """The file lists of what our system keys resolve to on one Debian release."""
    apt = Apt(workdir, platform.codename)
    packages: dict[str, Any] = {}
    resolved: dict[str, list[str]] = {}
    for name in ROSDEP_FILES:
        for key, entry in sorted((excerpt["rosdep"].get(name) or {}).items()):
            resolved[key] = resolve(entry, platform.system, platform.codename)
    # Each resolved package; its direct Depends that are development packages; and any
    # package built from the same source, at any depth (a transitional package's successor).
    todo = [(p, 0, "") for names in resolved.values() for p in names]
    while todo:
        name, depth, parent_source = todo.pop(0)
        if name in packages or name in TOOLCHAIN_PACKAGES:
            continue
        fields = apt.show(name)
        source = fields.get("Source", name).split(" ")[0]
        if depth > 0 and not (source == parent_source or (depth == 1 and name.endswith("-dev"))):
            continue
        depends = _depends(fields)
        packages[name] = {
            "version": fields["Version"],
            "source": source,
            "depends": depends,
            "files": apt.files(name),
        }
        todo += [(d, depth + 1, source) for d in depends]
    return {
        "platform": platform.name,
        "source": apt.source,
        "read": datetime.date.today().isoformat(),
        "note": (
            "What our system keys resolve to here (per rosdistro.yaml), with Depends (first "
            "alternatives) and files (dpkg -c, without /usr/share/doc, man, lintian). Listed: "
            "each resolved package, its direct Depends that are -dev packages, and the "
            "packages built from the same source at any depth; deeper Depends are named only."
        ),
        "resolved": resolved,
        "packages": packages,
    }


def _dump(path: Path, data: dict[str, Any], header: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(header)
        yaml.safe_dump(data, f, sort_keys=False, width=100, allow_unicode=True)
    print(f"wrote {path.relative_to(ROOT)}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m tests.rosdep_fixture",
        description="Record tests/fixtures/rosdep/ from a ros/rosdistro clone and Debian's "
        "archive.",
    )
    parser.add_argument("--rosdistro", type=Path, required=True, help="a ros/rosdistro clone")
    parser.add_argument("--commit", default="HEAD", help="the rosdistro commit (default HEAD)")
    args = parser.parse_args(argv)
    header = "# Recorded by `python -m tests.rosdep_fixture`; do not edit by hand.\n"
    excerpt = record_rosdistro(args.rosdistro, args.commit, all_keys())
    _dump(ROSDISTRO, excerpt, header)
    with tempfile.TemporaryDirectory(prefix="rosdep-fixture-") as tmp:
        for platform in platforms(excerpt):
            if platform.system == "debian":
                data = record_debian(Path(tmp), platform, excerpt)
            else:
                data = {"platform": platform.name, "unavailable": UBUNTU_UNAVAILABLE}
            _dump(platform.file_list, data, header)
    return 0


if __name__ == "__main__":
    sys.exit(main())
