"""The ROS 2 package nav2_pyif_planners (ament_python): what `colcon build` installs from this
folder. Outside a colcon workspace, `pip install .` at the repository root installs the same
code (pyproject.toml); the name and version are read from package.xml."""

from xml.etree import ElementTree

from setuptools import find_packages, setup

PACKAGE = ElementTree.parse("package.xml").getroot()
NAME = PACKAGE.findtext("name")

setup(
    name=NAME,
    version=PACKAGE.findtext("version"),
    packages=find_packages(include=["nav2_pyif_planners", "nav2_pyif_planners.*"]),
    # Nav2 Jazzy's FollowPath MPPI block, which Nav2MPPI's nav2_jazzy_params() reads
    package_data={"": ["py.typed"], "nav2_pyif_planners.mppi_nav2": ["*.yaml"]},
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{NAME}"]),
        (f"share/{NAME}", ["package.xml"]),
    ],
    install_requires=["setuptools"],
    zip_safe=False,
    extras_require={"test": ["pytest"]},
)
