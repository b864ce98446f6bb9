"""Hostile requests made from the shared vectors (protocol/vectors): a vector with a few bytes
flipped, inserted, deleted, cut short, or replaced by a msgpack head that claims a big length
or count. The hostile peer (hostile_fuzzer) sends them; the Hypothesis tests draw them too."""

from __future__ import annotations

import json
import random
from pathlib import Path

#: the shared vectors, in the checkout this package is installed from (editable)
VECTORS = Path(__file__).resolve().parents[2] / "protocol" / "vectors"
#: msgpack heads of a str, bin, ext, array or map whose length or count follows
CLAIMING_HEADS = (0xC6, 0xC9, 0xDB, 0xDD, 0xDF, 0xDC, 0xDE)


def load_seeds(kind: str = "request") -> dict[str, tuple[str, bytes]]:
    """name -> (op, bytes) of every shared vector of ``kind`` (request or reply)."""
    index = json.loads((VECTORS / "index.json").read_text())["vectors"]
    return {
        e["name"]: (e["op"], (VECTORS / f"{e['name']}.msgpack").read_bytes())
        for e in index
        if e["kind"] == kind
    }


def mutate(rng: random.Random, data: bytes, max_edits: int = 4) -> bytes:
    """``data`` with 1 to ``max_edits`` random edits."""
    out = bytearray(data)
    for _ in range(rng.randint(1, max_edits)):
        where = rng.randint(0, len(out))
        action = rng.choice(("flip", "insert", "delete", "cut", "claim"))
        if action == "cut":
            del out[where:]
        elif action == "insert":
            out[where:where] = rng.randbytes(rng.randint(1, 8))
        elif where < len(out):
            if action == "flip":
                out[where] ^= 1 << rng.randint(0, 7)
            elif action == "delete":
                del out[where]
            else:
                out[where] = rng.choice(CLAIMING_HEADS)
    return bytes(out)
