"""``ch5-agent``: thesis Table 5.4 through the agent. The garbage disposal agent learns each can
by transfer (``learning=transfer``) from every can learned before it, in the thesis's order
and in others, in truth and camera perception; per can: did it finish its disposals, how many
exploratory actions did learning take, how many actions did the agent take, beside Algorithm
6 alone from the same known objects (its N) and the agent learning randomly on the same can.
"""

from __future__ import annotations

from robot.reproduce.framework import (
    Comparison,
    Figure,
    Panel,
    Progress,
    Reproduction,
    Series,
    markdown_table,
    mean_and_std,
)

CANS = ("o1", "o2", "o3", "o4", "o5", "slide", "pedal")
ORDERS = {
    "thesis": CANS,
    "o2-first": ("o2", "o1", "o3", "o5", "o4", "slide", "pedal"),
    "new-first": ("pedal", "slide", "o5", "o4", "o3", "o2", "o1"),
}
"""The orders the cans are presented in: the thesis's, one with o2 first and o5 before o4,
and one with the two new mechanisms first."""
PERCEPTIONS = ("truth", "camera")
TRIALS = 5
QUICK = {"thesis": ("o1", "o3")}
THESIS_N_TRAN = {"o2": 29, "o3": 1, "o4": 3, "o5": 11}
"""Table 5.4's N_tran: exploratory actions to open the can with transfer."""


def _order_runs(order: tuple[str, ...], seed: int, perception: str, trials: int,
                folder) -> dict[str, dict]:
    """The agent on each can of ``order`` in turn, one known-object database for all, with
    Algorithm 6's N from the same database beside each."""
    from robot.reproduce._ch5_agent import agent_run, algorithm6_n

    result = {}
    for can in order:
        n = algorithm6_n(can, folder / "objects.json", folder, seed=seed, perception=perception)
        run = agent_run(can, folder, seed=seed, trials=trials, perception=perception)
        result[can] = {**run.record(), "algorithm6_n": n}
    return result


def _random_runs(cans: tuple[str, ...], seed: int, perception: str, trials: int,
                 folder) -> dict[str, dict]:
    """The agent learning randomly on each can, from nothing (its own models only)."""
    from robot.reproduce._ch5_agent import agent_run

    result = {}
    for can in cans:
        can_folder = folder / f"random-{can}"
        can_folder.mkdir()
        result[can] = agent_run(can, can_folder, seed=seed, trials=trials, learning="random",
                                perception=perception).record()
    return result


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    """Every order in truth and camera perception, and random learning on every can (a quick
    run: o1 then o3 in truth, two trials each)."""
    import tempfile
    from pathlib import Path

    full = scale >= 0.5
    orders, perceptions = (ORDERS, PERCEPTIONS) if full else (QUICK, ("truth",))
    trials = TRIALS if full else 2
    cans = tuple(dict.fromkeys(can for order in orders.values() for can in order))
    result: dict = {"seed": seed}
    steps = len(perceptions) * (len(orders) + 1)
    done = 0
    with tempfile.TemporaryDirectory() as scratch:
        for perception in perceptions:
            entry: dict = {"orders": {}}
            for name, order in orders.items():
                folder = Path(scratch) / f"{perception}-{name}"
                folder.mkdir()
                entry["orders"][name] = _order_runs(order, seed, perception, trials, folder)
                done += 1
                progress(done / steps)
            random_folder = Path(scratch) / f"{perception}-random"
            random_folder.mkdir()
            entry["random"] = _random_runs(cans, seed, perception, trials, random_folder)
            done += 1
            progress(done / steps)
            result[perception] = entry
    return result


def _cells(seeds: list[dict], perception: str, order: str, can: str) -> dict:
    """One can's numbers over the seeds (means), with random learning's beside them."""
    runs = [seed[perception]["orders"][order][can] for seed in seeds]
    randoms = [seed[perception]["random"][can] for seed in seeds]
    return {
        "finished": sum(run["finished"] for run in runs),
        "exploratory_actions": mean_and_std([run["exploratory_actions"] for run in runs])[0],
        "algorithm6_n": mean_and_std([run["algorithm6_n"] for run in runs])[0],
        "random_exploratory_actions": mean_and_std(
            [r["exploratory_actions"] for r in randoms])[0],
        "random_finished": sum(r["finished"] for r in randoms),
        "robot_actions": mean_and_std([run["robot_actions"] for run in runs])[0],
        "total_actions": mean_and_std([run["total_actions"] for run in runs])[0],
        "within_n_plus_5": sum(run["exploratory_actions"] <= run["algorithm6_n"] + 5
                               for run in runs),
        "at_most_random": sum(run["exploratory_actions"] <= r["exploratory_actions"]
                              for run, r in zip(runs, randoms, strict=True)),
    }


def summarize(seeds: list[dict]) -> dict:
    """perception -> order -> can -> seeds finished, mean exploratory actions (the agent's,
    Algorithm 6's N, random learning's), mean robot and total actions, and on how many
    seeds the agent stayed within N + 5 and within random learning's count."""
    summary: dict = {}
    for perception in PERCEPTIONS:
        if perception not in seeds[0]:
            continue
        orders = seeds[0][perception]["orders"]
        summary[perception] = {order: {can: _cells(seeds, perception, order, can)
                                       for can in orders[order]} for order in orders}
    return summary


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    """Per perception, thesis order: share of seeds finished and exploratory actions (beside
    Table 5.4's N_tran); every other order's exploratory actions and finishes."""
    rows = []
    for perception, orders in summary.items():
        for order, cans in orders.items():
            for can in cans:
                runs = [seed[perception]["orders"][order][can] for seed in seeds]
                where = f"{can} ({order} order, {perception})"
                mean, spread = mean_and_std([float(run["finished"]) for run in runs])
                rows.append(Comparison(f"{where}: share of seeds finished", mean, spread, 1.0,
                                       "issue 32"))
                mean, spread = mean_and_std([run["exploratory_actions"] for run in runs])
                reference = THESIS_N_TRAN.get(can) if order == "thesis" else None
                rows.append(Comparison(f"{where}: exploratory actions", mean, spread,
                                       reference, "thesis Table 5.4 (N_tran)"
                                       if reference is not None else ""))
    return rows


def listings(summary: dict, seeds: list[dict]) -> str:
    """Per perception and order, a row per can: the agent beside Algorithm 6 and random
    learning."""
    parts = []
    count = len(seeds)
    for perception, orders in summary.items():
        for order, cans in orders.items():
            rows = [[can, f"{c['finished']}/{count}", _number(c["exploratory_actions"]),
                     _number(c["algorithm6_n"]), _number(c["random_exploratory_actions"]),
                     f"{c['random_finished']}/{count}", _number(c["robot_actions"]),
                     _number(c["total_actions"]), f"{c['within_n_plus_5']}/{count}",
                     f"{c['at_most_random']}/{count}"]
                    for can, c in cans.items()]
            parts += [f"## {order} order ({perception} perception)", "", markdown_table(
                ["can", "finished", "exploratory (agent)", "Algorithm 6 N",
                 "exploratory (random)", "random finished", "robot actions", "all actions",
                 "agent <= N + 5", "agent <= random"], rows), ""]
    return "\n".join(parts)


def _number(value: float | None) -> str:
    return "-" if value is None else f"{value:.1f}"


def figures(seeds: list[dict]) -> list[Figure]:
    """Per perception, the thesis order: the agent's exploratory actions per can beside
    Algorithm 6's N and random learning's."""
    panels = []
    for perception in PERCEPTIONS:
        if perception not in seeds[0]:
            continue
        cans = list(seeds[0][perception]["orders"]["thesis"])
        x = list(range(1, len(cans) + 1))
        runs = [seed[perception]["orders"]["thesis"] for seed in seeds]
        panels.append(Panel(
            f"can ({', '.join(cans)}), in the thesis's order", f"exploratory actions "
            f"({perception})",
            [Series("agent, transfer", x, [[r[c]["exploratory_actions"] for c in cans]
                                           for r in runs]),
             Series("Algorithm 6 alone (N)", x, [[r[c]["algorithm6_n"] for c in cans]
                                                 for r in runs]),
             Series("agent, random learning", x,
                    [[seed[perception]["random"][c]["exploratory_actions"] for c in cans]
                     for seed in seeds])]))
    return [Figure("exploratory-actions", "Exploratory actions through the agent, per can",
                   panels)]


NOTES = """\
**Setup**: `agents/garbage_disposal.mas2g` as shipped, `learning=transfer`, five balls per
can (`trials=5`), at most 400 cycles. Each order starts from an empty known-object database;
each can is presented with the database (and learned models) of every can before it in the
order. "Exploratory actions" is the agent's own count (the sum of its `exploration(...)`
percepts: every physical action learning took, goal-directed ones included, as N of Table
5.4 counts them); "robot actions" are the agent's actions that reached the robot (grasp,
drop, close_lid, apply, learn), "all actions" every action it took (its belief updates and
prints included). "Algorithm 6 N" is Algorithm 6 alone on the same can, seed and perception
from a copy of the same database (what `ch5-transfer` measures): when no known object is
relevant (the first can of an order, or a can like none before it), that is Algorithm 4 on
every part and action. "Random" is the agent with `learning=random` on the same can from
nothing. A transfer request with no relevant source explores the pair asked about as
Algorithm 4 does (robot/envs/README.md), which is why the first can costs the agent less
than Algorithm 6's N.
"""

REPRODUCTION = Reproduction(
    name="ch5-agent",
    description="Table 5.4 through the agent: each can learned by transfer from the cans before "
                "it (three orders), beside Algorithm 6 alone and random learning",
    run_seed=run_seed, summarize=summarize, compare=compare, figures=figures,
    listings=listings, notes=NOTES, quick_scale=0.1, default_seeds=5,
)
