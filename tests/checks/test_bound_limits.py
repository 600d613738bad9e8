"""`bound`'s one-sided limits (`at_most`, `at_least`, `at_most_multiset`, `at_least_multiset`) beside the
exact ones (`upper_equals`, ...; `upper`, ... are their older spellings): a bound that improves keeps an
`at_most` property holding, where the exact form is violated."""

import pytest

from cpn.errors import ModelError
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario
from tests.checks._nets import COUNTER, scenario

# COUNTER: P holds one token, 0 in the initial marking, then 1, 2, 3 (dead); state i has value i


def _verdicts(tmp_path, body, explore=""):
    s = load_scenario(scenario(tmp_path, COUNTER, explore + body))
    r = run_scenario(s, s.runs[0])
    return {p.spec.name: p.verdict for p in r.results}


def _prop(name, **fields):
    lines = ["[[property]]", f'name = "{name}"', 'kind = "bound"']
    lines += [f"{k} = {v!r}" if isinstance(v, int) else f'{k} = "{v}"' for k, v in fields.items()]
    return "\n".join(lines) + "\n"


VALUE = "ms_to_col (C'P 1)"


def test_at_most_and_at_least_hold_when_the_bound_is_better(tmp_path):
    v = _verdicts(tmp_path, "".join([
        _prop("at most 5", expr=VALUE, at_most=5),
        _prop("exactly 5", expr=VALUE, upper_equals=5),
        _prop("old spelling 5", expr=VALUE, upper=5),
        _prop("at most 3", expr=VALUE, at_most=3),
        _prop("exactly 3", expr=VALUE, upper_equals=3),
        _prop("at least -1", expr=VALUE, at_least=-1),
        _prop("lower exactly -1", expr=VALUE, lower_equals=-1),
        _prop("at least 0, at most N", expr=VALUE, at_least=0, at_most="size (N.all()) - 1"),
    ]))
    got = {name: verdict.status.value for name, verdict in v.items()}
    assert got == {"at most 5": "holds", "exactly 5": "violated", "old spelling 5": "violated",
                   "at most 3": "holds", "exactly 3": "holds", "at least -1": "holds",
                   "lower exactly -1": "violated", "at least 0, at most N": "holds"}
    assert v["at most 5"].message == "ms_to_col (C'P 1): at most 5 (best upper bound 3)"
    assert v["exactly 5"].message == "ms_to_col (C'P 1): best upper bound is 3, expected 5"


def test_a_broken_one_sided_limit_gives_the_shortest_trace_past_it(tmp_path):
    v = _verdicts(tmp_path, _prop("at most 1", place="C'P 1", at_most=0)
                  + _prop("value at most 1", expr=VALUE, at_most=1)
                  + _prop("at least 1", expr=VALUE, at_least=1))
    assert v["at most 1"].status.value == "violated"  # the place always holds one token
    assert v["value at most 1"].status.value == "violated"
    assert v["value at most 1"].message == "ms_to_col (C'P 1): reaches 3, more than at_most = 1"
    assert len(v["value at most 1"].evidence.path) - 1 == 2  # to the first marking beyond 1, not to the largest
    assert v["at least 1"].message == "ms_to_col (C'P 1): falls to 0, less than at_least = 1"
    assert v["at least 1"].evidence.path == (0,)


def test_multiset_limits(tmp_path):
    v = _verdicts(tmp_path, "".join([
        _prop("within all", place="C'P 1", at_most_multiset="N.all()"),
        _prop("within all and 0 again", place="C'P 1", at_most_multiset="N.all() ++ 1`0"),
        _prop("exactly all and 0 again", place="C'P 1", upper_multiset_equals="N.all() ++ 1`0"),
        _prop("exactly all", place="C'P 1", upper_multiset_equals="N.all()"),
        _prop("old exactly all", place="C'P 1", upper_multiset="N.all()"),
        _prop("within 0 and 1", place="C'P 1", at_most_multiset="1`0 ++ 1`1"),
        _prop("at least nothing", place="C'P 1", at_least_multiset="empty"),
        _prop("at least a 0", place="C'P 1", at_least_multiset="1`0"),
    ]))
    got = {name: verdict.status.value for name, verdict in v.items()}
    assert got == {"within all": "holds", "within all and 0 again": "holds", "exactly all and 0 again": "violated",
                   "exactly all": "holds", "old exactly all": "holds", "within 0 and 1": "violated",
                   "at least nothing": "holds", "at least a 0": "violated"}
    assert len(v["within 0 and 1"].evidence.path) - 1 == 2  # P = 1`2
    assert len(v["at least a 0"].evidence.path) - 1 == 1


def test_on_a_partial_state_space_only_a_broken_limit_is_decided(tmp_path):
    v = _verdicts(tmp_path, _prop("at most 5", expr=VALUE, at_most=5) + _prop("at most 0", expr=VALUE, at_most=0)
                  + _prop("at least 0", expr=VALUE, at_least=0),
                  explore="[explore]\nmax_states = 2\n")
    assert v["at most 5"].status.value == "unknown" and "upper bound 1 so far (at_most = 5)" in v["at most 5"].message
    assert v["at most 0"].status.value == "violated"
    assert v["at least 0"].status.value == "unknown"


def test_the_sweep_line_decides_one_sided_limits(tmp_path):
    v = _verdicts(tmp_path, _prop("at most 5", expr=VALUE, at_most=5) + _prop("at most 2", expr=VALUE, at_most=2)
                  + _prop("ms within", place="C'P 1", at_most_multiset="N.all()")
                  + _prop("ms at least", place="C'P 1", at_least_multiset="1`0"),
                  explore=f'[explore]\nsweep_line = true\nprogress = "{VALUE}"\n')
    got = {name: verdict.status.value for name, verdict in v.items()}
    assert got == {"at most 5": "holds", "at most 2": "violated", "ms within": "holds", "ms at least": "violated"}


@pytest.mark.parametrize("fields, message, line", [
    ({"upper": 1, "upper_equals": 1}, "'upper' and 'upper_equals' are two spellings of the same bound", 6),
    ({}, "a 'bound' property needs a limit: one of upper_equals, lower_equals, at_most, at_least", 4),
    ({"at_most": "x"}, None, None),
    ({"at_most": True}, "'at_most' of a 'bound' property must be an integer or a CPN ML integer expression", 6),
])
def test_the_fields_are_checked_where_they_are_written(tmp_path, fields, message, line):
    path = scenario(tmp_path, COUNTER, _prop("b", place="C'P 1", **fields).replace("= True", "= true"))
    if message is None:  # a text is checked with the model: an unknown name
        s = load_scenario(path)
        with pytest.raises(ModelError) as info:
            run_scenario(s, s.runs[0])
        assert info.value.diagnostics[0].span.line == 6
        return
    with pytest.raises(ModelError) as info:
        load_scenario(path)
    d = next(d for d in info.value.diagnostics if message in d.message)
    assert d.code == "E0702" and d.span.line == line


def test_multiset_limits_are_not_decided_on_a_symmetry_quotient(tmp_path):
    net = ("net S;\ncolset ID = with a | b | c;\nvar i : ID;\nplace Idle : ID = ID.all();\nplace Busy : ID;\n"
           "trans Start;\narc Idle -> Start : i;\narc Start -> Busy : i;\ntrans Stop;\narc Busy -> Stop : i;\n"
           "arc Stop -> Idle : i;\n")
    body = ('[explore]\nsymmetry = ["ID"]\n' + _prop("ms", place="S'Busy 1", at_most_multiset="ID.all()")
            + _prop("int", place="S'Busy 1", at_most=3))
    s = load_scenario(scenario(tmp_path, net, body))
    r = run_scenario(s, s.runs[0])
    v = {p.spec.name: p.verdict for p in r.results}
    assert r.exploration.n_states == 4  # 0, 1, 2 or 3 busy: the 8 markings up to the order of a, b, c
    assert v["ms"].status.value == "unknown" and "not preserved by symmetry" in v["ms"].message
    assert v["int"].status.value == "holds"
