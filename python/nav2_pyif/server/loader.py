"""Find a planner: ``pkg.module:Class`` or a module of functions (the function-delegate style)."""

from __future__ import annotations

import importlib
import inspect
import sys
import traceback
from types import ModuleType

from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.plugin import PlannerPlugin


def import_module(name: str, *, reload: bool = False) -> ModuleType:
    """Import (or re-import, for hot swap) a module, with a clear error on failure."""
    try:
        if reload and name in sys.modules:
            importlib.invalidate_caches()
            return importlib.reload(sys.modules[name])
        return importlib.import_module(name)
    except BaseException as exc:  # a module may raise anything, even SystemExit, at import
        raise PlannerLoadError(_import_failure(name, exc)) from exc


def _import_failure(name: str, exc: BaseException) -> str:
    """What went wrong importing ``name``, with a hint only where one is true."""
    detail = "".join(traceback.format_exception_only(type(exc), exc)).strip()
    if isinstance(exc, SyntaxError):  # the file was found: no path hint, and no traceback
        return (
            f"cannot import planner module {name!r}: SyntaxError in {exc.filename}, line "
            f"{exc.lineno}: {exc.msg}\n    {(exc.text or '').strip()}"
        )
    if (
        isinstance(exc, ModuleNotFoundError)
        and exc.name
        and (name + ".").startswith(exc.name + ".")
    ):
        return (
            f"cannot import planner module {name!r}: {detail}\n"
            f"(is it installed in this environment, or its directory on PYTHONPATH or given "
            f"with --path?)"
        )
    if isinstance(exc, ModuleNotFoundError):
        return (
            f"cannot import planner module {name!r}: it imports {exc.name!r}, which is not "
            f"installed in this environment: {detail}\n{traceback.format_exc()}"
        )
    return (
        f"planner module {name!r} raised while being imported: {detail}\n{traceback.format_exc()}"
    )


#: The base classes a planner class derives from (nav2_pyif's PlannerPlugin subclasses),
#: named in planner-host's help and in the error for a class that derives from none.
PLUGIN_BASES = (
    "Controller",
    "GlobalPlanner",
    "Smoother",
    "GoalChecker",
    "ProgressChecker",
    "CostmapLayer",
    "Behavior",
    "PathHandler",
)
PLUGIN_BASES_TEXT = f"{', '.join(PLUGIN_BASES[:-1])} or {PLUGIN_BASES[-1]}"


def load_class(
    spec: str, *, kind: str | None = None, reload: bool = False, quiet: bool = False
) -> type[PlannerPlugin]:
    """``pkg.module:Class`` -> the class, checked to be a nav2_pyif plugin (a subclass of
    one of PLUGIN_BASES). ``pkg.module:function`` -> a function-delegate plugin with that
    function as the main role ``kind`` (default: the role it is named after)."""
    module_name, sep, class_name = spec.partition(":")
    if not sep or not module_name or not class_name:
        raise PlannerLoadError(
            f"planner {spec!r} is not of the form 'package.module:ClassName' (or "
            "'package.module:function')"
        )
    module = import_module(module_name, reload=reload)
    cls = getattr(module, class_name, None)
    if inspect.isfunction(cls):
        from nav2_pyif.server.delegates import function_class  # it imports this module

        # the module was just (re)imported: bind its functions without importing it again
        return function_class(module_name, class_name, kind, quiet=quiet)
    if cls is None:
        found = sorted(
            n
            for n, v in vars(module).items()
            if inspect.isclass(v)
            and issubclass(v, PlannerPlugin)
            and v.__module__ == module.__name__
        )
        raise PlannerLoadError(
            f"module {module_name!r} has no class {class_name!r}"
            + (f"; planners it defines: {', '.join(found)}" if found else "")
        )
    if not (inspect.isclass(cls) and issubclass(cls, PlannerPlugin)):
        raise PlannerLoadError(
            f"{spec} is not a nav2_pyif {PLUGIN_BASES_TEXT} subclass (got {type(cls).__name__})"
        )
    if inspect.isabstract(cls):
        missing = ", ".join(sorted(getattr(cls, "__abstractmethods__", ())))
        raise PlannerLoadError(f"{spec} does not implement {missing}")
    return cls
