"""What a mutation run costs and how it is budgeted: a mutant is parsed once and type-checked once for all
the runs of its gate that set the same values, the time per mutant is reported (and left out with
--no-timings), a seeded sample keeps the numbers of the full list, and --workers on the command line
gives the report of one worker."""

import json
import pathlib

import pytest

import cpn.gate.mutation as mutation
import cpn.lang.parser
from cpn.cli.main import main
from cpn.gate.mutation import mutate
from cpn.gate.scenario import load_scenario
from cpn.report.mutation import mutation_document, render_markdown, render_text

HERE = pathlib.Path(__file__).parent
WEAK = str(HERE / "weak.toml")
STRONG = str(HERE / "strong.toml")


def test_a_mutant_is_parsed_and_checked_once_for_every_run_of_its_gate(monkeypatch):
    source = (HERE / "counter.cpnet").read_text(encoding="utf-8")
    parsed, checked = [], []
    real_parse, real_load = cpn.lang.parser.parse, mutation._load_parsed

    def parse(text, *args, **kw):
        parsed.append(text)
        return real_parse(text, *args, **kw)

    def load(tree, text, *args, **kw):
        checked.append(text)
        return real_load(tree, text, *args, **kw)

    monkeypatch.setattr(cpn.lang.parser, "parse", parse)
    monkeypatch.setattr(mutation, "_load_parsed", load)
    # two scenarios of the same model, one gate of two runs; every mutant goes through both (--all-runs)
    model = mutate([load_scenario(WEAK), load_scenario(STRONG)], all_runs=True, max_mutants=6, seed=5).models[0]
    assert model.runs == 2 and len(model.outcomes) == 6
    texts = [o.mutant.apply(source) for o in model.outcomes]
    assert all(t != source for t in texts)
    mutant_parses = [t for t in parsed if t != source]
    assert sorted(mutant_parses) == sorted(texts)  # one parse per mutant, not one per run
    loadable = [t for o, t in zip(model.outcomes, texts) if o.outcome != mutation.NOT_LOADABLE]
    assert loadable and all(checked.count(t) == 1 for t in loadable)


@pytest.fixture(scope="module")
def strong_report():
    return mutate([load_scenario(STRONG)], max_mutants=8, seed=2)


def test_the_time_per_mutant_is_reported(strong_report):
    doc = mutation_document(strong_report, timings=True)
    m = doc["models"][0]
    per = [x["seconds"] for x in m["mutants"]]
    assert len(per) == 8 and all(s > 0 for s in per)
    assert m["seconds_per_mutant"] == pytest.approx(sum(per) / len(per), abs=0.002)
    assert m["seconds"] >= sum(per) - 0.01  # the model's time includes its mutants' and the original's
    assert f"{m['seconds_per_mutant']:.2f} s per mutant" in render_text(doc)
    assert "per mutant" in render_markdown(doc)
    plain = mutation_document(strong_report, timings=False)
    assert "seconds_per_mutant" not in plain["models"][0] and "per mutant" not in render_text(plain)
    assert all("seconds" not in x for x in plain["models"][0]["mutants"])


def test_a_sample_keeps_the_numbers_and_changes_of_the_full_list(strong_report):
    full = {o.mutant.number: (o.mutant.description, o.outcome) for o in mutate([load_scenario(STRONG)]).models[0].outcomes}
    sample = strong_report.models[0]
    assert sample.generated == len(full) and sample.selected == 8
    assert {o.mutant.number: (o.mutant.description, o.outcome) for o in sample.outcomes}.items() <= full.items()
    other = {o.mutant.number for o in mutate([load_scenario(STRONG)], max_mutants=8, seed=3).models[0].outcomes}
    assert other != {o.mutant.number for o in sample.outcomes}  # another seed, another sample


def test_workers_on_the_command_line(tmp_path, capsys):
    def report(workers):
        out = tmp_path / f"w{workers}.json"
        code = main(["mutate", STRONG, "--no-timings", "-q", "--max-mutants", "6", "--seed", "4",
                     "--workers", str(workers), "--json", str(out)])
        assert code == 0
        return json.loads(out.read_text(encoding="utf-8"))

    one, two = report(1), report(2)
    assert one == two  # without timings, the same document (the number of workers is kept with the times)
    assert one["models"][0]["selected"] == 6 and "workers" not in one
    assert main(["mutate", STRONG, "--workers", "0"]) == 64
    assert "--workers must be at least 1" in capsys.readouterr().err
