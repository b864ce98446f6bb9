"""The ROS 2 package nav2_pyif_protocol (ament_python): what `colcon build` installs from this
folder. Outside a colcon workspace, `pip install .` at the repository root installs the same
code (pyproject.toml); the name and version are read from package.xml. The code generators
beside it (codegen/) are a development tool, installed by neither."""

from xml.etree import ElementTree

from setuptools import find_packages, setup

PACKAGE = ElementTree.parse("package.xml").getroot()
NAME = PACKAGE.findtext("name")

setup(
    name=NAME,
    version=PACKAGE.findtext("version"),
    packages=find_packages(include=["nav2_pyif_protocol", "nav2_pyif_protocol.*"]),
    # the default Zenoh session configs the host and tools load (zenoh_defaults)
    package_data={"": ["py.typed"], "nav2_pyif_protocol": ["zenoh/*.json5"]},
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{NAME}"]),
        (f"share/{NAME}", ["package.xml"]),
    ],
    install_requires=["setuptools"],
    zip_safe=False,
    extras_require={"test": ["pytest"]},
)
