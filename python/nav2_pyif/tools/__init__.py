"""The `nav2-pyif` command: `router`, `hosts`, `reload`, and `sim` (the runner's command line)."""
