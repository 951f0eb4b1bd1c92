"""``ch5-agent``: thesis Table 5.4 through the agent. The garbage disposal agent learns each can
by transfer (``learning=transfer``) from every can learned before it, in the thesis's order
and in others, in truth and camera perception; per can: did it finish its disposals, how many
exploratory actions did learning take, how many actions did the agent take, beside Algorithm
6 alone from the same known objects (its N) and the agent learning randomly on the same can
(issue 32). The runs are ``studies/common/ch5_agent.py``'s.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import product
from typing import Annotated

from pydantic import Field, field_validator

from robot.reproduce.framework import (
    Claim,
    Deviation,
    Figure,
    Metric,
    Panel,
    Progress,
    SeedResult,
    Series,
    Study,
    StudyConfig,
    in_turn,
    markdown_table,
)
from robot.reproduce.studies.common.ch5 import CH5_DEVIATIONS, NEW_CANS, THESIS_CANS, Perception

ORDERS = {
    "thesis": THESIS_CANS + NEW_CANS,
    "o2-first": ("o2", "o1", "o3", "o5", "o4", "slide", "pedal"),
    "new-first": ("pedal", "slide", "o5", "o4", "o3", "o2", "o1"),
}
THESIS_N_TRAN = {"o2": 29, "o3": 1, "o4": 3, "o5": 11}
"""Table 5.4's N_tran: the actions that opened the can with transfer."""


class Config(StudyConfig):
    """Which cans in which orders, seen how, and the task the agent does on each."""

    orders: dict[str, tuple[str, ...]] = ORDERS
    """The orders the cans are presented in, by name: the thesis's (§5.6.1, then the two new
    mechanisms), one with o2 first and o5 before o4, one with the new mechanisms first. Each
    order starts from an empty known-object database."""
    perceptions: tuple[Perception, ...] = ("truth", "camera")
    """How the cans are seen: the simulator's ground truth and/or the rendered head camera."""
    trials: Annotated[int, Field(ge=1)] = 5
    """Balls the agent disposes of in each can (§6.4.2: five trials)."""
    max_cycles: Annotated[int, Field(ge=1)] = 400
    """Reasoning cycles a run on one can may take at most."""

    @field_validator("orders")
    @classmethod
    def _known_cans(cls, orders: dict[str, tuple[str, ...]]) -> dict[str, tuple[str, ...]]:
        from sim.canfile import CanFileError, find_can

        if not orders:
            raise ValueError("give at least one order")
        for name, cans in orders.items():
            if not cans or len(set(cans)) != len(cans):
                raise ValueError(f"order {name!r}: give at least one can, each once")
            for can in cans:
                try:
                    find_can(can)
                except CanFileError as error:
                    raise ValueError(str(error)) from None
        return orders


class CanRun(SeedResult):
    """The agent on one can: whether it finished, what learning and the whole task took."""

    finished: bool
    """Every ball disposed of, and the agent stopped by itself."""
    disposed: int
    exploratory_actions: int
    """The agent's own count: the physical actions its learning took."""
    robot_actions: int
    """Its actions that reached the robot: grasp, drop, close_lid, apply, learn."""
    total_actions: int
    """Every action it took, belief updates and prints included."""
    cycles: int
    learn_requests: int
    gave_up: bool


class OrderedCanRun(CanRun):
    """The agent on a can of an order, with Algorithm 6 alone from the same known objects."""

    algorithm6_n: int


class PerceptionRuns(SeedResult):
    orders: dict[str, dict[str, OrderedCanRun]]
    """order -> can -> the agent's run by transfer."""
    random: dict[str, CanRun]
    """can -> the agent learning randomly on it, from nothing."""


class Result(SeedResult):
    perceptions: dict[str, PerceptionRuns]


def _order(config: Config, cans: Sequence[str], seed: int, perception: str,
           folder) -> dict[str, OrderedCanRun]:
    """Each can in turn with the database of the cans before it, and Algorithm 6's N."""
    from robot.reproduce.studies.common.ch5_agent import agent_run, algorithm6_n

    runs = {}
    for can in cans:
        n = algorithm6_n(can, folder / "objects.json", folder, seed=seed, perception=perception)
        run = agent_run(can, folder, seed=seed, trials=config.trials, perception=perception,
                        max_cycles=config.max_cycles)
        runs[can] = OrderedCanRun(**run.record(), algorithm6_n=n)
    return runs


def _random(config: Config, cans: Sequence[str], seed: int, perception: str,
            folder) -> dict[str, CanRun]:
    """The agent learning randomly on each can, from nothing (its own models only)."""
    from robot.reproduce.studies.common.ch5_agent import agent_run

    runs = {}
    for can in cans:
        can_folder = folder / f"random-{can}"
        can_folder.mkdir()
        runs[can] = CanRun(**agent_run(can, can_folder, seed=seed, trials=config.trials,
                                       learning="random", perception=perception,
                                       max_cycles=config.max_cycles).record())
    return runs


def _cans(config: Config) -> tuple[str, ...]:
    """Every can of every order, once, in the order first met."""
    return tuple(dict.fromkeys(can for cans in config.orders.values() for can in cans))


def run(config: Config, seed: int, progress: Progress) -> Result:
    """Every order in every perception, and random learning on every can."""
    import tempfile
    from pathlib import Path

    steps = list(product(config.perceptions, [*config.orders, None]))
    result: dict[str, dict] = {perception: {"orders": {}} for perception in config.perceptions}
    with tempfile.TemporaryDirectory() as scratch:
        for perception, order in in_turn(steps, progress):
            folder = Path(scratch) / f"{perception}-{order or 'random'}"
            folder.mkdir()
            if order is None:
                result[perception]["random"] = _random(config, _cans(config), seed, perception,
                                                       folder)
            else:
                result[perception]["orders"][order] = _order(
                    config, config.orders[order], seed, perception, folder)
    return Result(perceptions={p: PerceptionRuns(**runs) for p, runs in result.items()})


def _where(config: Config):
    """(perception, order, can) of every run by transfer."""
    for perception, (order, cans) in product(config.perceptions, config.orders.items()):
        for can in cans:
            yield perception, order, can


def metrics(config: Config) -> list[Metric[Result]]:
    """Per perception, order and can: finished, the agent's exploratory actions (beside
    Table 5.4's N_tran in the thesis's order) and Algorithm 6's N; per perception and can,
    random learning's exploratory actions."""
    rows: list[Metric[Result]] = []
    for perception, order, can in _where(config):
        def get(seed: Result, p: str = perception, o: str = order,
                c: str = can) -> OrderedCanRun:
            return seed.perceptions[p].orders[o][c]

        key, where = f"{perception}.{order}.{can}", f"{can} ({order} order, {perception})"
        reference = THESIS_N_TRAN.get(can) if order == "thesis" else None
        rows += [
            Metric(f"{key}.finished", f"{where}: seeds that finished",
                   lambda s, get=get: float(get(s).finished), 1.0, "issue 32"),
            Metric(f"{key}.exploratory_actions", f"{where}: exploratory actions",
                   lambda s, get=get: get(s).exploratory_actions, reference,
                   "thesis Table 5.4 (N_tran)" if reference is not None else ""),
            Metric(f"{key}.algorithm6_n", f"{where}: Algorithm 6 alone, N",
                   lambda s, get=get: get(s).algorithm6_n),
        ]
    for perception, can in product(config.perceptions, _cans(config)):
        rows.append(Metric(f"{perception}.random.{can}.exploratory_actions",
                           f"{can} ({perception}): exploratory actions, random learning",
                           lambda s, p=perception, c=can:
                           s.perceptions[p].random[c].exploratory_actions))
    return rows


def claims(config: Config) -> list[Claim]:
    """Through the agent, transfer takes fewer exploratory actions than random learning on
    the same can, whatever was learned before (issue 32's done-when)."""
    return [Claim(f"Learning {can} by transfer after the cans before it ({order} order, "
                  f"{perception}) takes fewer exploratory actions than learning it randomly",
                  f"{perception}.{order}.{can}.exploratory_actions",
                  f"{perception}.random.{can}.exploratory_actions", "less")
            for perception, order, can in _where(config)]


def listings(config: Config, seeds: Sequence[Result]) -> str:
    """Per perception and order, a row per can: the agent beside Algorithm 6 and random
    learning (means over the seeds), and on how many seeds it stayed within N + 5 and within
    random learning's count."""
    count, parts = len(seeds), []
    for perception, order in product(config.perceptions, config.orders):
        rows = []
        for can in config.orders[order]:
            runs = [seed.perceptions[perception].orders[order][can] for seed in seeds]
            randoms = [seed.perceptions[perception].random[can] for seed in seeds]
            below_random = sum(r.exploratory_actions <= q.exploratory_actions
                               for r, q in zip(runs, randoms, strict=True))
            rows.append([
                can, f"{sum(r.finished for r in runs)}/{count}",
                _mean([r.exploratory_actions for r in runs]),
                _mean([r.algorithm6_n for r in runs]),
                _mean([r.exploratory_actions for r in randoms]),
                f"{sum(r.finished for r in randoms)}/{count}",
                _mean([r.robot_actions for r in runs]), _mean([r.total_actions for r in runs]),
                f"{sum(r.exploratory_actions <= r.algorithm6_n + 5 for r in runs)}/{count}",
                f"{below_random}/{count}"])
        parts += [f"## {order} order ({perception} perception)", "", markdown_table(
            ["can", "finished", "exploratory (agent)", "Algorithm 6 N", "exploratory (random)",
             "random finished", "robot actions", "all actions", "agent <= N + 5",
             "agent <= random"], rows), ""]
    return "\n".join(parts)


def _mean(values: Sequence[int]) -> str:
    return f"{sum(values) / len(values):.1f}"


def figures(config: Config, seeds: Sequence[Result]) -> list[Figure]:
    """Per perception, the first order: the agent's exploratory actions per can beside
    Algorithm 6's N and random learning's."""
    order = next(iter(config.orders))
    cans = config.orders[order]
    x = list(range(1, len(cans) + 1))
    panels = []
    for perception in config.perceptions:
        runs = [seed.perceptions[perception] for seed in seeds]
        panels.append(Panel(
            f"can ({', '.join(cans)}), in the {order} order",
            f"exploratory actions ({perception})",
            [Series("agent, transfer", x,
                    [[r.orders[order][c].exploratory_actions for c in cans] for r in runs]),
             Series("Algorithm 6 alone (N)", x,
                    [[r.orders[order][c].algorithm6_n for c in cans] for r in runs]),
             Series("agent, random learning", x,
                    [[r.random[c].exploratory_actions for c in cans] for r in runs])]))
    return [Figure("exploratory-actions", "Exploratory actions through the agent, per can",
                   panels)]


AGENT_DEVIATIONS = (*CH5_DEVIATIONS, Deviation(
    "The agent", "chapter 6's rules 6.2, 6.4 and 6.12 learn and use one part at a time; "
    "chapter 5 runs Algorithm 6 on the whole can, outside any agent.",
    "agents/garbage_disposal.goal takes transfer's percepts about any part (merged by eq. 6.3), "
    "moves its focus to a part with a reliable affordance, never asks the same question twice "
    "in a learning episode (asked/1) and gives a part up when every action on it was tried; "
    "its transfer request runs Algorithm 6 up to line 23 (the look-alike of the source's "
    "functional part) and the agent learns the other parts a pair at a time (docs/robot.md)."))
"""What the agent does beyond the thesis's rules to use Algorithm 6's answers."""

STUDY = Study(
    name="ch5-agent",
    description="Table 5.4 through the agent: each can learned by transfer from the cans before "
                "it (three orders), beside Algorithm 6 alone and random learning",
    config=Config, result=Result, run=run, metrics=metrics, claims=claims, figures=figures,
    listings=listings, default_seeds=5, deviations=AGENT_DEVIATIONS,
    quick={"orders": {"thesis": ("o1", "o3")}, "perceptions": ("truth",), "trials": 2},
    headline=("truth.thesis.o1.exploratory_actions", "truth.thesis.o3.exploratory_actions"),
    notes="""\
**Setup**: `agents/garbage_disposal.mas2g` as shipped, `learning=transfer`. Each order starts
from an empty known-object database; each can is presented with the database (and learned
models) of every can before it in the order. "Exploratory actions" is the agent's own count
(the sum of its `exploration(...)` percepts: every physical action learning took,
goal-directed ones included, as N of Table 5.4 counts them); "robot actions" are the agent's
actions that reached the robot (grasp, drop, close_lid, apply, learn), "all actions" every
action it took (its belief updates and prints included). "Algorithm 6 N" is Algorithm 6 alone
on the same can, seed and perception from a copy of the same database (what `ch5-transfer`
measures): when no known object is relevant (the first can of an order, or a can like none
before it), that is Algorithm 4 on every part and action. "Random" is the agent with
`learning=random` on the same can from nothing. The agent's first transfer request runs
Algorithm 6 on the part that looks like the source's functional part (lines 2-23); the other
parts, and every part when no known object is relevant, are explored a pair at a time as the
agent asks, as Algorithm 4 explores a pair (robot/envs/README.md), which is why the agent can
take fewer actions than Algorithm 6's N. See docs/results/ch5.md.""",
)
