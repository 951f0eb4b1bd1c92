"""The builder's part for `.test2g` files: GOAL 6+'s ``use system. timeout = N. test m
with pre{..} in{..} post{..}  agent { do main until C. }`` and GOAL 5's ``masTest { mas =
"x.mas2g". agent { test { do init. assert C. evaluate { .. } in do main. } } }``."""

from __future__ import annotations

from lark import Token, v_args

from goalagent import ast
from goalagent.parser.builder_base import BuilderBase
from goalagent.parser.errors import GoalSyntaxError


@v_args(meta=True)
class TestParts(BuilderBase):
    """Tree nodes of `.test2g` files."""

    # --- conditions --------------------------------------------------------------------
    def _condition(self, kind: str, meta, children) -> ast.TestCondition:
        text, _ = self.source.fragment(meta.start_pos, meta.end_pos)
        text = text.rstrip(".").strip()
        conditions = [c if isinstance(c, tuple) else (c,) for c in children
                      if isinstance(c, (tuple, ast.MentalLiteral, ast.NotLiteral))]
        then = conditions[1] if len(conditions) > 1 else None
        return ast.TestCondition(kind, conditions[0], self._pos(meta), text,  # type: ignore
                                 then)

    def eventually(self, meta, children):
        return self._condition("eventually", meta, children)

    def always(self, meta, children):
        return self._condition("always", meta, children)

    def never(self, meta, children):
        return self._condition("never", meta, children)

    def atend(self, meta, children):
        return self._condition("atend", meta, children)

    def atstart(self, meta, children):
        return self._condition("atstart", meta, children)

    def watch(self, meta, children):
        return self._condition("watch", meta, children)

    def leadsto(self, meta, children):
        """``C leadsto D``, GOAL 5's ``always C -> eventually D`` and ``reactTo(C, D)``."""
        return self._condition("leadsto", meta, children)

    def test_condition(self, meta, children):
        return children[0]

    def test_pre(self, meta, children):
        return ("pre", children[1])

    def test_post(self, meta, children):
        return ("post", children[1])

    def test_in(self, meta, children):
        return ("in", tuple(c for c in children if isinstance(c, ast.TestCondition)))

    def module_test(self, meta, children):
        name = children[1]
        parts = dict(c for c in children[2:] if isinstance(c, tuple) and len(c) == 2
                     and isinstance(c[0], str))
        return ast.ModuleTest(str(name), self._token_pos(name), parts.get("pre"),
                              parts.get("in", ()), parts.get("post"))

    # --- steps -------------------------------------------------------------------------
    def do_target(self, meta, children):
        """``do a``, ``do a + b`` (GOAL 5: several actions in one step): the first one's
        name, and the actions."""
        actions = tuple(children[0])
        return (getattr(actions[0], "name", ""), actions)

    def _until(self, children) -> ast.Condition | None:
        for index, child in enumerate(children):
            if isinstance(child, Token) and child.type == "UNTIL":
                return children[index + 1]
            if isinstance(child, Token) and child.type == "WHILE":  # while C: until not C
                return (ast.NotLiteral(children[index + 1], self._token_pos(child)),)
        return None

    def do_step(self, meta, children):
        target, actions = children[1]
        return ast.TestStep("do", self._pos(meta), target, actions[0], self._until(children),
                            actions=actions)

    def assert_step(self, meta, children):
        message = next((str(c)[1:-1] for c in children[2:]
                        if isinstance(c, Token) and c.type in ("DQSTRING", "QATOM")), None)
        return ast.TestStep("assert", self._pos(meta), condition=children[1], message=message)

    def evaluate_step(self, meta, children):
        conditions = tuple(c for c in children if isinstance(c, ast.TestCondition))
        target, actions = next(c for c in children if isinstance(c, tuple) and len(c) == 2
                               and not isinstance(c[0], ast.TestCondition)
                               and isinstance(c[0], str))
        return ast.TestStep("evaluate", self._pos(meta), target, actions[0],
                            self._until(children), conditions=conditions, actions=actions)

    def agent_steps(self, meta, children):
        name = children[0]
        steps = tuple(c for c in children[1:] if isinstance(c, ast.TestStep))
        return ast.AgentTest(str(name), self._token_pos(name), steps)

    # --- files -------------------------------------------------------------------------
    def file_option_number(self, meta, children):
        return ("number_option", children[0], children[1])

    def test_file(self, meta, children):
        uses = [c for c in children if isinstance(c, ast.UseClause)]
        timeout = None
        for child in children:
            if isinstance(child, tuple) and child[0] == "number_option":
                key, value = child[1], child[2]
                if str(key) != "timeout":
                    raise GoalSyntaxError.at(self._token_pos(key),
                                             f"unknown test option {str(key)!r} (timeout)")
                timeout = float(str(value))
        systems = [u for u in uses if u.case in (None, "mas")]
        if not systems:
            raise GoalSyntaxError.at(self.source.pos(0), "the test names no system: start it "
                                     "with `use name.` naming the .mas2g it runs")
        system = systems[0]
        return ("test", system.ref, system.pos, timeout,
                tuple(c for c in children if isinstance(c, ast.ModuleTest)),
                tuple(c for c in children if isinstance(c, ast.AgentTest)))

    def mastest_option(self, meta, children):
        return ("mastest_option", children[0], self.check(children[1]))

    def mastest_block(self, meta, children):
        return tuple(c for c in children if isinstance(c, ast.TestStep))

    def mastest_agent(self, meta, children):
        """``a, b { before { .. } test { .. } after { .. } }``: the blocks (any names) in
        order, for each agent named."""
        names = [c for c in children if isinstance(c, Token)]
        steps = tuple(step for block in children if isinstance(block, tuple)
                      for step in block)
        return [ast.AgentTest(str(name), self._token_pos(name), steps) for name in names]

    def mastest_file(self, meta, children):
        mas, mas_pos, timeout = None, self.source.pos(0), None
        for child in children:
            if isinstance(child, tuple) and child[0] == "mastest_option":
                key, value = str(child[1]), child[2]
                term = self.engine.parse_term(value.text)
                if key == "mas":
                    mas, mas_pos = str(term), value.pos
                elif key == "timeout":
                    timeout = float(term)  # type: ignore[arg-type]
                else:
                    raise GoalSyntaxError.at(self._token_pos(child[1]),
                                             f"unknown masTest option {key!r} (mas, timeout)")
        if mas is None:
            raise GoalSyntaxError.at(self._pos(meta), "masTest names no system: add "
                                     'mas = "file.mas2g".')
        return ("test", mas, mas_pos, timeout, (),
                tuple(test for c in children if isinstance(c, list) for test in c))
