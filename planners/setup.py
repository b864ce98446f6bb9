"""The ROS 2 package nav2_pyif_planners (ament_python): what `colcon build` installs from this
folder. Outside a colcon workspace it is the distribution nav2-pyif-planners, apart from the
core (which installs no planner): `pip install ./planners` in a clone. The name and version
are read from package.xml."""

from xml.etree import ElementTree

from setuptools import find_packages, setup

PACKAGE = ElementTree.parse("package.xml").getroot()
NAME = PACKAGE.findtext("name")
VERSION = PACKAGE.findtext("version")

setup(
    name=NAME,
    version=VERSION,
    packages=find_packages(include=["nav2_pyif_planners", "nav2_pyif_planners.*"]),
    # Nav2 Jazzy's FollowPath MPPI block, which Nav2MPPI's nav2_jazzy_params() reads
    package_data={"": ["py.typed"], "nav2_pyif_planners.mppi_nav2": ["*.yaml"]},
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{NAME}"]),
        (f"share/{NAME}", ["package.xml"]),
    ],
    # For pip: the API of the same release. colcon installs without resolving these (the
    # workspace's nav2_pyif satisfies the first; package.xml names what rosdep installs).
    install_requires=["setuptools", f"nav2-pyif=={VERSION}", "numpy>=1.24"],
    zip_safe=False,
    # jax: the JAX planners (mppi_jax, mppi_nav2, learned) on the CPU; jax[cuda12] for GPUs.
    extras_require={"test": ["pytest"], "jax": ["jax>=0.4.30"]},
    # The short names `nav2-pyif sim` takes (--controller mppi, ...), found by entry point.
    entry_points={
        "nav2_pyif.planners": [
            "astar = nav2_pyif_planners.astar:AStar",
            "pure_pursuit = nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
            "mppi = nav2_pyif_planners.mppi:MPPI",
            "mppi_jax = nav2_pyif_planners.mppi_jax:MPPIJax",
            "mppi_nav2 = nav2_pyif_planners.mppi_nav2:Nav2MPPI",  # Nav2 MPPI (Jazzy) in JAX
            "learned = nav2_pyif_planners.learned.controller:LearnedController",  # needs --scan
            "apf = nav2_pyif_planners.apf",  # function-delegate style: its functions are the roles
            # Nav2's other plugins (--smoother, --goal-checker, --progress-checker, --layer,
            # --recovery)
            "simple_smoother = nav2_pyif_planners.simple_smoother:SimpleSmoother",
            "stopped_goal_checker = nav2_pyif_planners.checker_plugins:StoppedGoalChecker",
            "simple_progress_checker = nav2_pyif_planners.checker_plugins:SimpleProgressChecker",
            "keepout = nav2_pyif_planners.keepout_layer:KeepOutLayer",
            "free_backup = nav2_pyif_planners.free_backup:FreestBackUp",
        ]
    },
)
