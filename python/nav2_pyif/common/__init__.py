"""What every nav2_pyif process shares: its Zenoh configuration, environment-variable defaults
for its options, how it ends on SIGINT/SIGTERM, and starting a planner host as a child. Imports
nothing else of nav2_pyif."""
