"""The ROS 2 package nav2_pyif (ament_python): what `colcon build` installs from this folder,
with `ros2 run nav2_pyif planner-host`. Outside a colcon workspace, `pip install .` at the
repository root installs the same code (pyproject.toml); the name and version are read from
package.xml."""

from xml.etree import ElementTree

from setuptools import find_packages, setup

PACKAGE = ElementTree.parse("package.xml").getroot()
NAME = PACKAGE.findtext("name")

setup(
    name=NAME,
    version=PACKAGE.findtext("version"),
    packages=find_packages(include=["nav2_pyif", "nav2_pyif.*", "nav2_pyif_entry"]),
    package_data={"": ["py.typed"], "nav2_pyif.runner.maps": ["*.yaml", "*.pgm"]},
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{NAME}"]),
        (f"share/{NAME}", ["package.xml"]),
    ],
    install_requires=["setuptools"],
    zip_safe=False,
    extras_require={"test": ["pytest"]},
    # Through nav2_pyif_entry, as pyproject.toml's: a Ctrl-C while importing exits 130.
    entry_points={
        "console_scripts": [
            "planner-host = nav2_pyif_entry:planner_host",
            "nav2-pyif = nav2_pyif_entry:nav2_pyif",
        ]
    },
)
