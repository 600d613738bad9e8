"""`cpn-verify simulate MODEL`: fire random (seeded) binding elements and print the trace."""

from __future__ import annotations

import argparse
import json
import random

from cpn.cli._common import (
    ExitStatus,
    UsageError,
    add_output_option,
    add_quiet_option,
    add_set_option,
    load_model,
    prepare_outputs,
    sets_of,
    write_output,
)
from cpn.report.words import noun


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser("simulate", help="fire random enabled binding elements and print the trace",
                              description="Starting from the initial marking, repeatedly choose one enabled "
                              "binding element at random (reproducibly, with --seed) and fire it; print step, "
                              "model time, transition instance and binding.")
    p.add_argument("model", metavar="MODEL", help="model file (.cpnet, .pnml or .cpn)")
    p.add_argument("--steps", type=int, default=20, metavar="N", help="at most N steps (default 20)")
    p.add_argument("--seed", type=int, default=0, metavar="S", help="random seed (default 0)")
    add_set_option(p)
    p.add_argument("--show-marking", action="store_true", help="print the final marking")
    add_output_option(p, "--json", "the trace and the final marking as JSON")
    add_quiet_option(p)
    return p


def run(args) -> int:
    if args.steps < 0:
        raise UsageError("--steps must not be negative")
    sets = sets_of(args)
    outputs = {o.option: o for o in prepare_outputs(("--json", args.json))}
    text = not ("--json" in outputs and outputs["--json"].to_stdout)
    from cpn.values import draws

    # one generator, seeded by --seed, chooses the binding elements and draws the values of CPN Tools' random
    # distribution functions (also those of constants, drawn when the model is loaded): one seed, one run
    rng = random.Random(args.seed)
    draws.use(rng)
    model = load_model(args.model, sets)
    # a draw is made anew at each occurrence: the reference interpreter remembers no result of a marking
    # (the compiled engine reuses the effect of a binding element)
    checked = model.net.checked
    lazy = bool(getattr(checked, "random_draws", ()) or getattr(checked, "simulation_only", ()))
    engine = model.engine(simulation=True, reference=lazy)
    draw_variables = getattr(checked, "draw_variables", None) or {}
    draw_outputs = getattr(checked, "draw_outputs", None) or {}
    steps, s, ended = _walk(engine, args.steps, rng, lazy, text, (draw_variables, draw_outputs))
    n = len(steps)
    if text:
        if ended == "dead":
            print(f"dead marking after {n} {noun(n, 'step')}: no binding element is enabled")
        elif not args.quiet:
            print(f"stopped after {n} {noun(n, 'step')} (--steps {args.steps})")
    marking = {p.name: engine.format_marking(s, p.index) for p in engine.places}
    if args.show_marking and text:
        print()
        for name, m in marking.items():
            if m != "empty":
                print(f"{name}: {m}")
    if "--json" in outputs:
        result = {"model": args.model, "seed": args.seed, "max_steps": args.steps, "set": sets,
                  "steps": steps, "ended": ended, "time": engine.clock(s),
                  "final_marking": {k: v for k, v in marking.items() if v != "empty"}}
        write_output(outputs["--json"], json.dumps(result, indent=2, ensure_ascii=False) + "\n")
    return ExitStatus.OK


def _walk(engine, max_steps: int, rng, lazy: bool, text: bool, draws: tuple) -> tuple[list[dict], object, str]:
    """(the steps, the last state, why the run ended: "steps" or "dead") of one run from the initial
    marking, each step printed as it occurs where `text`."""
    from cpn.errors import EvaluationError

    draw_variables, draw_outputs = draws
    s = engine.initial_state()
    steps: list[dict] = []
    width = max(len(str(max_steps)), 4)
    if text:
        print(f"{'step':>{width}}  {'time':>6}  binding element")
    ended = "steps"
    try:
        while len(steps) < max_steps:
            # the reference interpreter fires only the binding element chosen: a call that simulate cannot
            # run (a socket, a file) stops the run at the occurrence that makes it
            succ = engine.successors(s, lazy=True) if lazy else engine.successors(s)
            if not succ:
                ended = "dead"
                break
            be, s = _choose(engine, succ, rng, draw_variables, draw_outputs)
            if lazy:
                s = s()
            steps.append({"step": len(steps) + 1, "time": engine.clock(s),
                          "binding_element": engine.format_binding_element(be)})
            if text:
                print(f"{steps[-1]['step']:>{width}}  {_time(steps[-1]['time']):>6}  {steps[-1]['binding_element']}")
    except EvaluationError as err:
        err.trace = [st["binding_element"] for st in steps]
        raise
    return steps, s, ended


def _choose(engine, succ: list, rng: random.Random, draw_variables: dict, draw_outputs: dict):
    """One of the enabled binding elements `succ` ((binding element, successor) pairs), at random.

    Without draws, every binding element is equally likely. The free variables that explore makes of a draw
    (`bernoulli(p)`, `discrete(a, b)`, `CS.ran()`, `@+[a,b]`: `draw_variables`, name -> the weight of each
    value or None for equal weights) are draws here, as in CPN Tools' simulator: a binding element without
    its draws (transition and the other variables) is chosen first, every one equally likely, then the values
    of its draws, each with its probability (`bernoulli(0.9)` gives 1 nine times in ten), among those that
    are enabled. The variables that a guard conjunct binds to draws (`draw_outputs`, by transition) follow
    their draws.
    """
    if not draw_variables:
        return succ[rng.randrange(len(succ))]
    groups: dict = {}
    for item in succ:
        be = engine.binding_element(item[0])
        outputs = draw_outputs.get(engine.transitions[be.transition].span, ())
        weight, rest = 1.0, []
        for name, value in be.binding.items():
            if name in outputs:
                continue
            if name in draw_variables:
                weights = draw_variables[name]
                if weights is not None:
                    weight *= weights.get(value, 0.0)
            else:
                rest.append((name, value))
        groups.setdefault((be.transition, tuple(rest)), []).append((weight, item))
    members = list(groups.values())[rng.randrange(len(groups))]
    if len(members) == 1:
        return members[0][1]
    total = sum(w for w, _ in members)
    if total <= 0.0:  # only values of probability 0 are enabled: none is likelier than another
        return members[rng.randrange(len(members))][1]
    x = rng.random() * total
    for w, item in members:
        x -= w
        if x < 0.0:
            return item
    return members[-1][1]


def _time(t) -> str:
    """Model time for the trace: an integer as it is, a real time (`@++`) to three decimals."""
    return f"{t:.3f}" if isinstance(t, float) else str(t)
