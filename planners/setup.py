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
)
