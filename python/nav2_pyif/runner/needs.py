"""What the offline runner needs beyond the planner host: matplotlib for the picture of each
run, tqdm for the progress bar. They are the ``runner`` extra (``pip install
'nav2-pyif[runner]'``), not dependencies of the host or of the authors' API, so the runner
checks for them before it starts anything."""

from __future__ import annotations

from importlib.util import find_spec

#: How to install them, with pip and in a ROS workspace.
INSTALL_HINT = (
    "install the runner extra: pip install 'nav2-pyif[runner]' (in a ROS 2 workspace: "
    "sudo apt install python3-matplotlib python3-tqdm)"
)


def missing(*, progress: bool) -> list[str]:
    """The runner's modules that cannot be imported: matplotlib always (every run is drawn),
    tqdm when the progress bar is shown."""
    wanted = ["matplotlib", *(["tqdm"] if progress else [])]
    return [name for name in wanted if find_spec(name) is None]
