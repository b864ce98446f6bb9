"""Benchmarks of nav2_pyif, each printing its figures (see BENCHMARKS.md)."""
