"""nav2-pyif eval: planners compared across many scenarios (scenarios, metrics, jobs, report)."""
