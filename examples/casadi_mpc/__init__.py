"""A CasADi/IPOPT model predictive controller served by nav2_pyif (README.md beside this)."""
