"""``planner-host --watch``: reload a planner when its source files change.

The reload is the hot swap's (``PlannerService.reload``): a version that fails to import or
to take the live sessions (configure, activate, ...) is refused, and the old one keeps
serving. The files watched are the planner's top-level package (its directory), or its
module file when it is a single module. Uses the ``watchfiles`` library (the ``watch``
extra), imported only when --watch is given: the core stays lean.
"""

from __future__ import annotations

import importlib.util
import logging
import threading
from collections.abc import Callable
from pathlib import Path

from nav2_pyif.server.spec import PlannerSpec

log = logging.getLogger("nav2_pyif.server.host")

WATCH_HINT = "pip install 'nav2-pyif[watch]' (the watchfiles library)"
#: How long a burst of writes (an editor's save) is gathered into one reload [ms]: short,
#: so that the edit-to-served loop stays well under a second.
DEBOUNCE_MS = 50
STEP_MS = 10


def watchfiles_missing() -> str | None:
    """Why --watch cannot run here (None: it can)."""
    if importlib.util.find_spec("watchfiles") is None:
        return f"--watch needs the watchfiles library: {WATCH_HINT}"
    return None


def source_roots(spec: PlannerSpec) -> list[Path]:
    """The planner's sources: its top-level package's directories, or its module file.
    Found without importing it (a top-level name's spec needs no parent package)."""
    module = (spec.planner or "").partition(":")[0] or spec.module or ""
    found = importlib.util.find_spec(module.split(".")[0]) if module else None
    if found is None:
        return []
    if found.submodule_search_locations:
        return [Path(p).resolve() for p in found.submodule_search_locations]
    if found.has_location and found.origin:
        return [Path(found.origin).resolve()]
    return []  # a built-in or frozen module: nothing to watch


def keys_of(changed: set[Path], roots: dict[str, list[Path]]) -> set[str]:
    """The keys whose sources hold a changed file."""
    return {
        key
        for key, paths in roots.items()
        for file in changed
        if any(file == root or root in file.parents for root in paths)
    }


class SourceWatcher:
    """A thread that calls ``on_change(keys, files)`` after each burst of changes to the
    Python files of ``roots`` (key -> its sources)."""

    def __init__(
        self,
        roots: dict[str, list[Path]],
        on_change: Callable[[set[str], list[Path]], None],
    ) -> None:
        self.roots = roots
        self.on_change = on_change
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="source-watch", daemon=True)

    @property
    def paths(self) -> list[Path]:
        return sorted({p for paths in self.roots.values() for p in paths})

    def start(self) -> SourceWatcher:
        for key, paths in self.roots.items():
            where = ", ".join(map(str, paths)) or "nothing (no source file found)"
            log.info("--watch: %s reloads when these change: %s", key, where)
        if self.paths:
            self._thread.start()
        return self

    def _run(self) -> None:
        from watchfiles import PythonFilter, watch

        logging.getLogger("watchfiles").setLevel(logging.WARNING)  # we say what changed

        for batch in watch(
            *self.paths,
            watch_filter=PythonFilter(),
            debounce=DEBOUNCE_MS,
            step=STEP_MS,
            stop_event=self._stop,
            raise_interrupt=False,  # the host's own handlers stop it
        ):
            changed = {Path(path).resolve() for _, path in batch}
            keys = keys_of(changed, self.roots)
            if keys:
                self.on_change(keys, sorted(changed))

    def stop(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=5.0)
