"""The default Zenoh session configs, as files that are loaded (rmw_zenoh's
``DEFAULT_RMW_ZENOH_SESSION_CONFIG.json5``), not rebuilt in code: ``zenoh/<mode>.json5``
beside this module. The planner host and the nav2-pyif tools load the one of their mode
(nav2_pyif.common.zenoh_config); ``generate`` copies ``client.json5`` into the Nav2 plugin's
package (``bridge_plugin/config/default_session.json5``, installed to its share directory),
which its zenoh-c backend loads (nav2_pyif_codegen.zenoh_copy)."""

from __future__ import annotations

from pathlib import Path

DIRECTORY = Path(__file__).resolve().parent / "zenoh"
MODES = ("peer", "client", "router")
BRIDGE_COPY = "bridge_plugin/config/default_session.json5"


def path(mode: str) -> Path:
    """The default config file of a session in ``mode`` (peer, client or router)."""
    if mode not in MODES:
        raise ValueError(f"no default Zenoh config for mode {mode!r}; modes: {', '.join(MODES)}")
    return DIRECTORY / f"{mode}.json5"
