#!/usr/bin/env python3
"""Compile the plugin's Nav2 translation units against one distribution's real headers.

For a distribution whose ROS 2 core cannot be built here (Lyrical: testenv/README.md), this is
the check that the plugin sources compile against its Nav2 plugin interfaces: every
`bridge_plugin/src/nav2/*.cpp` is compiled (to an object file, so templates and the pluginlib
registrations are instantiated: a pure virtual left unimplemented fails PLUGINLIB_EXPORT_CLASS)
with these include paths, in this order:

1. every `include/` folder of the packages under `--sources` (the distribution's own sources:
   Nav2's nav2_core, nav2_ros_common, nav2_costmap_2d, nav2_util, nav2_behaviors, ..., and
   whatever else of its `.repos` is laid out, e.g. bond_core);
2. forwarding headers for geometry2 0.45's rename of tf2's and tf2_ros's `.h` headers to
   `.hpp` (`tf2_ros/buffer.hpp` holding `#include "tf2_ros/buffer.h"`), generated into `--out`
   for each `.h` the base has without its `.hpp`;
3. the C++ headers of the sources' nav2_msgs, generated from its .msg/.srv/.action files by
   the base's rosidl_generator_cpp (the distribution's own messages, the base's generator);
4. every `include/*` folder of `--base` (a built environment: its `ros/` install and `venv/`),
   leaving out the packages the sources have: the base's rclcpp, tf2, common messages, and
   the zenoh-cpp headers.

What it proves: the plugin's classes implement the distribution's nav2_core / nav2_costmap_2d
interfaces exactly (signatures, pure virtuals, node and TF types), and the plugin's code
compiles against its Nav2 headers, warning-free with -Wall -Wextra -Wpedantic -Werror (warnings
in those headers are theirs: they are -isystem). What it does not: that the plugin links or
runs there, that CMake configures there, nor that the base's ROS 2 core (rclcpp, tf2, the
common messages, the message generator) is the distribution's: an API difference in those is
not seen. `--expect-api` checks which API `nav2_pyif_bridge/nav2_api.hpp` detected.

Exit status: 0 all compiled, 1 a file failed, 2 usage error (a folder missing).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import os
import shlex
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PLUGIN = REPO / "bridge_plugin"
# geometry2 0.45 (Kilted and Lyrical) renamed these packages' headers from .h to .hpp.
RENAMED_TO_HPP = ("tf2", "tf2_ros")
# Message packages of the sources whose C++ headers are generated here (by the base's rosidl).
GENERATED = ("nav2_msgs",)
GENERATE_CPP = """
import pathlib, sys
from rosidl_generator_cpp.cli import GenerateCpp
source, out, *include_paths = sys.argv[1:]
source = pathlib.Path(source)
files = [
    f"{source}:{path.relative_to(source).as_posix()}"
    for kind in ("msg", "srv", "action")
    for path in sorted((source / kind).glob("*." + kind))
]
GenerateCpp("cpp").generate(source.name, files, include_paths, pathlib.Path(out) / source.name)
"""
API_MACROS = {
    "humble": (0, 0),
    "jazzy": (1, 0),
    "lyrical": (1, 1),
}


def source_packages(sources: Path) -> dict[str, Path]:
    """package name -> its folder, for each package.xml under `sources`."""
    found: dict[str, Path] = {}
    for manifest in sorted(sources.rglob("package.xml")):
        package = manifest.parent
        if any(part.startswith(".") or part == "test" for part in package.parts):
            continue
        found.setdefault(package.name, package)
    return found


def generate_messages(package: Path, base: Path, setup: Path, out: Path) -> None:
    """The C++ headers of a message package of the sources, by the base's generator (in the
    base's environment, `setup` sourced). Skipped when done for these sources before."""
    stamp = out / package.name / ".generated"
    newest = max(p.stat().st_mtime for p in package.rglob("*") if p.is_file())
    if stamp.exists() and stamp.stat().st_mtime >= newest:
        return
    shares = [str(base / "venv" / "share"), str(base / "ros" / "share")]
    script = (
        f"source {shlex.quote(str(setup))} >/dev/null && exec python3 -c "
        f"{shlex.quote(GENERATE_CPP)} {shlex.join([str(package), str(out), *shares])}"
    )
    done = subprocess.run(["bash", "-c", script], capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"generating {package.name}'s C++ headers failed:\n{done.stderr}")
    stamp.touch()


def base_include_dirs(base: Path) -> list[Path]:
    """The per-package include folders of the base's ROS install and venv."""
    dirs: list[Path] = []
    for root in (base / "ros" / "include", base / "venv" / "include"):
        if root.is_dir():
            dirs.extend(sorted(p for p in root.iterdir() if p.is_dir()))
    return dirs


def zenoh_flags(base: Path) -> list[str]:
    """zenoh-cpp over the base's zenoh-pico (the plugin's transport; no Nav2 in it)."""
    include = base / "zenoh-pico" / "include"
    if not include.is_dir():
        return []
    # what the zenohcxx::zenohpico and zenohpico targets give their users on Linux
    defines = ["ZENOHCXX_ZENOHPICO", "ZENOH_C_STANDARD=11", "ZENOH_LINUX", "ZENOH_COMPILER_GCC"]
    return ["-isystem", str(include), *(f"-D{d}" for d in defines)]


def write_renamed_headers(base_dirs: list[Path], shim: Path) -> int:
    """`X.hpp` forwarding to `X.h` for each tf2 / tf2_ros header the base has only as .h."""
    written = 0
    for directory in base_dirs:
        if directory.name not in RENAMED_TO_HPP:
            continue
        for header in (directory / directory.name).rglob("*.h"):
            relative = header.relative_to(directory)
            if header.with_suffix(".hpp").exists():
                continue
            target = shim / relative.with_suffix(".hpp")
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(
                "// Forwarding header: this base names it .h (testenv/compile_against_headers.py)\n"
                f'#include "{relative.as_posix()}"\n'
            )
            written += 1
    return written


def include_flags(sources: Path, base: Path, setup: Path, out: Path) -> list[str]:
    own = source_packages(sources)
    base_dirs = base_include_dirs(base)
    write_renamed_headers(base_dirs, out / "renamed_headers")
    flags = ["-I", str(PLUGIN / "include")]
    for package in own.values():
        if (package / "include").is_dir():
            flags += ["-isystem", str(package / "include")]
    for name in GENERATED:
        if name in own:
            generate_messages(own[name], base, setup, out / "generated")
            flags += ["-isystem", str(out / "generated")]
    flags += ["-isystem", str(out / "renamed_headers")]
    for directory in base_dirs:
        package = own.get(directory.name)
        if package and ((package / "include").is_dir() or package.name in GENERATED):
            continue  # the distribution's own headers win (a message package's are the base's)
        flags += ["-isystem", str(directory)]
    return flags + zenoh_flags(base)


def compile_one(
    compiler: str, std: str, flags: list[str], source: Path, out: Path
) -> tuple[Path, int, str]:
    command = [
        compiler,
        f"-std={std}",
        "-fPIC",
        "-Wall",
        "-Wextra",
        "-Wpedantic",
        "-Werror",
        "-DNAV2_PYIF_NAV2_MAX_KEEP_UNKNOWN=1",  # what CMake sets for nav2_costmap_2d >= 1.3
        *flags,
        "-c",
        str(source),
        "-o",
        str(out / (source.stem + ".o")),
    ]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    return source, done.returncode, done.stderr


def api_probe(out: Path, api: str) -> Path:
    jazzy, lyrical = API_MACROS[api]
    probe = out / f"expect_{api}_api.cpp"
    probe.write_text(
        '#include "nav2_pyif_bridge/nav2_api.hpp"\n'
        f'static_assert(NAV2_PYIF_JAZZY_API == {jazzy}, "expected the {api} API");\n'
        f'static_assert(NAV2_PYIF_LYRICAL_API == {lyrical}, "expected the {api} API");\n'
    )
    return probe


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="Example: testenv/compile_against_headers.py --sources "
        "/srv/trixie/opt/nav2_pyif_testenv/lyrical/src --base /opt/nav2_pyif_testenv/jazzy "
        "--expect-api lyrical --std c++20",
    )
    parser.add_argument("--sources", type=Path, required=True, help="the distribution's sources")
    parser.add_argument(
        "--base", type=Path, required=True, help="a built environment (ros/, venv/) for the core"
    )
    parser.add_argument(
        "--setup",
        type=Path,
        help="the base's setup script, for its message generator (default: "
        "BASE/setup-zenoh-pico.bash)",
    )
    parser.add_argument(
        "--out",
        type=Path,
        default=Path("/tmp/nav2_pyif_header_check"),
        help="objects, generated and forwarding headers",
    )
    parser.add_argument("--expect-api", choices=sorted(API_MACROS), help="fail unless detected")
    parser.add_argument(
        "--std",
        default="c++17",
        help="the C++ standard (Lyrical's Nav2 needs c++20: its nav2_package() sets it, and the "
        "plugin's CMake does the same for the Lyrical API)",
    )
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--compiler", default=os.environ.get("CXX", "g++"))
    parser.add_argument("files", nargs="*", type=Path, help="default: bridge_plugin/src/nav2/*.cpp")
    args = parser.parse_args(argv)
    setup = args.setup or args.base / "setup-zenoh-pico.bash"
    for folder in (args.sources, args.base):
        if not folder.is_dir():
            print(f"compile_against_headers: no folder {folder}", file=sys.stderr)
            return 2
    if not setup.is_file():
        print(f"compile_against_headers: no setup script {setup} (--setup)", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    try:
        flags = include_flags(args.sources, args.base, setup, args.out)
    except RuntimeError as error:
        print(f"compile_against_headers: {error}", file=sys.stderr)
        return 1
    files = args.files or sorted((PLUGIN / "src" / "nav2").glob("*.cpp"))
    if args.expect_api:
        files = [api_probe(args.out, args.expect_api), *files]
    print("flags:", shlex.join(flags), flush=True)
    failed = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        jobs = [
            pool.submit(compile_one, args.compiler, args.std, flags, f, args.out) for f in files
        ]
        for job in jobs:
            source, code, stderr = job.result()
            print(f"{'ok  ' if code == 0 else 'FAIL'} {source.name}", flush=True)
            if code != 0:
                failed += 1
                print(stderr, flush=True)
    print(f"{len(files) - failed} of {len(files)} compiled")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
