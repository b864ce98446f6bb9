"""What every nav2_pyif process shares: its Zenoh configuration (and how a command-line tool
joins the network: reach), environment-variable defaults for its options, how it ends on
SIGINT/SIGTERM, and starting a planner host as a child. Imports nothing else of nav2_pyif."""
