"""An OMPL RRT* / PRM* global planner served by nav2_pyif (README.md beside this file)."""
