"""``planner-host --record``: every call of the chosen keys to size-bounded, rotated MCAP files
(format.py says their layout; nav2_pyif.replay reads them). Needs the ``record`` extra (mcap)."""
