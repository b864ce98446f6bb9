"""Every key of every package.xml resolves, through rosdistro's rosdep files, to packages that
really provide what the build uses, on the Debian and Ubuntu releases of Humble, Jazzy and
Lyrical (`rosdep install` once said yes to `msgpack`, then the build stopped at
"msgpack.hpp not found" where libmsgpack-dev carries only msgpack-c).

Checked without network against tests/fixtures/rosdep/ (see tests/rosdep_fixture.py, which
records it): the rosdistro excerpt for our keys, and the Debian packages' file lists. What the
build uses is read from its sources (#include lines, CMake find_* calls) and must be named in
USES under the key that provides it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from tests.rosdep_fixture import (
    ROOT,
    ROSDISTRO,
    Platform,
    all_keys,
    applies,
    installed_with,
    load_yaml,
    platforms,
    resolve,
    rosdep_entry,
)

pytestmark = pytest.mark.unit

BRIDGE = ROOT / "bridge_plugin"
EXCERPT = load_yaml(ROSDISTRO)
RECORDED = f"rosdistro {EXCERPT['commit'][:12]}, read {EXCERPT['read']}"
RERECORD = "re-record: python -m tests.rosdep_fixture --rosdistro <a ros/rosdistro clone>"


@dataclass(frozen=True)
class Uses:
    """What the build takes from a system key's packages."""

    headers: tuple[str, ...] = ()  # under /usr/include
    libraries: tuple[tuple[str, ...], ...] = ()  # lib<name>.so, any one name of each tuple
    cmake: tuple[str, ...] = ()  # find_package(<Name>) config files
    python: tuple[str, ...] = ()  # modules under /usr/lib/python3/dist-packages


#: Each system (non-ROS) key of bridge_plugin/package.xml, and what the build uses from it.
USES = {
    "msgpack": Uses(headers=("msgpack.h",), libraries=(("msgpack-c", "msgpackc"),)),
    "nlohmann-json-dev": Uses(headers=("nlohmann/json.hpp",), cmake=("nlohmann_json",)),
    "zlib": Uses(headers=("zlib.h",), libraries=(("z",),)),
    "python3-pytest": Uses(python=("pytest",)),
}
#: Headers and CMake packages that ROS packages provide under other names than their own.
ROS_PROVIDED = {
    "zenoh.hxx": "zenoh_cpp_vendor",
    "zenohc": "zenoh_cpp_vendor",
    "zenohcxx": "zenoh_cpp_vendor",
    "gtest/": "ament_cmake_gtest",  # through gtest_vendor
}
#: CMake lookups of builds outside a ROS workspace, which no rosdep key serves.
OUTSIDE_ROS = {
    "GTest": "the codec-only build (NAV2_PYIF_CODEC_ONLY) without ROS: libgtest-dev",
    "zenohpico": "the zenoh-pico backend of builds outside ROS (found QUIET)",
}
#: What CMake or the compiler brings: CMake's own find modules and the C/C++ toolchain.
CMAKE_MODULES = {"Threads": None, "ZLIB": "zlib"}
# fmt: off
STD_HEADERS = {
    "algorithm", "any", "array", "atomic", "bitset", "cassert", "cctype", "cerrno", "cfloat",
    "charconv", "chrono", "cinttypes", "climits", "clocale", "cmath", "complex",
    "condition_variable", "csetjmp", "csignal", "cstdarg", "cstddef", "cstdint", "cstdio",
    "cstdlib", "cstring", "ctime", "cwchar", "deque", "exception", "execution", "filesystem",
    "forward_list", "fstream", "functional", "future", "initializer_list", "iomanip", "ios",
    "iosfwd", "iostream", "istream", "iterator", "limits", "list", "locale", "map", "memory",
    "memory_resource", "mutex", "new", "numeric", "optional", "ostream", "queue", "random",
    "ratio", "regex", "set", "shared_mutex", "sstream", "stack", "stdexcept", "streambuf",
    "string", "string_view", "system_error", "thread", "tuple", "type_traits", "typeindex",
    "typeinfo", "unordered_map", "unordered_set", "utility", "valarray", "variant", "vector",
}
# fmt: on
LIBC_HEADERS = {
    "unistd.h",
    "signal.h",
    "spawn.h",
    "fcntl.h",
    "errno.h",
    "poll.h",
    "pthread.h",
    "netdb.h",
}
LIBC_DIRS = ("sys/", "netinet/", "arpa/")

_INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
_FIND = re.compile(r"\b(find_package|find_path|find_library)\(\s*([^)]*)\)", re.S)


def _keys() -> dict[str, list[str]]:
    return all_keys(ROOT)


def _ros_keys() -> set[str]:
    return {k for d in EXCERPT["distributions"].values() for k in d["packages"]}


def _sources() -> list[Path]:
    return sorted(p for p in BRIDGE.rglob("*") if p.suffix in {".cpp", ".hpp", ".h", ".hxx"})


def _is_local(include: str, names: set[str]) -> bool:
    return include in names or any(n.endswith("/" + include) for n in names)


def _ros_package(name: str) -> str | None:
    """The ROS package a header path or CMake package comes from, by name."""
    for prefix, package in ROS_PROVIDED.items():
        if name == prefix or (prefix.endswith("/") and name.startswith(prefix)):
            return package
    first = name.split("/")[0]
    return first if "/" in name or name in _ros_keys() else None


def build_uses() -> dict[str, list[str]]:
    """What the build takes from outside the package, read from its sources: "header X",
    "library a|b" and "cmake Name" -> where each is used."""
    local = {str(p.relative_to(BRIDGE)) for p in BRIDGE.rglob("*") if p.is_file()}
    out: dict[str, list[str]] = {}
    for source in _sources():
        for _, include in _INCLUDE.findall(source.read_text(encoding="utf-8")):
            if not _is_local(include, local):
                out.setdefault(f"header {include}", []).append(str(source.relative_to(ROOT)))
    for cmake in sorted([BRIDGE / "CMakeLists.txt", *BRIDGE.glob("cmake/*.cmake")]):
        for call, args in _FIND.findall(cmake.read_text(encoding="utf-8")):
            words = args.split()
            if call == "find_package":
                item = f"cmake {words[0]}"
            elif call == "find_path":
                item = f"header {words[1]}"
            else:
                names = words[words.index("NAMES") + 1 :] if "NAMES" in words else words[1:2]
                item = "library " + "|".join(n for n in names if n.isidentifier() or "-" in n)
            out.setdefault(item, []).append(str(cmake.relative_to(ROOT)))
    return out


def _provider(item: str, keys: set[str]) -> str | None:
    """The key (or "toolchain", "cmake", "outside ROS") that provides one used item."""
    kind, name = item.split(" ", 1)
    for key, uses in USES.items():
        provided = {
            "header": uses.headers,
            "library": ["|".join(names) for names in uses.libraries],
            "cmake": uses.cmake,
        }[kind]
        if name in provided:
            return key
    if kind == "header" and (
        name in STD_HEADERS or name in LIBC_HEADERS or name.startswith(LIBC_DIRS)
    ):
        return "toolchain"
    if kind == "cmake" and name in CMAKE_MODULES:
        return CMAKE_MODULES[name] or "cmake"
    if kind == "cmake" and name in OUTSIDE_ROS:
        return "outside ROS"
    package = _ros_package(name)
    return package if package in keys or (kind == "cmake" and name in keys) else None


# --- the keys against the recorded excerpt ---------------------------------------------------


def test_every_key_is_in_the_recorded_excerpt() -> None:
    keys = set(_keys())
    recorded = _ros_keys() | {k for entries in EXCERPT["rosdep"].values() for k in entries}
    assert not keys - recorded, (
        f"keys of package.xml not in the excerpt ({RECORDED}), or in no rosdep file and no "
        f"distribution: {sorted(keys - recorded)}; {RERECORD}"
    )
    assert not recorded - keys, f"the excerpt names keys no package.xml has: {RERECORD}"


def test_the_target_platforms_are_those_of_humble_jazzy_and_lyrical() -> None:
    names = {(p.distribution, p.name) for p in platforms(EXCERPT)}
    assert names == {
        ("humble", "ubuntu:jammy"),
        ("jazzy", "ubuntu:noble"),
        ("jazzy", "debian:bookworm"),
        ("lyrical", "ubuntu:resolute"),
        ("lyrical", "debian:trixie"),
    }, f"rosdistro's release_platforms changed ({RECORDED}): {sorted(names)}"


@pytest.mark.parametrize("platform", platforms(EXCERPT), ids=lambda p: f"{p.distribution}-{p.name}")
def test_every_key_resolves(platform: Platform) -> None:
    released = EXCERPT["distributions"][platform.distribution]["packages"]
    problems = []
    for key, where in sorted(_keys().items()):
        if not any(applies(w, platform.distribution) for w in where):
            continue  # a conditional dependency of other distributions (REP 149)
        if key in released:
            if released[key] is None:
                problems.append(f"{key} ({where[0]}): not released in {platform.distribution}")
            continue
        entry = rosdep_entry(EXCERPT, key)
        if entry is None or not resolve(entry[1], platform.system, platform.codename):
            problems.append(f"{key} ({where[0]}): no rosdep rule for {platform.name}")
    assert not problems, f"{RECORDED}:\n" + "\n".join(problems)


# --- what the build uses against what the keys provide ---------------------------------------


def test_the_build_uses_only_what_its_keys_provide() -> None:
    keys = set(_keys())
    problems = [
        f"{item} (in {', '.join(sorted(set(where)))})"
        for item, where in sorted(build_uses().items())
        if _provider(item, keys) is None
    ]
    assert not problems, (
        "used by the build but provided by no key of package.xml (add the key, and name the "
        "file in USES under it):\n" + "\n".join(problems)
    )
    assert set(USES) <= keys, f"USES names keys package.xml lacks: {set(USES) - keys}"


def _provides(files: set[str], uses: Uses) -> list[str]:
    """What of `uses` the file list lacks."""
    missing = [f"/usr/include/{h}" for h in uses.headers if f"/usr/include/{h}" not in files]
    for names in uses.libraries:
        if not any(
            re.search(rf"/lib/([^/]+/)?lib{re.escape(n)}\.so$", f) for f in files for n in names
        ):
            missing.append("lib{" + ",".join(names) + "}.so")
    for name in uses.cmake:
        configs = {f"/{name}Config.cmake", f"/{name.lower()}-config.cmake"}
        if not any(f.endswith(c) for f in files for c in configs):
            missing.append(f"{name}Config.cmake")
    for module in uses.python:
        base = f"/usr/lib/python3/dist-packages/{module}"
        if f"{base}/__init__.py" not in files and f"{base}.py" not in files:
            missing.append(f"{base}/__init__.py")
    return missing


def _file_list(platform: Platform) -> dict[str, Any]:
    data = load_yaml(platform.file_list)
    if "unavailable" in data:
        pytest.skip(f"no file lists recorded for {platform.name}: {data['unavailable']}")
    return data


@pytest.mark.parametrize("platform", platforms(EXCERPT), ids=lambda p: f"{p.distribution}-{p.name}")
def test_resolved_packages_provide_what_the_build_uses(platform: Platform) -> None:
    data = _file_list(platform)
    packages = data["packages"]
    problems = []
    for key, uses in sorted(USES.items()):
        entry = rosdep_entry(EXCERPT, key)
        assert entry is not None, f"{key} is no rosdep key ({RECORDED})"
        names = resolve(entry[1], platform.system, platform.codename)
        assert data["resolved"].get(key) == names, (
            f"{platform.file_list.name} was recorded for {key} -> {data['resolved'].get(key)}, "
            f"the excerpt now resolves it to {names}; {RERECORD}"
        )
        installed = installed_with(packages, names)
        files = {f for name in installed for f in packages[name]["files"]}
        missing = _provides(files, uses)
        if missing:
            problems.append(
                f"{key} -> {', '.join(names)} (with {', '.join(installed)}) lacks "
                + ", ".join(missing)
            )
    assert not problems, f"{platform.name} ({data['read']}):\n" + "\n".join(problems)
