"""Record a planner host's calls to MCAP files (``planner-host --record``) and replay them
against another planner offline (``nav2-pyif replay``). Needs the ``record`` extra (mcap)."""
