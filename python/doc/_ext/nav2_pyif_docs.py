"""The site's pages generated from the code, written before Sphinx reads the sources.

- ``_generated/plugin_parameters.md``: the Nav2 plugin's own parameters, from
  ``nav2_pyif_protocol.bridge_params.BRIDGE_PARAMS`` (the table the C++ settings are
  generated from);
- ``_generated/errors.md``: which nav2_core exception each error type becomes, per plugin
  type, from ``nav2_pyif_protocol.constants``;
- ``_generated/architecture.png``: the call path, drawn by ``architecture_figure``;
- ``_generated/<name>.md``: the repository's own Markdown documents the site shows
  (PROTOCOL.md, RELIABILITY.md, BENCHMARKS.md), their links rewritten for the site by
  ``site_links``.

Pages pull them in with MyST's ``{include}`` and ``{image}``; ``_generated/`` is not
committed."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from architecture_figure import draw_call_path
from nav2_pyif_protocol.bridge_params import BRIDGE_PARAMS, BridgeParam, Kind
from nav2_pyif_protocol.constants import (
    ERRORS_BY_PLUGIN,
    GENERIC_ERROR,
    HOST_FAILURE_ERROR,
    INVALID_ERROR,
)
from site_links import REPOSITORY_DOCUMENTS, for_the_site


def _default(param: BridgeParam) -> str:
    if param.shown_default is not None:
        return param.shown_default
    if param.default is None:
        return "(none)"
    if param.kind is Kind.SECONDS:
        return f"{param.default:g} s"
    return f"`{param.default}`"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def plugin_parameters_table() -> str:
    rows = [
        "| parameter | default | `ros2 param set` on a running plugin | what it does |",
        "|---|---|---|---|",
    ]
    for param in BRIDGE_PARAMS:
        names = ", ".join(f"`{n}`" for n in (param.name, *param.aliases))
        live = "yes" if param.live else "no: read at configure"
        rows.append(f"| {names} | {_cell(_default(param))} | {live} | {_cell(param.doc)} |")
    return "\n".join(rows) + "\n"


def error_mapping_table() -> str:
    rows = [
        "| plugin type | raised by the planner, thrown under its own name | any other "
        "exception | a failing `configure` | the host failed (no host, no reply, a crash) |",
        "|---|---|---|---|---|",
    ]
    for plugin, own in ERRORS_BY_PLUGIN.items():
        names = ", ".join(sorted(f"`{e.value}`" for e in own))
        rows.append(
            f"| {plugin.value} | {names} | `{GENERIC_ERROR[plugin].value}` "
            f"| `{INVALID_ERROR[plugin].value}` | `{HOST_FAILURE_ERROR[plugin].value}` |"
        )
    return "\n".join(rows) + "\n"


DOC = Path(__file__).resolve().parents[1]  # python/doc


def _write_if_changed(path: Path, text: str) -> None:
    """Unchanged files keep their time stamp, so Sphinx rebuilds no page for them."""
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def generate(app: Any) -> None:
    out = Path(app.srcdir) / "_generated"
    out.mkdir(exist_ok=True)
    _write_if_changed(out / "plugin_parameters.md", plugin_parameters_table())
    _write_if_changed(out / "errors.md", error_mapping_table())
    for name, source in REPOSITORY_DOCUMENTS.items():
        # Links resolve against this folder, not app.srcdir: rosdoc2 builds a copy of it
        # elsewhere, with the same pages at the same places.
        _write_if_changed(out / name, for_the_site(source, DOC))
    figure = out / "architecture.png"
    if not figure.exists():
        draw_call_path(figure)


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", generate)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
