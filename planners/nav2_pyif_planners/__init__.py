"""Reference planners for nav2_pyif, each short, documented and vectorised with NumPy.

astar.AStar                     global planner: cost-aware 8-connected A* on the costmap
pure_pursuit.RegulatedPurePursuit  controller: Nav2's regulated pure pursuit, in NumPy
mppi.MPPI                       controller: model predictive path integral, >= 1000 rollouts
mppi_jax.MPPIJax                controller: the same in JAX (GPU when present; needs jax)
apf                             controller: an artificial potential field, in the
                                function-delegate style (module functions)
"""
