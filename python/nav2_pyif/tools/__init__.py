"""The `nav2-pyif` command: `router`, `hosts`, `reload` (admin: the hot swap request a host
answers), and `sim` (the runner's command line)."""
