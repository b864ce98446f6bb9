"""A Dynamic Window Approach controller in NumPy served by nav2_pyif (README.md beside this)."""
