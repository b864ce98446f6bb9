"""The nav2_pyif wire protocol: msgpack messages between the Nav2 plugin and the planner host.

PROTOCOL.md (beside this package) is the specification; ``schema`` is its machine-readable
form, ``codec`` encodes and validates, ``arrays`` packs poses, paths and costmaps.
"""

from nav2_pyif_protocol.codec import (
    ErrorInfo,
    ProtocolError,
    Reply,
    Request,
    decode_reply,
    decode_request,
    encode_reply,
    encode_request,
)
from nav2_pyif_protocol.constants import PROTOCOL_VERSION, ErrorType, Op, PluginType
from nav2_pyif_protocol.keys import KeySpace

__all__ = [
    "PROTOCOL_VERSION",
    "ErrorInfo",
    "ErrorType",
    "KeySpace",
    "Op",
    "PluginType",
    "ProtocolError",
    "Reply",
    "Request",
    "decode_reply",
    "decode_request",
    "encode_reply",
    "encode_request",
]
