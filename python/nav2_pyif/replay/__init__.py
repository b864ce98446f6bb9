"""``nav2-pyif replay``: a recording's calls (planner-host --record) fed, in order, to planners
served as the host serves them, offline; how each output differs from the recorded one."""
