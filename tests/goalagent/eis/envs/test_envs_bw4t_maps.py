"""BW4T's standard maps (issue 26), re-created from their published layouts: systems naming
them run. Each has BW4T's 28 zones (9 rooms, the drop zone, corridors) and its sequence."""

from __future__ import annotations

import io
from dataclasses import replace
from pathlib import Path

import pytest

from goalagent.eis.envs.bw4t.mapfile import MAPS_DIR, load_map, shipped_maps
from goalagent.eis.exceptions import EnvironmentInterfaceException
from goalagent.mas import MultiAgentSystem

ROBOT = Path(__file__).resolve().parents[4] / "agents" / "examples" / "bw4t_robot.goal"
STANDARD = {"Random": 0, "SuperRandom": 0, "Banana": 6, "Dutch Flag": 6, "Rainbow": 6}


@pytest.mark.parametrize("name, sequence", STANDARD.items())
def test_bw4t_standard_maps_are_shipped(name: str, sequence: int) -> None:
    assert name in shipped_maps()
    layout = load_map(name)
    rooms = [zone for zone in layout.zones if zone.kind == "ROOM" and zone.name != "DropZone"]
    assert len(layout.zones) == 28 and len(rooms) == 9
    assert len(layout.sequence) == sequence
    assert load_map(f"environments/maps/{name}") == layout  # where BW4T setups keep them
    assert load_map(name.lower()) == layout  # BW4T on Windows found a map in any case


@pytest.mark.parametrize("name", ["Random", "Banana"])
def test_a_system_naming_a_standard_map_runs(tmp_path: Path, name: str) -> None:
    (tmp_path / "s.mas2g").write_text(
        f'environment {{ env = "bw4t-client-3.9.1.jar". init = [map = "{name}"]. }}\n'
        f'agentfiles {{ "{ROBOT}" [name = robot]. }}\n'
        "launchpolicy { when entity@env do launch robot. }\n")
    failures: list[str] = []
    system = MultiAgentSystem.from_mas_file(tmp_path / "s.mas2g", output=io.StringIO(),
                                            warn=failures.append)
    try:
        system.run(max_cycles=30)
        assert system.agents and not system.failures
        assert [a.name for a in system.agents] == ["robot"]
        assert system.agents[0].total_actions > 0
    finally:
        system.close()


@pytest.mark.parametrize("system", ["s.mas2g", "batch/s.mas2g"])
def test_a_map_of_bw4t_2s_server_beside_the_client_jar_is_found(tmp_path: Path,
                                                                 system: str) -> None:
    # BW4T 2 ships its server in BW4TServer/ beside BW4TClient.jar, with its maps in
    # BW4TServer/maps/NAME (no suffix); systems name such a map and the jar (goalhub's
    # tradr-bw4t: env = "../BW4T2/BW4TClient.jar", map = "big24")
    maps = tmp_path / "BW4T2" / "BW4TServer" / "maps"
    maps.mkdir(parents=True)
    (maps / "big12").write_text((MAPS_DIR / "TwoRooms.map").read_text())
    path = tmp_path / system
    path.parent.mkdir(exist_ok=True)
    jar = "../BW4T2/BW4TClient.jar" if "/" in system else "BW4T2/BW4TClient.jar"
    text = (f'environment {{ env = "{jar}". init = [map = "big12", agentcount = "1"]. }}\n'
            f'agentfiles {{ "{ROBOT}" [name = robot]. }}\n'
            "launchpolicy { when entity@env do launch robot. }\n")
    path.write_text(text)
    system_run = MultiAgentSystem.from_mas_file(path, output=io.StringIO())
    try:
        assert system_run.environment.world.spec == replace(load_map("TwoRooms"), name="big12")
        system_run.run(max_cycles=5)
        assert not system_run.failures and system_run.agents[0].total_actions > 0
    finally:
        system_run.close()
    path.write_text(text.replace('"big12"', '"big24"'))  # not there: the same clear refusal
    refused = "no map file 'big24' and no shipped map"
    with pytest.raises(EnvironmentInterfaceException, match=refused):
        MultiAgentSystem.from_mas_file(path, output=io.StringIO()).close()
