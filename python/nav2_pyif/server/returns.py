"""Where a planner returned what the host refused (NaN, None, a tuple, ...): its ``return``.

The host finds out only after the method returned, when its frame is gone, so the line is
read from the method's source: its ``return`` statements (not those of nested functions),
narrowed by what was returned (``None``: a bare ``return`` or none at all; a tuple: a
``return a, b``). Only on the error path, cached per method: the hot path pays nothing.
"""

from __future__ import annotations

import ast
import functools
import inspect
import textwrap
import traceback
from collections.abc import Callable
from types import CodeType
from typing import Any

_NESTED = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)


def return_site(planner: object, method: str, returned: Any) -> tuple[traceback.StackSummary, str]:
    """A one-frame stack at the ``return`` of ``planner.method`` that gave ``returned`` (its
    ``def`` line when it has no ``return``), and a note ("" when none) on what else it may
    have been. Raises LookupError when its source cannot be read."""
    func = _function(planner, method)
    code = getattr(func, "__code__", None)
    if not isinstance(code, CodeType):
        raise LookupError(f"{method} is not a Python function")
    returns = _returns(code, func)
    if returns is None:
        raise LookupError(f"no source of {method}")
    if not returns:
        frame = traceback.FrameSummary(code.co_filename, code.co_firstlineno, code.co_name)
        note = f"{code.co_name} has no return statement: it returns None"
        return traceback.StackSummary.from_list([frame]), note
    matching = [line for line, kind in returns if kind == _kind(returned)] or [
        line for line, _ in returns
    ]
    frame = traceback.FrameSummary(code.co_filename, matching[0], code.co_name)
    note = ""
    if len(matching) > 1:
        others = ", ".join(map(str, matching[1:]))
        note = f"(or the return at line {others})"
    return traceback.StackSummary.from_list([frame]), note


def _function(planner: object, method: str) -> Callable[..., Any] | None:
    """The function behind ``method``: a function-delegate module's own, else the method's."""
    funcs = getattr(type(planner), "_funcs", None)  # delegates.py's classes
    if isinstance(funcs, dict) and method in funcs:
        target = funcs[method]
    else:
        target = getattr(type(planner), method, None)
    target = getattr(target, "__func__", target)
    return inspect.unwrap(target) if callable(target) else None


def _kind(value: Any) -> str:
    if value is None:
        return "none"
    return "tuple" if isinstance(value, tuple) else "value"


@functools.lru_cache(maxsize=256)
def _returns(code: CodeType, func: Callable[..., Any]) -> tuple[tuple[int, str], ...] | None:
    """(line, kind of value) of each ``return`` of ``func``, in source order."""
    try:
        lines, start = inspect.getsourcelines(func)
        tree = ast.parse(textwrap.dedent("".join(lines)))
    except (OSError, TypeError, SyntaxError):
        return None
    body = next(
        (n for n in tree.body if isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef)), None
    )
    if body is None:  # a lambda, say
        return None
    found: list[tuple[int, str]] = []
    pending: list[ast.AST] = list(body.body)
    while pending:
        node = pending.pop(0)
        if isinstance(node, _NESTED):
            continue
        if isinstance(node, ast.Return):
            value = node.value
            none = value is None or (isinstance(value, ast.Constant) and value.value is None)
            kind = "none" if none else "tuple" if isinstance(value, ast.Tuple) else "value"
            found.append((start + node.lineno - 1, kind))
        pending.extend(ast.iter_child_nodes(node))
    return tuple(sorted(found))
