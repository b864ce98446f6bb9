"""Bundled maps (map_server format), each with a default start and goal.

office       20 x 14 m: rooms, doorways 1 m wide, a corridor, furniture
cluttered    14 x 10 m: scattered boxes and a 0.8 m zig-zag corridor
"""

from __future__ import annotations

from pathlib import Path

MAPS_DIR = Path(__file__).parent
BUNDLED = ("office", "cluttered")


def map_path(name_or_path: str) -> Path:
    """A bundled map's YAML by name, or the given path."""
    if name_or_path in BUNDLED:
        return MAPS_DIR / f"{name_or_path}.yaml"
    return Path(name_or_path)
