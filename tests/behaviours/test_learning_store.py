"""The learned-model store: JSON round trip, atomic replacement, clear errors on bad files."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from behaviours.learners.effect_models import LinearEffectModel, ModelStore, StoreError
from behaviours.learning import learn

ROOT = Path(__file__).resolve().parents[2]


def learn_into(store: ModelStore, key: tuple[str, ...], slope: float, seed: int = 0):
    """Learn a noisy line e = 0.002 + slope·θ for extend_arm and keep it under key."""
    rng = np.random.default_rng(seed)
    return learn(
        lambda t: 0.002 + slope * t + float(rng.normal(0, 0.003)),
        obj=key[1],
        action=key[2],
        effect_name="opened",
        bounds=(0.0, 0.1),
        delta=0.1,
        n_max=8,
        random_state=seed,
        store=store,
        key=key,
    )


def test_models_survive_the_process(tmp_path: Path) -> None:
    path = tmp_path / "models" / "effects.json"
    store = ModelStore(path)
    lid = learn_into(store, ("o1", "lid", "extend_arm"), 1.3)
    body = learn_into(store, ("o1", "body", "extend_arm"), 0.2, seed=1)
    reread = ModelStore(path)
    assert len(reread) == 2
    assert list(reread) == [("o1", "lid", "extend_arm"), ("o1", "body", "extend_arm")]
    for key, result in ((("o1", "lid", "extend_arm"), lid), (("o1", "body", "extend_arm"), body)):
        stored = reread.get(key)
        assert stored is not None and stored.bounds == (0.0, 0.1)
        assert np.array_equal(stored.model.theta_, result.model.theta_)
        assert stored.model.coef_ == pytest.approx(result.model.coef_)
        assert stored.model.maximum(stored.bounds) == pytest.approx(
            (result.theta_max, result.e_max)
        )
    assert reread.get(("o2", "lid", "extend_arm")) is None
    record = json.loads(path.read_text())["models"][0]
    assert record["key"] == ["o1", "lid", "extend_arm"]
    assert record["slope"] == pytest.approx(lid.model.coef_)


def test_relearning_replaces_the_model_under_its_key(tmp_path: Path) -> None:
    path = tmp_path / "effects.json"
    store = ModelStore(path)
    learn_into(store, ("o1", "lid", "extend_arm"), 1.3)
    second = learn_into(store, ("o1", "lid", "extend_arm"), 0.1, seed=4)
    reread = ModelStore(path)
    assert len(reread) == 1
    assert reread.get(("o1", "lid", "extend_arm")).model.coef_ == pytest.approx(second.model.coef_)


def test_lookup_falls_back_to_the_newest_model_of_the_part_on_another_can(
    tmp_path: Path,
) -> None:
    store = ModelStore(tmp_path / "effects.json")
    o1 = learn_into(store, ("o1", "lid", "extend_arm"), 1.3)
    o3 = learn_into(store, ("o3", "lid", "extend_arm"), 0.9, seed=2)
    learn_into(store, ("o3", "lid", "lift_up"), 0.0, seed=3)
    reread = ModelStore(tmp_path / "effects.json")
    assert reread.lookup("o1", "lid", "extend_arm").model.coef_ == pytest.approx(o1.model.coef_)
    assert reread.lookup("o2", "lid", "extend_arm").model.coef_ == pytest.approx(o3.model.coef_)
    assert reread.lookup("o2", "handle", "extend_arm") is None
    learn_into(reread, ("o1", "lid", "extend_arm"), 1.1, seed=5)  # relearned: newest again
    assert ModelStore(tmp_path / "effects.json").lookup("o2", "lid", "extend_arm").key[0] == "o1"


def test_default_key_is_object_and_action(tmp_path: Path) -> None:
    store = ModelStore(tmp_path / "effects.json")
    learn(
        lambda t: t,
        obj="handle",
        action="lift_up",
        effect_name="opened",
        bounds=(0.0, 0.1),
        delta=0.1,
        n_max=5,
        random_state=0,
        store=store,
    )
    assert ("handle", "lift_up") in ModelStore(tmp_path / "effects.json")


CRASH_SCRIPT = textwrap.dedent(
    """
    import os, sys
    from behaviours.learners.effect_models import LinearEffectModel, ModelStore
    store = ModelStore(sys.argv[1])
    def crash(fd):
        os._exit(3)  # the process dies after writing the temporary file, before the rename
    os.fsync = crash
    store.put(("o1", "lid", "extend_arm"), (0.0, 0.1),
              LinearEffectModel().fit([0.01, 0.05, 0.09], [0.0, 0.0, 0.0]))
    """
)


def test_a_crash_mid_write_leaves_the_old_file(tmp_path: Path) -> None:
    path = tmp_path / "effects.json"
    store = ModelStore(path)
    store.put(
        ("o1", "lid", "extend_arm"), (0.0, 0.1), LinearEffectModel().fit([0.0, 0.1], [0, 0.13])
    )
    before = path.read_bytes()
    crashed = subprocess.run(
        [sys.executable, "-c", CRASH_SCRIPT, str(path)], cwd=ROOT, capture_output=True, timeout=60
    )
    assert crashed.returncode == 3, crashed.stderr.decode()
    assert path.read_bytes() == before
    leftovers = [p.name for p in tmp_path.iterdir() if p.name != path.name]
    assert len(leftovers) == 1 and leftovers[0].startswith(".effects.json.")  # the dead temp file
    assert ModelStore(path).get(("o1", "lid", "extend_arm")).model.coef_ == pytest.approx(1.3)


def test_a_failed_write_cleans_up_and_keeps_the_old_file(tmp_path: Path) -> None:
    path = tmp_path / "effects.json"
    store = ModelStore(path)
    store.put(
        ("o1", "lid", "extend_arm"), (0.0, 0.1), LinearEffectModel().fit([0.0, 0.1], [0, 0.13])
    )
    before = path.read_bytes()
    store.put(("o1", "lid", "lift_up"), (0.0, 0.1), LinearEffectModel().fit([0.0, 0.1], [0, 0.0]))
    assert path.read_bytes() != before
    (tmp_path / "blocked").mkdir()
    blocked = ModelStore(tmp_path / "blocked" / "effects.json")
    (tmp_path / "blocked" / "effects.json").mkdir()  # os.replace onto a folder fails
    with pytest.raises(OSError):
        blocked.put(("o1", "lid", "x"), (0.0, 0.1), LinearEffectModel().fit([0.0, 0.1], [0, 0]))
    assert sorted(p.name for p in (tmp_path / "blocked").iterdir()) == ["effects.json"]
    assert len(blocked) == 0  # memory still matches the disk


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("{not json", "cannot read effect-model store"),
        ('{"format": "other"}', "is not a goalagent effect-model store"),
        ('{"format": "goalagent-effect-models", "version": 9, "models": []}', "has version 9"),
        (
            '{"format": "goalagent-effect-models", "version": 1, "models": [{"key": ["a"]}]}',
            r"effects.json': models\[0\]: must contain \['bounds', 'effect'",
        ),
    ],
)
def test_bad_store_files_give_clear_errors(tmp_path: Path, content: str, message: str) -> None:
    path = tmp_path / "effects.json"
    path.write_text(content)
    with pytest.raises(StoreError, match=message):
        ModelStore(path)


def test_bad_keys_are_refused(tmp_path: Path) -> None:
    store = ModelStore(tmp_path / "effects.json")
    with pytest.raises(ValueError, match="tuple of non-empty strings"):
        store.put(("o1", ""), (0.0, 0.1), LinearEffectModel().fit([0.0, 0.1], [0, 0]))
    assert not (tmp_path / "effects.json").exists()
