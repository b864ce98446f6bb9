"""Coverage-guided fuzzing (atheris, libFuzzer) of the planner host's request path: decode,
dispatch to a reference planner of each plugin type, encode the reply (tests/host_path.py).
A crash is a reply that breaks the contract (undecodable, an untyped error), an exception out
of the host, or a module the request made the host import; libFuzzer then saves the input.

    python -m tests.fuzz_host_path --seconds 600      # a campaign (RELIABILITY.md)
    python -m tests.fuzz_host_path --runs 2000        # what the suite runs

The seed corpus is every shared vector (protocol/vectors) to every plugin type's planner.
Exit status: 0 when nothing broke; libFuzzer's own (1 for a crash, 77/70 on a timeout or out
of memory, 72 when interrupted) otherwise; 2 for a usage error.
"""

from __future__ import annotations

import argparse
import importlib.util
import logging
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

#: the code the fuzzer measures coverage of: the host, the protocol, the reference planners
INSTRUMENTED = ["nav2_pyif", "nav2_pyif_protocol", "nav2_pyif_planners"]


def parse(argv: list[str]) -> argparse.Namespace:
    # Imported here, not at the top: the fuzzing child instruments nav2_pyif as it imports
    # it, and a module imported before that is measured by no coverage.
    from nav2_pyif.common.option_types import positive_int

    parser = argparse.ArgumentParser(
        prog="python -m tests.fuzz_host_path",
        description="Fuzz the planner host's request path with atheris (coverage-guided).",
    )
    budget = parser.add_mutually_exclusive_group()
    budget.add_argument("--seconds", type=positive_int, help="stop after this long (default 600)")
    budget.add_argument("--runs", type=positive_int, help="stop after this many inputs")
    parser.add_argument(
        "--artifacts",
        type=Path,
        help="where a crashing input is saved (default: a new temporary folder, kept only "
        "when it holds one)",
    )
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    """Prepare the corpus folders, run the fuzzer in a child (libFuzzer ends its process
    itself), remove the folders whatever happens; a kept crash is named."""
    args = parse(sys.argv[1:] if argv is None else argv)
    if importlib.util.find_spec("atheris") is None:
        print(
            "fuzz_host_path: atheris is not installed (pip install atheris; the dev extra "
            "has it on x86-64 Linux)",
            file=sys.stderr,
        )
        return 2
    work = Path(tempfile.mkdtemp(prefix="nav2_pyif_fuzz_"))
    artifacts = args.artifacts or work / "artifacts"
    artifacts.mkdir(parents=True, exist_ok=True)
    budget = f"-runs={args.runs}" if args.runs else f"-max_total_time={args.seconds or 600}"
    child: subprocess.Popen[bytes] | None = None

    def stop(signum: int, frame: object) -> None:
        raise KeyboardInterrupt if signum == signal.SIGINT else SystemExit(128 + signum)

    signal.signal(signal.SIGTERM, stop)
    try:
        child = subprocess.Popen([sys.executable, "-c", _CHILD, str(work), str(artifacts), budget])
        code = child.wait()
    except KeyboardInterrupt:
        code = 130
    except SystemExit as exc:
        code = int(exc.code or 1)
    finally:
        if child is not None and child.poll() is None:
            child.terminate()
            child.wait()
        crashes = sorted(artifacts.iterdir())
        if crashes and args.artifacts is None:
            kept = Path(tempfile.mkdtemp(prefix="nav2_pyif_fuzz_crashes_"))
            for crash in crashes:
                shutil.move(str(crash), kept)
            print(f"fuzz_host_path: {len(crashes)} crashing input(s) kept in {kept}")
        shutil.rmtree(work, ignore_errors=True)
    return code


def fuzz(work: Path, artifacts: Path, budget: str) -> None:
    """The child: the harness, instrumented, under libFuzzer (which exits the process)."""
    import atheris

    logging.disable(logging.CRITICAL)  # every refused request would be logged
    with atheris.instrument_imports(include=INSTRUMENTED):
        from tests.host_path import HostPath, seed_inputs
    host = HostPath()
    seeds, corpus = work / "seeds", work / "corpus"
    seeds.mkdir()
    corpus.mkdir()
    for i, seed in enumerate(seed_inputs()):
        (seeds / f"seed{i:04d}").write_bytes(seed)
    print(f"fuzz_host_path: crashing inputs are saved to {artifacts}/", flush=True)
    atheris.Setup(
        [
            sys.argv[0],
            budget,
            "-print_final_stats=1",
            "-rss_limit_mb=4096",
            "-timeout=20",
            f"-artifact_prefix={artifacts}/",
            str(corpus),
            str(seeds),
        ],
        host.one_input,
    )
    atheris.Fuzz()


_CHILD = "import sys; from tests.fuzz_host_path import fuzz; from pathlib import Path; " + (
    "fuzz(Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3])"
)

if __name__ == "__main__":
    sys.exit(main())
