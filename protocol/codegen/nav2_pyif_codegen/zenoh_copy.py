"""The plugin's copy of the default client config (nav2_pyif_protocol.zenoh_defaults):
``bridge_plugin/config/default_session.json5``, which its zenoh-c backend loads."""

from __future__ import annotations

from nav2_pyif_protocol.zenoh_defaults import BRIDGE_COPY, path

from nav2_pyif_codegen.cpp_codec import COMMAND


def files() -> dict[str, str]:
    header = (
        "// Generated from protocol/nav2_pyif_protocol/zenoh/client.json5 by\n"
        f"// `{COMMAND}`: do not edit.\n"
    )
    return {BRIDGE_COPY: header + path("client").read_text()}
